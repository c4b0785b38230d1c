#include <growth/meshlab/layer.h>
#include <growth/cloud_scale.h>
#include <growth/mesh_normals.h>

#include "filter_g2s_layer.h"

#include <growth/cloud_generator.h>
#include <growth/input_cloud.h>

#include <vcg/complex/algorithms/update/normal.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace {

using Mesh = std::unique_ptr<CMeshO>; // CMeshO can be neither copied nor moved

// The angle between two vectors (-1 when one is zero), as vcglib's Angle.
double angleBetween(const growth::Vec3d& a, const growth::Vec3d& b) {
  const double w = a.Norm() * b.Norm();
  if (w == 0) return -1;
  return std::acos(std::max(-1.0, std::min(1.0, (a * b) / w)));
}

// A Robust G2S mesh of a generated cloud (noisy, so with uneven and some near-degenerate faces).
Mesh g2sMesh(growth::Shape shape, size_t n, double sigmaSpacings) {
  growth::CloudSpec spec;
  spec.shape = shape;
  spec.count = n;
  spec.gaussianSigma = sigmaSpacings * growth::meanSpacing(growth::generateCloud(spec).points);
  CMeshO cloud;
  growth::toMesh(growth::generateCloud(spec), cloud);
  Mesh out(new CMeshO);
  growth::g2s::Stat st;
  growth::g2s::build(cloud, *out, growth::g2s::Params(), st);
  return out;
}

// The normals vcglib gives (PerFaceNormalized, PerVertexAngleWeighted, NormalizePerVertex).
void vcglibNormals(CMeshO& m, std::vector<vcg::Point3f>& face, std::vector<vcg::Point3f>& vert) {
  vcg::tri::UpdateNormal<CMeshO>::PerFaceNormalized(m);
  vcg::tri::UpdateNormal<CMeshO>::PerVertexAngleWeighted(m);
  vcg::tri::UpdateNormal<CMeshO>::NormalizePerVertex(m);
  face.clear();
  vert.clear();
  for (const CFaceO& f : m.face) face.push_back(f.cN());
  for (const CVertexO& v : m.vert) vert.push_back(v.cN());
}

} // namespace

