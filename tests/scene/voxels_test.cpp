#include "sims/scene/voxels.h"

#include <cmath>

#include <gtest/gtest.h>

#include "scene/test_scenes.h"

namespace sims::scene {
namespace {

using Eigen::Vector3d;

double DistanceToUnitBoxSurface(const Vector3d& p) {
  const Vector3d d = (p - Vector3d::Constant(0.5)).cwiseAbs() - Vector3d::Constant(0.5);
  if ((d.array() <= 0).all()) return -d.maxCoeff();
  return d.cwiseMax(0.0).norm();
}

TEST(VoxelsTest, SolidVoxelisationFillsTheInterior) {
  const TriangleMesh box = TriangleMesh::Box({0, 0, 0}, {1, 1, 1});
  const VoxelGrid g = VoxelizeSolid(box, 0.05);
  // 20 cells per axis, plus at most one extra boundary layer per axis.
  EXPECT_GE(g.Count(), 20 * 20 * 20);
  EXPECT_LE(g.Count(), 21 * 21 * 21);
  EXPECT_TRUE(g.Occupied({0.5, 0.5, 0.5}));
  EXPECT_FALSE(g.Occupied({1.2, 0.5, 0.5}));
  // A solid box merges into a single box.
  const auto boxes = MergeVoxelsToBoxes(g);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_NEAR(boxes[0].size().x(), 1.0, 0.051);
}

TEST(VoxelsTest, OverlappingShellsStaySolid) {
  // Two overlapping closed boxes: parity tests would call the overlap "outside".
  TriangleMesh m = TriangleMesh::Box({0, 0, 0}, {1, 1, 1});
  m.Append(TriangleMesh::Box({0.5, 0, 0}, {1.5, 1, 1}));
  const VoxelGrid g = VoxelizeSolid(m, 0.05);
  EXPECT_TRUE(g.Occupied({0.75, 0.5, 0.5}));
  EXPECT_TRUE(InsideByWindingNumber(m, {0.75, 0.5, 0.5}));
  EXPECT_FALSE(InsideByWindingNumber(m, {1.75, 0.5, 0.5}));
}

TEST(VoxelsTest, LShapeMergesIntoFewBoxesWithTheCornerFree) {
  TriangleMesh m = TriangleMesh::Box({0, 0, 0}, {1, 0.2, 0.1});
  m.Append(TriangleMesh::Box({0, 0, 0.1}, {0.1, 0.2, 1}));
  const auto boxes = MergeVoxelsToBoxes(VoxelizeSolid(m, 0.02));
  EXPECT_LE(boxes.size(), 4u);
  for (const auto& b : boxes) {
    const Vector3d corner(0.5, 0.1, 0.5);  // the empty corner of the L
    EXPECT_FALSE((corner.array() >= b.min.array()).all() &&
                 (corner.array() <= b.max.array()).all());
  }
}

TEST(VoxelsTest, EgocentricOccupancyOfAUnitBox) {
  const Scene s = testing::BoxScene({0, 0, 0}, {1, 1, 1});
  OccupancyOptions o;
  o.include_floor = false;
  const SceneOccupancy occ(s, o);
  VoxelObservationConfig cfg;  // 32³ over 1.2 m
  std::vector<float> v(cfg.size());
  SampleOccupancy(occ, {0.5, 0.5, 0.5}, 0.0, cfg, v.data());
  const double step = cfg.extent / cfg.cells;
  int count = 0;
  for (int k = 0; k < cfg.cells; ++k)
    for (int j = 0; j < cfg.cells; ++j)
      for (int i = 0; i < cfg.cells; ++i) {
        const Vector3d p = Vector3d(0.5, 0.5, 0.5) + Vector3d(i + 0.5, j + 0.5, k + 0.5) * step -
                           Vector3d::Constant(0.6);
        const float value = v[(k * cfg.cells + j) * cfg.cells + i];
        count += value > 0.5f;
        const bool inside = (p.array() >= 0).all() && (p.array() <= 1).all();
        // Away from the surface (more than one precomputed cell) the answer is exact.
        if (DistanceToUnitBoxSurface(p) > o.resolution) {
          EXPECT_EQ(value > 0.5f, inside) << p.transpose();
        }
        if (i % 7 == 0 && j % 5 == 0 && k % 3 == 0) {
          EXPECT_EQ(occ.InsideExact(p), inside);
        }
      }
  // 26 cell centres per axis fall inside [0, 1].
  EXPECT_NEAR(count, 26 * 26 * 26, 26 * 26 * 6 * 1.0);
  // Rotating the cube by 45° about z moves the box corners out of the view's corners.
  std::vector<float> r(cfg.size());
  SampleOccupancy(occ, {0.5, 0.5, 0.5}, M_PI / 4, cfg, r.data());
  EXPECT_EQ(r[(16 * cfg.cells + 16) * cfg.cells + 16], 1.0f);  // centre
  EXPECT_EQ(r[(16 * cfg.cells + 0) * cfg.cells + 0], 0.0f);    // local (-0.58, -0.58): outside
  EXPECT_EQ(r[(16 * cfg.cells + 16) * cfg.cells + 1], 1.0f);   // local (-0.54, 0): inside
  // Dual voxels: the second grid is around the goal.
  std::vector<float> dual(2 * cfg.size());
  SampleDualOccupancy(occ, {0.5, 0.5, 0.5}, {5, 5, 0.5}, 0.0, cfg, dual.data());
  EXPECT_EQ(std::count(dual.begin() + cfg.size(), dual.end(), 1.0f), 0);
  EXPECT_EQ(std::count(dual.begin(), dual.begin() + cfg.size(), 1.0f), count);
}

TEST(VoxelsTest, PenetrationDepthAndFraction) {
  const Scene s = testing::BoxScene({0, 0, 0}, {1, 1, 1});
  const SceneOccupancy occ(s);
  EXPECT_NEAR(occ.PenetrationDepth({0.5, 0.5, 0.9}), 0.1, 1e-9);
  EXPECT_NEAR(occ.PenetrationDepth({3, 3, -0.2}), 0.2, 1e-9);  // below the floor
  EXPECT_EQ(occ.PenetrationDepth({3, 3, 0.2}), 0.0);
  const PenetrationStats st =
      MeasurePenetration(occ, {{0.5, 0.5, 0.9}, {0.5, 0.5, 0.7}, {3, 3, 1}, {2, 2, 2}});
  EXPECT_EQ(st.num_points, 4);
  EXPECT_NEAR(st.fraction_inside, 0.5, 1e-12);
  EXPECT_NEAR(st.mean_depth, 0.2, 1e-9);
  EXPECT_NEAR(st.max_depth, 0.3, 1e-9);
}

}  // namespace
}  // namespace sims::scene
