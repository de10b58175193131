#include "sims/scene/builtin.h"

#include <deque>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "sims/scene/ray_caster.h"

namespace sims::scene {
namespace {

std::set<std::string> PartNames(const Object& o) {
  std::set<std::string> names;
  for (const auto& p : o.parts) names.insert(p.name);
  return names;
}

TEST(BuiltinTest, EveryCategoryBuildsWithNamedSampledParts) {
  for (const auto& c : ProceduralCategories()) {
    const Object o = MakeFurniture(c, DefaultFurnitureParams(c), c + "_x");
    EXPECT_EQ(o.category, c);
    EXPECT_EQ(o.instance, c + "_x");
    ASSERT_FALSE(o.parts.empty()) << c;
    for (const auto& p : o.parts) {
      EXPECT_FALSE(p.mesh.empty()) << c << "/" << p.name;
      EXPECT_TRUE(p.mesh.IsClosed()) << c << "/" << p.name;
      EXPECT_EQ(p.points.size(), static_cast<std::size_t>(Object::kDefaultPointsPerPart));
    }
    // Standing on the floor, centred on the origin.
    const Aabb b = o.Bounds();
    EXPECT_NEAR(b.min.z(), 0.0, 1e-12) << c;
    EXPECT_NEAR(b.center().y(), 0.0, 0.05) << c;
  }
}

TEST(BuiltinTest, PartNamesArePartNetLike) {
  FurnitureParams p = DefaultFurnitureParams("chair");
  p.has_arms = true;
  p.width = 0.56;
  EXPECT_EQ(PartNames(MakeFurniture("chair", p)),
            (std::set<std::string>{"seat surface", "legs", "back", "left arm", "right arm"}));
  p.has_arms = false;
  p.has_back = false;
  p.height = p.seat_height;
  EXPECT_EQ(PartNames(MakeFurniture("chair", p)), (std::set<std::string>{"seat surface", "legs"}));
  const Object bed = MakeFurniture("bed", DefaultFurnitureParams("bed"));
  EXPECT_EQ(bed.PartsNamed("pillow").size(), 2u);
  EXPECT_NE(bed.FindPart("mattress"), nullptr);
  EXPECT_NE(bed.FindPart("headboard"), nullptr);
  // Pillow ids differ so UniHSI keys ("pillow4", "pillow5") stay unique.
  EXPECT_NE(bed.PartsNamed("pillow")[0]->id, bed.PartsNamed("pillow")[1]->id);
  EXPECT_NE(MakeFurniture("shelf", DefaultFurnitureParams("shelf")).FindPart("board"), nullptr);
  EXPECT_NE(MakeFurniture("table", DefaultFurnitureParams("table")).FindPart("top"), nullptr);
  const Object sofa = MakeFurniture("sofa", DefaultFurnitureParams("sofa"));
  EXPECT_TRUE(PartNames(sofa).count("left arm") && PartNames(sofa).count("seat surface"));
  // The seat top is at seat_height and the left arm is on +y (the sitter's left).
  const Object chair = MakeFurniture("chair", DefaultFurnitureParams("chair"));
  EXPECT_NEAR(chair.FindPart("seat surface")->mesh.Bounds().max.z(), 0.45, 1e-12);
  EXPECT_GT(sofa.FindPart("left arm")->mesh.Bounds().center().y(), 0.5);
  EXPECT_LT(chair.FindPart("back")->mesh.Bounds().center().x(), 0.0);  // back behind, front +x
}

TEST(BuiltinTest, HeldOutDimensionsAreDisjointFromTraining) {
  for (const std::string c : {"chair", "sofa", "bed", "table"}) {
    const FurnitureParams nominal = DefaultFurnitureParams(c);
    Rng rng(11);
    for (int i = 0; i < 200; ++i) {
      const bool held_out = i % 2 == 1;
      const FurnitureParams p = RandomFurnitureParams(c, rng, held_out);
      const double f = p.seat_height / nominal.seat_height;
      const double d = p.depth / nominal.depth;
      if (held_out) {
        EXPECT_TRUE(f < 0.87 || f > 1.13) << c << " seat factor " << f;
        EXPECT_TRUE(d < 0.87 || d > 1.13) << c << " depth factor " << d;
      } else {
        EXPECT_TRUE(f >= 0.9 && f <= 1.1) << c << " seat factor " << f;
        EXPECT_TRUE(d >= 0.9 && d <= 1.1) << c << " depth factor " << d;
      }
    }
  }
  Rng a(5), b(5);
  const Object x = RandomFurniture("chair", a, false), y = RandomFurniture("chair", b, false);
  EXPECT_TRUE(x.Bounds().max.isApprox(y.Bounds().max));
}

TEST(BuiltinTest, WideTrainingScaleSkipsTheHeldOutBands) {
  const TrainingScale wide{0.7, 1.3};
  const FurnitureParams nominal = DefaultFurnitureParams("bed");
  Rng rng(3);
  int below = 0, inside = 0, above = 0;
  for (int i = 0; i < 2000; ++i) {
    const double d = RandomFurnitureParams("bed", rng, false, wide).depth / nominal.depth;
    ASSERT_TRUE(d >= 0.7 - 1e-12 && d <= 1.3 + 1e-12) << d;
    ASSERT_FALSE((d > 0.76 && d < 0.86) || (d > 1.14 && d < 1.24)) << "held-out factor " << d;
    (d < 0.76 ? below : d > 1.24 ? above : inside) += 1;
  }
  // Uniform over the 0.40 of allowed length: 0.06 below, 0.28 in the middle, 0.06 above.
  EXPECT_NEAR(below / 2000.0, 0.15, 0.03);
  EXPECT_NEAR(above / 2000.0, 0.15, 0.03);
  EXPECT_NEAR(inside / 2000.0, 0.70, 0.04);
  // The default range meets no band: the same draws as before the option existed.
  Rng a(9), b(9);
  EXPECT_EQ(RandomFurnitureParams("bed", a, false).depth,
            RandomFurnitureParams("bed", b, false, TrainingScale{0.9, 1.1}).depth);
  Rng c(9), u(9);
  u.Uniform();  // the width factor; depth is the second draw
  EXPECT_NEAR(RandomFurnitureParams("bed", c, false).depth / nominal.depth, 0.9 + 0.2 * u.Uniform(),
              1e-12);
}

TEST(BuiltinTest, BadCategoryAndParamsAreClearErrors) {
  try {
    MakeFurniture("throne", FurnitureParams{});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("armchair"), std::string::npos) << e.what();
  }
  FurnitureParams p;
  p.seat_height = 2.0;  // above the overall height
  EXPECT_THROW(MakeFurniture("chair", p), Error);
}

TEST(BuiltinTest, RoomsAreFurnishedWalledAndNotOverlapping) {
  const std::vector<Scene> rooms = BuiltinRooms();
  std::set<std::string> types;
  for (const Scene& s : rooms) {
    ASSERT_EQ(s.rooms.size(), 1u);
    types.insert(s.rooms[0].type);
    EXPECT_FALSE(s.walls.empty()) << s.name;
    EXPECT_GE(s.objects.size(), 5u) << s.name;
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
      const Aabb a = s.objects[i].Bounds();
      // Inside the walls' inner faces (walls are 0.1 m thick, centred on the room edge).
      EXPECT_GE(a.min.x(), 0.05 - 1e-9) << s.objects[i].instance;
      EXPECT_GE(a.min.y(), 0.05 - 1e-9) << s.objects[i].instance;
      EXPECT_LE(a.max.x(), 4.95 + 1e-9) << s.objects[i].instance;
      EXPECT_LE(a.max.y(), 4.95 + 1e-9) << s.objects[i].instance;
      EXPECT_EQ(s.objects[i].room, s.rooms[0].id);
      for (std::size_t j = i + 1; j < s.objects.size(); ++j) {
        const Aabb b = s.objects[j].Bounds();
        const Eigen::Vector3d overlap = a.max.cwiseMin(b.max) - a.min.cwiseMax(b.min);
        const bool disjoint = (overlap.array() <= 1e-9).any();
        EXPECT_TRUE(disjoint) << s.name << ": " << s.objects[i].instance << " overlaps "
                              << s.objects[j].instance;
      }
    }
  }
  EXPECT_EQ(types, (std::set<std::string>{"bedroom", "living room", "dining room", "library"}));
}