// The same normals as vcglib's, to float accuracy: its angles come from normalised float edges and
// acos, ours from double and a polynomial atan within 1e-5 rad, so unit vectors agree to ~1e-6.
TEST(MeshNormals, MatchVcglibAngleWeightedNormals) {
  for (const Mesh& m : {g2sMesh(growth::Shape::Torus, 20000, 0.0), g2sMesh(growth::Shape::Sphere, 20000, 0.25)}) {
    ASSERT_GT(m->fn, 30000);
    std::vector<vcg::Point3f> face, vert;
    vcglibNormals(*m, face, vert);
    growth::updateNormals(*m);
    double worstFace = 0, worstVertex = 0;
    for (size_t f = 0; f < m->face.size(); ++f) worstFace = std::max(worstFace, double((m->face[f].cN() - face[f]).Norm()));
    // How well a vertex normal is conditioned: |sum of the angle-weighted face normals| / sum of
    // the angles, 1 on a flat fan. Where the faces fold around the vertex (a noisy point inside
    // the triangle of its three neighbours) the sum nearly cancels and a relative error of the
    // weights grows by 1 / that ratio, so the tolerance does too.
    std::vector<growth::Vec3d> sum(m->vert.size(), growth::Vec3d(0, 0, 0));
    std::vector<double> angles(m->vert.size(), 0.0);
    for (const CFaceO& f : m->face) {
      const growth::Vec3d p[3] = {growth::Vec3d::Construct(f.cP(0)), growth::Vec3d::Construct(f.cP(1)),
                                 growth::Vec3d::Construct(f.cP(2))};
      const growth::Vec3d n = ((p[1] - p[0]) ^ (p[2] - p[0])).Normalize();
      for (int k = 0; k < 3; ++k) {
        const double angle = angleBetween(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
        const size_t v = size_t(vcg::tri::Index(*m, f.cV(k)));
        sum[v] += n * angle;
        angles[v] += angle;
      }
    }
    size_t wellConditioned = 0;
    for (size_t v = 0; v < m->vert.size(); ++v) {
      EXPECT_NEAR(m->vert[v].cN().Norm(), 1.0, 1e-6) << v;
      const double condition = angles[v] > 0 ? sum[v].Norm() / angles[v] : 1.0;
      wellConditioned += condition > 0.5;
      worstVertex = std::max(worstVertex, double((m->vert[v].cN() - vert[v]).Norm()) * std::min(1.0, condition));
    }
    EXPECT_GT(double(wellConditioned), 0.99 * double(m->vert.size()));
    EXPECT_LT(worstFace, 1e-5);
    EXPECT_LT(worstVertex, 1e-4);
  }
}

// Each vertex normal is the angle-weighted mean of its faces' normals: at the apex of a square
// pyramid the four faces have equal angles, so the normal is the axis; at a base corner its two
// faces have equal angles, so the normal is the normalised sum of their normals.
TEST(MeshNormals, AngleWeightsAtAPyramid) {
  CMeshO m;
  vcg::tri::Allocator<CMeshO>::AddVertices(m, 5);
  m.vert[0].P() = vcg::Point3f(0, 0, 1); // apex
  m.vert[1].P() = vcg::Point3f(1, 1, 0);
  m.vert[2].P() = vcg::Point3f(-1, 1, 0);
  m.vert[3].P() = vcg::Point3f(-1, -1, 0);
  m.vert[4].P() = vcg::Point3f(1, -1, 0);
  vcg::tri::Allocator<CMeshO>::AddFaces(m, 4);
  for (int k = 0; k < 4; ++k) {
    m.face[k].V(0) = &m.vert[0];
    m.face[k].V(1) = &m.vert[1 + k];
    m.face[k].V(2) = &m.vert[1 + (k + 1) % 4];
  }
  growth::updateNormals(m);
  const vcg::Point3f apex = m.vert[0].cN();
  EXPECT_NEAR(apex[0], 0.f, 1e-6f);
  EXPECT_NEAR(apex[1], 0.f, 1e-6f);
  EXPECT_NEAR(apex[2], 1.f, 1e-6f);
  // Base corner 1 = (1, 1, 0) lies on faces 0 and 3, with the same angle in both: its normal is
  // the normalised sum of their two normals.
  const vcg::Point3f expected = (m.face[0].cN() + m.face[3].cN()).Normalize();
  EXPECT_LT((m.vert[1].cN() - expected).Norm(), 1e-6f);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(m.face[k].cN().Norm(), 1.f, 1e-6f);
}

// A degenerate face adds nothing and gets a zero normal; a vertex on no face keeps a zero normal;
// deleted faces are skipped.
TEST(MeshNormals, DegenerateDeletedAndIsolated) {
  CMeshO m;
  vcg::tri::Allocator<CMeshO>::AddVertices(m, 6);
  m.vert[0].P() = vcg::Point3f(0, 0, 0);
  m.vert[1].P() = vcg::Point3f(1, 0, 0);
  m.vert[2].P() = vcg::Point3f(0, 1, 0);
  m.vert[3].P() = vcg::Point3f(2, 0, 0); // collinear with 0 and 1
  m.vert[4].P() = vcg::Point3f(5, 5, 5); // on no face
  m.vert[5].P() = vcg::Point3f(0, 0, 1);
  vcg::tri::Allocator<CMeshO>::AddFaces(m, 3);
  auto set = [&](int f, int a, int b, int c) {
    m.face[f].V(0) = &m.vert[a];
    m.face[f].V(1) = &m.vert[b];
    m.face[f].V(2) = &m.vert[c];
  };
  set(0, 0, 1, 2);
  set(1, 0, 1, 3); // degenerate
  set(2, 0, 2, 5);
  vcg::tri::Allocator<CMeshO>::DeleteFace(m, m.face[2]);
  growth::updateNormals(m);
  EXPECT_EQ(m.face[1].cN(), vcg::Point3f(0, 0, 0));
  EXPECT_EQ(m.vert[4].cN(), vcg::Point3f(0, 0, 0));
  EXPECT_EQ(m.vert[5].cN(), vcg::Point3f(0, 0, 0)); // only on the deleted face
  EXPECT_LT((m.vert[3].cN() - vcg::Point3f(0, 0, 0)).Norm(), 1e-12f); // only on the degenerate face
  for (int v = 0; v < 3; ++v) EXPECT_LT((m.vert[v].cN() - vcg::Point3f(0, 0, 1)).Norm(), 1e-6f) << v;
}
