#include "sims/scene/ray_caster.h"

#include <gtest/gtest.h>

#include "scene/test_scenes.h"
#include "sims/scene/builtin.h"

namespace sims::scene {
namespace {

using Eigen::Vector3d;

TEST(RayCasterTest, CastsHeightsAndHits) {
  Scene s = testing::BoxScene({1, -0.5, 0}, {2, 0.5, 0.8});
  s.walls = TriangleMesh::Box({4, -5, 0}, {4.1, 5, 2.5});
  const RayCaster rc(s);
  EXPECT_EQ(rc.num_triangles(), 24);
  EXPECT_NEAR(rc.HeightAt(1.5, 0), 0.8, 1e-6);
  EXPECT_EQ(rc.HeightAt(0.5, 0), 0.0);
  EXPECT_NEAR(rc.HeightAt(4.05, 0), 2.5, 1e-6);
  const auto d = rc.Cast({0, 0, 0.4}, {2, 0, 0}, 10.0);  // direction gets normalised
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(*d, 1.0, 1e-6);
  EXPECT_FALSE(rc.Cast({0, 0, 0.4}, {-1, 0, 0}, 10.0).has_value());
  EXPECT_FALSE(rc.Cast({0, 0, 0.4}, {1, 0, 0}, 0.9).has_value());
  const auto hit = rc.CastHit({1.5, 0, 3}, {0, 0, -1}, 10.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->object, 0);
  EXPECT_EQ(hit->part, 0);
  EXPECT_NEAR(std::abs(hit->normal.z()), 1.0, 1e-6);
  EXPECT_TRUE(hit->point.isApprox(Vector3d(1.5, 0, 0.8), 1e-6));
  const auto wall = rc.CastHit({3, 0, 1}, {1, 0, 0}, 10.0);
  ASSERT_TRUE(wall.has_value());
  EXPECT_EQ(wall->object, -1);
  // Batch down-casts match single casts at any thread count.
  std::vector<double> xy, h1(50), h2(50);
  for (int i = 0; i < 50; ++i) xy.insert(xy.end(), {0.1 * i, 0.0});
  rc.HeightsAt(xy.data(), 50, h1.data(), 1);
  rc.HeightsAt(xy.data(), 50, h2.data(), 2);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(h1[i], h2[i]);
    EXPECT_EQ(h1[i], rc.HeightAt(xy[2 * i], 0.0));
  }
}

TEST(RayCasterTest, LineOfSight) {
  Scene s;
  s.walls = TriangleMesh::Box({0.95, -1, 0}, {1.05, 1, 2.5});
  const RayCaster rc(s);
  EXPECT_TRUE(rc.Occluded({0, 0, 1}, {2, 0, 1}));
  EXPECT_TRUE(rc.Occluded({2, 0, 1}, {0, 0, 1}));
  EXPECT_FALSE(rc.Occluded({0, 0, 1}, {0.9, 0, 1}));
  EXPECT_FALSE(rc.Occluded({0, 2, 1}, {2, 2, 1}));  // past the wall's end
  EXPECT_FALSE(rc.Occluded({0, 0, 3}, {2, 0, 3}));  // over it
  // A point on a surface is visible from the front (the endpoint itself does not occlude).
  EXPECT_FALSE(rc.Occluded({0, 0, 1}, {0.95, 0, 1}));
  // An empty scene never occludes.
  EXPECT_FALSE(RayCaster(Scene{}).Occluded({0, 0, 0}, {1, 1, 1}));
  // In the house, rooms are separated by walls except through doors.
  const RayCaster house(BuiltinHouse());
  EXPECT_TRUE(house.Occluded({2.5, 7.5, 1.5}, {7.5, 7.5, 1.5}));   // bedroom -> library
  EXPECT_FALSE(house.Occluded({2.5, 3.5, 1.5}, {2.5, 6.5, 1.5}));  // living -> bedroom door
}

}  // namespace
}  // namespace sims::scene
