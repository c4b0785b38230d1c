// Determinism of both engines: the same cloud and parameters give the same mesh,
// bit for bit (vertex positions and normals, face vertex indices, normals and quality), on a rerun,
// on 1 or 2 threads, and when two runs go on at once in one process (no shared mutable state).
// Clean, noisy, outlier-ridden, non-uniform, clustered and open clouds.
//
// Threads: the sphere packer has Params::threads (its per-box and per-point phases, growth/
// parallel.h; the plugin uses 0 = automatic, the hardware's). Robust G2S runs on one thread (its
// Params have no thread count), so for it the rerun and concurrent-run checks are the ones that
// apply. The clouds have 24,000 points so that every parallel phase of the packer really splits
// its work on 2 threads (the box grid hands out parts of at least 8192 points) and the packer
// takes its spatial order (from 20,000 points).
#include "filter_g2s_layer.h"
#include "filter_spherepack_layer.h"

#include <growth/meshlab/layer.h>
#include <growth/cloud_generator.h>
#include <growth/input_cloud.h>

#include <common/ml_mesh_type.h>
#include <vcg/complex/allocate.h>

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace sp = growth::spherepack;
namespace g2s = growth::g2s;
using growth::CloudSpec;
using growth::Shape;

namespace {

struct Case {
  std::string name;
  CloudSpec spec;
  bool forG2S = true; // false: the sphere packer only (tests/g2s_outliers_test.cpp covers G2S on far points)
};

std::vector<Case> clouds() {
  std::vector<Case> c;
  auto add = [&](const std::string& name, Shape shape, std::uint64_t seed) -> CloudSpec& {
    CloudSpec s;
    s.shape = shape;
    s.count = 24000;
    s.seed = seed;
    c.push_back({name, s});
    return c.back().spec;
  };
  add("clean sphere", Shape::Sphere, 11);
  add("torus, uniform noise", Shape::Torus, 12).noiseBound = 0.01;
  {
    CloudSpec& s = add("sphere, Gaussian noise and 5 % outliers", Shape::Sphere, 13);
    s.gaussianSigma = 0.004; // about a third of the spacing
    s.outlierFraction = 0.05;
  }
  {
    CloudSpec& s = add("open patch, non-uniform, noisy", Shape::Patch, 14);
    s.nonUniform = true;
    s.noiseBound = 0.005;
  }
  add("genus 2, a dense cluster", Shape::Genus2, 15).clusterFraction = 0.01;
  add("genus 2, far points", Shape::Genus2, 16).farPoints = 3;
  c.back().forG2S = false;
  return c;
}

void cloudOf(const CloudSpec& spec, CMeshO& m) { growth::toMesh(growth::generateCloud(spec), m); }

template <class P>
bool sameBits(const P& a, const P& b) {
  return std::memcmp(&a, &b, sizeof(P)) == 0;
}

// The same mesh, bit for bit.
void expectSameMesh(const CMeshO& a, const CMeshO& b) {
  ASSERT_EQ(a.vert.size(), b.vert.size());
  ASSERT_EQ(a.face.size(), b.face.size());
  ASSERT_GT(a.face.size(), 0u);
  for (size_t i = 0; i < a.vert.size(); ++i) {
    ASSERT_TRUE(sameBits(a.vert[i].cP(), b.vert[i].cP())) << "vertex " << i;
    ASSERT_TRUE(sameBits(a.vert[i].cN(), b.vert[i].cN())) << "vertex normal " << i;
  }
  ASSERT_EQ(a.face.IsQualityEnabled(), b.face.IsQualityEnabled());
  for (size_t f = 0; f < a.face.size(); ++f) {
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(vcg::tri::Index(a, a.face[f].cV(k)), vcg::tri::Index(b, b.face[f].cV(k))) << "face " << f;
    ASSERT_TRUE(sameBits(a.face[f].cN(), b.face[f].cN())) << "face normal " << f;
    if (a.face.IsQualityEnabled()) {
      ASSERT_TRUE(sameBits(a.face[f].cQ(), b.face[f].cQ())) << "face quality " << f;
    }
  }
}

void packWith(const CMeshO& cloud, int threads, CMeshO& out) {
  sp::Params p;
  p.threads = threads;
  sp::Stat st;
  sp::build(cloud, out, p, st);
}

void growG2S(const CMeshO& cloud, CMeshO& out) {
  g2s::Stat st;
  g2s::build(cloud, out, g2s::Params(), st);
}

} // namespace

