#include "sims/scene/scene.h"

#include <gtest/gtest.h>

namespace sims::scene {
namespace {

Object TwoPartObject() {
  Object o;
  o.category = "bed";
  o.instance = "bed_0";
  Part mattress;
  mattress.name = "mattress";
  mattress.id = 18;
  mattress.mesh = TriangleMesh::Box({-1, -0.5, 0.3}, {1, 0.5, 0.5});
  Part seat;
  seat.name = "seat soft surface";
  seat.id = 16;
  seat.mesh = TriangleMesh::Box({-1, -0.5, 0}, {1, 0.5, 0.3});
  o.parts = {mattress, seat};
  return o;
}

TEST(SceneTest, FindPartByDatasetKeys) {
  const Object o = TwoPartObject();
  EXPECT_EQ(o.FindPartByKey("mattress18"), &o.parts[0]);
  EXPECT_EQ(o.FindPartByKey("seat_soft_surface16"), &o.parts[1]);
  EXPECT_EQ(o.FindPartByKey("Seat_Soft_Surface"), &o.parts[1]);
  EXPECT_EQ(o.FindPartByKey("pillow20"), nullptr);
  EXPECT_EQ(UniHsiPartKey(o.parts[1]), "seat_soft_surface16");
  EXPECT_EQ(NormalizeName("  Seat__Soft-Surface "), "seat soft surface");
}

TEST(SceneTest, ApplyTransformMovesMeshesPointsAndPose) {
  Object o = TwoPartObject();
  Rng rng(1);
  o.ResamplePoints(rng, 32);
  ASSERT_EQ(o.parts[0].points.size(), 32u);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(5, 0, 0);
  o.ApplyTransform(X);
  const Aabb b = o.Bounds();
  EXPECT_NEAR(b.min.x(), 4.5, 1e-12);
  EXPECT_NEAR(b.max.y(), 1.0, 1e-12);
  for (const auto& p : o.parts[0].points) {
    EXPECT_GE(p.x(), 4.5 - 1e-9);
    EXPECT_LE(p.x(), 5.5 + 1e-9);
  }
  // Local bounds do not change with the pose.
  const Aabb local = o.LocalBounds();
  EXPECT_NEAR(local.min.x(), -1, 1e-12);
  EXPECT_NEAR(local.max.y(), 0.5, 1e-12);
}

TEST(SceneTest, UniqueInstancesAndRooms) {
  Scene s;
  Object a = TwoPartObject();
  s.AddObject(a);
  s.AddObject(a);  // duplicate id gets renamed
  EXPECT_EQ(s.objects[0].instance, "bed_0");
  EXPECT_EQ(s.objects[1].instance, "bed_1");
  EXPECT_EQ(s.ObjectIndex("bed_1"), 1);
  EXPECT_EQ(s.ObjectsOfCategory("bed").size(), 2u);
  EXPECT_EQ(s.TriangleCount(), 48u);
  Room r;
  r.id = "r";
  r.floor_polygon = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}};  // an L
  s.rooms.push_back(r);
  EXPECT_TRUE(r.Contains({0.5, 2.5}));
  EXPECT_FALSE(r.Contains({2, 2}));
  EXPECT_EQ(s.RoomAt(3, 0.5), &s.rooms[0]);
  EXPECT_EQ(s.RoomAt(3, 2), nullptr);
}

}  // namespace
}  // namespace sims::scene
