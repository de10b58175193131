#include "sims/scene/mesh.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sims::scene {
namespace {

using Eigen::Vector3d;

TEST(MeshTest, BoxAreaVolumeAndBounds) {
  const TriangleMesh box = TriangleMesh::Box({0, 0, 0}, {1, 2, 3});
  EXPECT_EQ(box.triangles.size(), 12u);
  EXPECT_NEAR(box.Area(), 2 * (2 + 3 + 6), 1e-12);
  EXPECT_NEAR(box.SignedVolume(), 6.0, 1e-12);  // outward winding gives a positive volume
  EXPECT_TRUE(box.IsClosed());
  EXPECT_TRUE(box.Bounds().max.isApprox(Vector3d(1, 2, 3)));
}

TEST(MeshTest, CylinderIsClosedWithTheRightVolume) {
  const TriangleMesh c = TriangleMesh::Cylinder({0, 0, 0}, 0.5, 2.0, 64);
  EXPECT_TRUE(c.IsClosed());
  // A 64-gon prism: area of the polygon times the height.
  const double polygon = 0.5 * 64 * 0.25 * std::sin(2 * M_PI / 64);
  EXPECT_NEAR(c.SignedVolume(), polygon * 2.0, 1e-9);
}

TEST(MeshTest, ReflectionKeepsOutwardWinding) {
  TriangleMesh box = TriangleMesh::Box({0, 0, 0}, {1, 1, 1});
  box.Transform(Eigen::Affine3d(Eigen::Scaling(Vector3d(-1, 1, 1))));
  EXPECT_NEAR(box.SignedVolume(), 1.0, 1e-12);
}

TEST(MeshTest, SamplesAreUniformByArea) {
  // Two triangles of areas 0.5 and 4.5: samples split 1:9.
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {10, 0, 0}, {13, 0, 0}, {10, 3, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  Rng rng(3);
  const auto pts = m.SamplePoints(20000, rng);
  ASSERT_EQ(pts.size(), 20000u);
  int small = 0;
  for (const auto& p : pts) {
    if (p.x() < 5) {
      ++small;
      EXPECT_LE(p.x() + p.y(), 1.0 + 1e-12);
    }
  }
  EXPECT_NEAR(small / 20000.0, 0.1, 0.01);
  // Same seed, same points.
  Rng rng2(3);
  EXPECT_TRUE(m.SamplePoints(10, rng2)[7].isApprox(pts[7]));
}

TEST(MeshTest, ClosestPointOnTriangleRegions) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(ClosestPointOnTriangle({0.2, 0.2, 5}, a, b, c).isApprox(Vector3d(0.2, 0.2, 0)));
  EXPECT_TRUE(ClosestPointOnTriangle({-1, -1, 0}, a, b, c).isApprox(a));
  EXPECT_TRUE(ClosestPointOnTriangle({0.5, -2, 0}, a, b, c).isApprox(Vector3d(0.5, 0, 0)));
  EXPECT_TRUE(ClosestPointOnTriangle({1, 1, 0}, a, b, c).isApprox(Vector3d(0.5, 0.5, 0)));
  const TriangleMesh box = TriangleMesh::Box({0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(box.ClosestPoint({0.5, 0.5, 3}).isApprox(Vector3d(0.5, 0.5, 1)));
  EXPECT_TRUE(box.ClosestPoint({0.5, 0.5, 0.9}).isApprox(Vector3d(0.5, 0.5, 1)));
}

TEST(MeshTest, ComponentsSplitTouchingPrimitivesButNotSharedEdges) {
  // A seat and a leg touching at a corner and face stay two pieces.
  TriangleMesh m = TriangleMesh::Box({0, 0, 0.4}, {0.5, 0.5, 0.45});
  m.Append(TriangleMesh::Box({0, 0, 0}, {0.05, 0.05, 0.4}));
  EXPECT_EQ(m.EdgeConnectedComponents().size(), 2u);
  // Two walls meeting at a corner share a vertical edge but are separate solids; so are two
  // cushions sharing a face.
  TriangleMesh corner = TriangleMesh::Box({0, 0, 0}, {5, 0.1, 2.5});
  corner.Append(TriangleMesh::Box({0, 0, 0}, {0.1, 5, 2.5}));
  EXPECT_EQ(corner.EdgeConnectedComponents().size(), 2u);
  TriangleMesh cushions = TriangleMesh::Box({0, 0, 0}, {1, 1, 0.2});
  cushions.Append(TriangleMesh::Box({0, 1, 0}, {1, 2, 0.2}));
  EXPECT_EQ(cushions.EdgeConnectedComponents().size(), 2u);
  TriangleMesh open_quad;
  open_quad.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  open_quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_FALSE(open_quad.IsClosed());
  EXPECT_EQ(open_quad.EdgeConnectedComponents().size(), 1u);
  // A box whose faces come with duplicated vertices (as exporters write them) is one piece.
  TriangleMesh split;
  const TriangleMesh box = TriangleMesh::Box({0, 0, 0}, {1, 1, 1});
  for (const auto& t : box.triangles) {
    const int base = static_cast<int>(split.vertices.size());
    for (int k = 0; k < 3; ++k) split.vertices.push_back(box.vertices[t[k]]);
    split.triangles.emplace_back(base, base + 1, base + 2);
  }
  const auto pieces = split.EdgeConnectedComponents();
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].vertices.size(), 8u);
  EXPECT_TRUE(split.IsClosed());
}

}  // namespace
}  // namespace sims::scene