TEST(Determinism, SpherePackerSameMeshOnRerunsAndOnOneOrTwoThreads) {
  for (const Case& c : clouds()) {
    SCOPED_TRACE(c.name);
    CMeshO cloud;
    cloudOf(c.spec, cloud);
    CMeshO one, two, twoAgain;
    packWith(cloud, 1, one);
    packWith(cloud, 2, two);
    packWith(cloud, 2, twoAgain);
    ASSERT_NO_FATAL_FAILURE(expectSameMesh(two, twoAgain)) << "rerun on 2 threads";
    ASSERT_NO_FATAL_FAILURE(expectSameMesh(one, two)) << "1 thread against 2";
  }
}

TEST(Determinism, RobustG2SSameMeshOnReruns) {
  for (const Case& c : clouds()) {
    if (!c.forG2S) continue;
    SCOPED_TRACE(c.name);
    CMeshO cloud;
    cloudOf(c.spec, cloud);
    CMeshO a, b;
    growG2S(cloud, a);
    growG2S(cloud, b);
    ASSERT_NO_FATAL_FAILURE(expectSameMesh(a, b));
  }
}

// Two runs at once in one process (as two MeshLab documents could) give what one run alone gives:
// nothing either engine keeps between or across runs changes a result.
TEST(Determinism, TwoRunsAtOnceGiveTheMeshOfOneRun) {
  const std::vector<Case> all = clouds();
  CMeshO noisy, clustered;
  cloudOf(all[2].spec, noisy);
  cloudOf(all[4].spec, clustered);
  CMeshO packAlone, g2sAlone;
  packWith(noisy, 2, packAlone);
  growG2S(clustered, g2sAlone);
  CMeshO pack[2], grown[2];
  {
    std::thread t0([&] { packWith(noisy, 2, pack[0]); }), t1([&] { growG2S(clustered, grown[0]); }),
        t2([&] { packWith(noisy, 1, pack[1]); }), t3([&] { growG2S(clustered, grown[1]); });
    t0.join();
    t1.join();
    t2.join();
    t3.join();
  }
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE(k);
    ASSERT_NO_FATAL_FAILURE(expectSameMesh(packAlone, pack[k]));
    ASSERT_NO_FATAL_FAILURE(expectSameMesh(g2sAlone, grown[k]));
  }
}

// The mesh depends on the points, not on where the layer's vertex vector happens to sit in memory
// or on what was allocated before: a copy of the cloud built after other allocations, and a cloud
// with deleted vertices in front, give the same mesh.
TEST(Determinism, SameMeshFromACopyOfTheCloud) {
  const std::vector<Case> all = clouds();
  CMeshO cloud;
  cloudOf(all[1].spec, cloud);
  std::vector<std::vector<char>> ballast;
  for (int i = 0; i < 64; ++i) ballast.emplace_back(size_t(4096) * size_t(i + 1), char(i));
  CMeshO copy;
  vcg::tri::Allocator<CMeshO>::AddVertices(copy, 5);
  for (const auto& v : cloud.vert) {
    auto w = vcg::tri::Allocator<CMeshO>::AddVertices(copy, 1);
    w->P() = v.cP();
    w->N() = v.cN();
  }
  for (int i = 0; i < 5; ++i) vcg::tri::Allocator<CMeshO>::DeleteVertex(copy, copy.vert[size_t(i)]);
  CMeshO packA, packB, g2sA, g2sB;
  packWith(cloud, 2, packA);
  packWith(copy, 2, packB);
  growG2S(cloud, g2sA);
  growG2S(copy, g2sB);
  ASSERT_NO_FATAL_FAILURE(expectSameMesh(packA, packB));
  ASSERT_NO_FATAL_FAILURE(expectSameMesh(g2sA, g2sB));
}
