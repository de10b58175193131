#include "sims/scene/contact_targets.h"

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "sims/scene/builtin.h"

namespace sims::scene {
namespace {

using Eigen::Vector3d;

TEST(ContactTargetsTest, NearestPointsOnParts) {
  const Object chair = MakeFurniture("chair", DefaultFurnitureParams("chair"));
  const Part& seat = *chair.FindPart("seat surface");
  const Vector3d pelvis(0.0, 0.05, 0.9);
  EXPECT_TRUE(NearestPointOnPart(seat, pelvis).isApprox(Vector3d(0.0, 0.05, 0.45)));
  const Vector3d sample = NearestSamplePoint(seat, pelvis);
  EXPECT_NEAR(sample.z(), 0.45, 0.06);  // samples cover the whole slab, top included
  EXPECT_LT((sample - pelvis).norm(), 0.5);
  const SurfacePoint sp = NearestPointOnObject(chair, Vector3d(-0.5, 0.0, 0.7));
  EXPECT_EQ(chair.parts[sp.part].name, "back");
  EXPECT_NEAR(sp.distance, 0.5 - 0.23, 1e-9);
}

TEST(ContactTargetsTest, StandPointsAreInFrontAndFree) {
  Scene s;
  Object chair = MakeFurniture("chair", DefaultFurnitureParams("chair"));
  PlaceObject(&chair, 1.0, 1.0, M_PI / 2);  // facing +y
  s.AddObject(chair);
  const auto points = StandPoints(s, 0);
  ASSERT_FALSE(points.empty());
  // Best first: straight in front along the chair's +x (world +y).
  EXPECT_NEAR(points[0].x(), 1.0, 1e-9);
  EXPECT_NEAR(points[0].y(), 1.0 + 0.23 + 0.45, 1e-9);
  EXPECT_EQ(points[0].z(), 0.0);
  // A wall right in front removes the front candidates.
  s.walls = TriangleMesh::Box({0, 1.5, 0}, {2, 1.6, 2.5});
  const auto blocked = StandPoints(s, 0);
  for (const auto& p : blocked) EXPECT_LT(p.y(), 1.5);
  EXPECT_THROW(StandPoints(s, 3), Error);
}

TEST(ContactTargetsTest, HouseStandPointsStayInFreeFloor) {
  const Scene house = BuiltinHouse();
  const RayCaster caster(house);
  int with_points = 0;
  for (int i = 0; i < static_cast<int>(house.objects.size()); ++i) {
    const auto pts = StandPoints(house, caster, i);
    with_points += !pts.empty();
    for (const auto& p : pts) {
      EXPECT_LE(caster.HeightAt(p.x(), p.y()), 0.05);
      const Room* room = house.RoomAt(p.x(), p.y());
      ASSERT_NE(room, nullptr);
      EXPECT_EQ(room->id, house.objects[i].room) << house.objects[i].instance;
    }
  }
  EXPECT_EQ(with_points, static_cast<int>(house.objects.size()));
}

}  // namespace
}  // namespace sims::scene
