// growth::Error and growth::Cancelled: the two ways the engine reports to its host. The MeshLab
// glue tells them apart (a user-facing message versus a silent cancel), so they must stay
// distinct types, and the message of an Error must reach the host unchanged.
#include <growth/meshlab/layer.h>
#include <growth/error.h>
#include <growth/input_cloud.h>

#include <common/ml_mesh_type.h>

#include <gtest/gtest.h>

#include <string>
#include <type_traits>

namespace {

TEST(Error, CarriesTheUserMessageUnchanged) {
  const std::string message = "The layer has no normals: run \"Compute normals for point sets\".";
  try {
    throw growth::Error(message);
  } catch (const std::exception& e) {
    EXPECT_EQ(message, e.what());
  }
}

TEST(Error, ErrorAndCancelledAreDistinct) {
  static_assert(!std::is_base_of<growth::Error, growth::Cancelled>::value, "a cancel is not an error");
  static_assert(!std::is_base_of<growth::Cancelled, growth::Error>::value, "an error is not a cancel");
  bool caughtAsError = false, caughtAsCancelled = false;
  try {
    throw growth::Cancelled();
  } catch (const growth::Error&) {
    caughtAsError = true;
  } catch (const growth::Cancelled& c) {
    caughtAsCancelled = true;
    EXPECT_STRNE("", c.what());
  }
  EXPECT_FALSE(caughtAsError);
  EXPECT_TRUE(caughtAsCancelled);
}

// The engine's own checks throw Error (not some other exception) with a non-empty message.
TEST(Error, ReadCloudThrowsErrorOnAnEmptyLayer) {
  CMeshO empty;
  try {
    growth::readCloud(empty, growth::CloudCheck());
    FAIL() << "an empty layer must be refused";
  } catch (const growth::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no vertices"), std::string::npos) << e.what();
  }
}

} // namespace
