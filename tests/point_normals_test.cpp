// Normals estimated from the points as MeshLab's "Compute normals for point sets" gives them
// (growth/point_normals.h): PCA over the k nearest, signs propagated between neighbours.
#include <growth/cloud_generator.h>
#include <growth/point_normals.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

TEST(PointNormals, EstimateIsLikeMeshLabs) {
  // Unit normals, perpendicular to the surface up to the sampling, and one orientation on most of
  // a smooth closed surface (the propagation flips a sign only across folds).
  growth::CloudSpec s;
  s.shape = growth::Shape::Torus;
  s.count = 20000;
  s.seed = 3;
  const growth::Cloud exact = growth::generateCloud(s);
  const std::vector<growth::Vec3d> n = growth::estimateNormals(exact.points, 10);
  ASSERT_EQ(n.size(), exact.points.size());
  size_t agree = 0, perpendicular = 0;
  for (size_t i = 0; i < n.size(); ++i) {
    EXPECT_NEAR(n[i].Norm(), 1.0, 1e-9);
    const double c = n[i] * exact.normals[i];
    agree += c > 0 ? 1 : 0;
    perpendicular += std::abs(c) > 0.95 ? 1 : 0;
  }
  EXPECT_GT(double(perpendicular), 0.99 * double(n.size()));
  // All one way, inwards or outwards (the sign of the first point's fit decides).
  EXPECT_TRUE(agree == n.size() || agree == 0) << agree << " of " << n.size();
  // The same normals on every run.
  EXPECT_EQ(growth::estimateNormals(exact.points, 10), n);
}