// Random rooms: walled, each piece inside its own room, no two pieces overlapping, the same
// seed giving the same rooms, and held-out rooms built from held-out dimensions.
TEST(BuiltinTest, RandomRoomsAreFurnishedWalledAndNotOverlapping) {
  Rng rng(5);
  const Scene s = RandomRooms(4, rng, false);
  ASSERT_EQ(s.rooms.size(), 4u);
  EXPECT_FALSE(s.walls.empty());
  std::map<std::string, int> pieces;
  for (const Room& r : s.rooms) pieces[r.id] = 0;
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    ASSERT_TRUE(pieces.count(o.room)) << o.instance;
    ++pieces[o.room];
    const Room& room = *std::find_if(s.rooms.begin(), s.rooms.end(),
                                     [&](const Room& r) { return r.id == o.room; });
    const Eigen::Vector2d lo = room.floor_polygon[0], hi = room.floor_polygon[2];
    const Aabb a = o.Bounds();
    EXPECT_GE(a.min.x(), lo.x() + 0.05 - 1e-9) << o.instance;
    EXPECT_GE(a.min.y(), lo.y() + 0.05 - 1e-9) << o.instance;
    EXPECT_LE(a.max.x(), hi.x() - 0.05 + 1e-9) << o.instance;
    EXPECT_LE(a.max.y(), hi.y() - 0.05 + 1e-9) << o.instance;
    for (std::size_t j = i + 1; j < s.objects.size(); ++j) {
      const Aabb b = s.objects[j].Bounds();
      const Eigen::Vector3d overlap = a.max.cwiseMin(b.max) - a.min.cwiseMax(b.min);
      EXPECT_TRUE((overlap.array() <= 1e-9).any())
          << o.instance << " overlaps " << s.objects[j].instance;
    }
  }
  for (const auto& [id, n] : pieces) {
    EXPECT_GE(n, 2) << id;
    EXPECT_LE(n, 7) << id;
  }
  Rng same(5);
  const Scene again = RandomRooms(4, same, false);
  ASSERT_EQ(again.objects.size(), s.objects.size());
  for (std::size_t i = 0; i < s.objects.size(); ++i)
    EXPECT_TRUE(again.objects[i].X_WO.isApprox(s.objects[i].X_WO));
  Rng held(5);
  const Scene test = RandomRooms(4, held, true);
  EXPECT_NE(test.name, s.name);
  // Held-out pieces are 0.76–0.86 or 1.14–1.24 of nominal, training pieces 0.9–1.1: the two
  // first pieces' footprints differ.
  ASSERT_FALSE(test.objects.empty());
  EXPECT_FALSE(test.objects[0].LocalBounds().max.isApprox(s.objects[0].LocalBounds().max));
}

// Free floor cells (nothing above 5 cm within `clearance`) on a 0.1 m grid over the house.
TEST(BuiltinTest, HouseRoomsAreConnectedThroughDoors) {
  const Scene house = BuiltinHouse();
  ASSERT_EQ(house.rooms.size(), 4u);
  const RayCaster caster(house);
  const double step = 0.1, clearance = 0.25;
  const int n = 100;
  std::vector<uint8_t> free(n * n, 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) * step, y = (j + 0.5) * step;
      bool ok = true;
      for (double dx : {-clearance, 0.0, clearance})
        for (double dy : {-clearance, 0.0, clearance})
          if (caster.HeightAt(x + dx, y + dy) > 0.05) ok = false;
      free[j * n + i] = ok;
    }
  // Breadth-first search from the living-room centre.
  std::vector<uint8_t> seen(n * n, 0);
  std::deque<int> q;
  const int start = 25 * n + 35;  // (3.55, 2.55) in the living room
  ASSERT_TRUE(free[start]);
  seen[start] = 1;
  q.push_back(start);
  while (!q.empty()) {
    const int c = q.front();
    q.pop_front();
    const int i = c % n, j = c / n;
    const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& d : nb) {
      const int a = i + d[0], b = j + d[1];
      if (a < 0 || b < 0 || a >= n || b >= n) continue;
      const int k = b * n + a;
      if (free[k] && !seen[k]) {
        seen[k] = 1;
        q.push_back(k);
      }
    }
  }
  // Every room has plenty of floor (several m²) reachable on foot from the living room, and
  // most of its free floor is reachable.
  for (const Room& r : house.rooms) {
    int reached = 0, free_cells = 0;
    for (int k = 0; k < n * n; ++k) {
      if (!r.Contains({(k % n + 0.5) * step, (k / n + 0.5) * step})) continue;
      free_cells += free[k];
      reached += seen[k];
    }
    EXPECT_GT(reached, 300) << r.id;
    EXPECT_GT(reached, 0.8 * free_cells) << r.id;
  }
  // And the outside is not reachable (the outer walls are closed).
  EXPECT_EQ(house.RoomAt(-1, 5), nullptr);
  EXPECT_GT(caster.HeightAt(0.0, 5.0), 2.0);
}

TEST(BuiltinTest, ScenesByName) {
  EXPECT_EQ(BuiltinScene("house").rooms.size(), 4u);
  EXPECT_EQ(BuiltinScene("Living Room").rooms[0].type, "living room");
  EXPECT_EQ(BuiltinScene("sofa").objects.size(), 1u);
  EXPECT_TRUE(BuiltinScene("empty").objects.empty());
  try {
    BuiltinScene("castle");
    FAIL();
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("castle"), std::string::npos);
    EXPECT_NE(msg.find("dining_room"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace sims::scene
