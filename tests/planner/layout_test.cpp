// Scene graphs, required graphs, layout retrieval with substitution, multi-room composition
// and binding of keyframes to objects.
#include "sims/planner/layout.h"

#include <cmath>
#include <deque>
#include <fstream>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/scene/mesh.h"

namespace sims::planner {
namespace {

using ::testing::HasSubstr;

scene::Object Box(const std::string& category, const std::string& instance, double x, double y,
                  double sx, double sy, double sz, const std::string& room = "") {
  scene::Object o;
  o.category = category;
  o.instance = instance;
  o.room = room;
  o.X_WO.translation() = Eigen::Vector3d(x, y, 0);
  scene::Part p;
  p.name = "body";
  p.mesh = scene::TriangleMesh::Box(Eigen::Vector3d(x - sx / 2, y - sy / 2, 0),
                                    Eigen::Vector3d(x + sx / 2, y + sy / 2, sz));
  o.parts.push_back(p);
  return o;
}

scene::Scene Room(const std::string& name, const std::string& type, double w, double h,
                  std::vector<scene::Object> objects) {
  scene::Scene s;
  s.name = name;
  scene::Room r;
  r.id = name;
  r.type = type;
  r.floor_polygon = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  s.rooms.push_back(r);
  for (scene::Object& o : objects) {
    o.room = name;
    s.objects.push_back(o);
  }
  return s;
}

// Hand-made rooms: every object of a room within reach of the others.
scene::Scene Bedroom() {
  return Room("my_bedroom", "bedroom", 4, 4,
              {Box("bed", "bed_0", 1.2, 2.0, 2.0, 1.6, 0.5),
               Box("nightstand", "ns_0", 2.6, 2.8, 0.5, 0.5, 0.5),
               Box("lamp", "lamp_0", 2.6, 3.5, 0.3, 0.3, 1.5)});
}
scene::Scene LivingRoom() {
  return Room("my_living", "living room", 5, 4,
              {Box("couch", "sofa_0", 2.5, 3.2, 2.0, 0.9, 0.8),
               Box("coffee table", "table_0", 2.5, 2.0, 1.0, 0.6, 0.4),
               Box("stool", "stool_0", 1.0, 2.0, 0.4, 0.4, 0.45)});
}
scene::Scene Library() {
  return Room("my_library", "study", 4, 5,
              {Box("bookcase", "shelf_0", 0.3, 2.5, 0.4, 1.6, 2.0),
               Box("desk", "desk_0", 2.0, 2.5, 1.2, 0.6, 0.75),
               Box("chair", "chair_0", 2.0, 1.8, 0.5, 0.5, 0.9)});
}

LayoutDatabase HandMadeDatabase() {
  LayoutDatabase db;
  for (const scene::Scene& s : {Bedroom(), LivingRoom(), Library()}) {
    LayoutSource src;
    src.kind = "scene_file";
    src.path = s.name;
    src.name = s.name;
    for (LayoutEntry& e : MakeLayoutEntries(s, src)) db.layouts.push_back(e);
  }
  return db;
}

SceneLoader HandMadeLoader() {
  return [](const LayoutSource& s) {
    for (const scene::Scene& sc : {Bedroom(), LivingRoom(), Library()})
      if (sc.name == s.path) return sc;
    throw Error("unknown test scene " + s.path);
  };
}

LongScript Script(const std::string& json) {
  return LongScriptFromJson(nlohmann::json::parse(json), "test script");
}

TEST(SceneGraphTest, EdgesNeedProximityAndLineOfSight) {
  scene::Scene s;
  s.name = "hand";
  s.objects = {
      Box("chair", "a", 0, 0, 0.5, 0.5, 0.9), Box("chair", "b", 1.2, 0, 0.5, 0.5, 0.9),
      Box("sofa", "c", 5, 0, 2, 0.9, 0.8),    Box("floor lamp", "d", 0, 1.0, 0.3, 0.3, 1.6),
      Box("table", "e", 5, 3, 1, 1, 0.75),    Box("chair", "f", 5, 4.2, 0.5, 0.5, 0.9)};
  // A wall between the table and the chair f.
  s.walls = scene::TriangleMesh::Box(Eigen::Vector3d(3, 3.65, 0), Eigen::Vector3d(7, 3.75, 2.5));
  SceneGraph g = BuildSceneGraph(s);
  ASSERT_EQ(g.size(), 6);
  EXPECT_EQ(g.nodes[3].category, "lamp");
  EXPECT_FALSE(g.nodes[3].important);
  EXPECT_TRUE(g.HasEdge(0, 1));   // 0.7 m apart, nothing between
  EXPECT_FALSE(g.HasEdge(0, 2));  // too far
  EXPECT_TRUE(g.HasEdge(0, 3));
  EXPECT_FALSE(g.HasEdge(4, 5));  // near, but the wall blocks the line of sight
  // Without the wall they are neighbours.
  scene::Scene open = s;
  open.walls = {};
  EXPECT_TRUE(BuildSceneGraph(open).HasEdge(4, 5));
  // A custom line-of-sight hook is used instead of the ray caster.
  int calls = 0;
  SceneGraph blind = BuildSceneGraph(open, {}, Vocabulary::Default(),
                                     [&](const Eigen::Vector3d&, const Eigen::Vector3d&) {
                                       ++calls;
                                       return false;
                                     });
  EXPECT_GT(calls, 0);
  EXPECT_FALSE(blind.HasEdge(0, 1));
}

TEST(SceneGraphTest, RequiredGraphConsolidatesInstances) {
  LongScript ls = Script(R"({"scripts": [
    {"scene": "bedroom", "keyframes": [{"skill": "loco", "furniture": "bed"}, {"skill": "sit", "furniture": "bed"},
                                       {"skill": "loco", "furniture": "nightstand"}, {"skill": "touch", "furniture": "nightstand"}]},
    {"scene": "living room", "keyframes": [{"skill": "loco", "furniture": "sofa"}, {"skill": "sit", "furniture": "sofa"},
                                           {"skill": "loco", "furniture": "chair"}, {"skill": "sit", "furniture": "chair"},
                                           {"skill": "loco", "furniture": "chair", "instance": 1}, {"skill": "sit", "furniture": "chair", "instance": 1}]},
    {"scene": "living room", "keyframes": [{"skill": "loco", "furniture": "chair", "instance": 4}, {"skill": "sit", "furniture": "chair", "instance": 4},
                                           {"skill": "loco", "furniture": "sofa"}, {"skill": "liedown", "furniture": "sofa"}]}]})");
  RequiredGraph rg = BuildRequiredGraph(ls);
  std::vector<std::string> names;
  for (const GraphNode& n : rg.graph.nodes) names.push_back(n.instance);
  // Two chairs at most in one script → two chair nodes; the third script's chair is chair#0.
  EXPECT_EQ(names,
            (std::vector<std::string>{"bed#0", "nightstand#0", "sofa#0", "chair#0", "chair#1"}));
  EXPECT_TRUE(rg.graph.HasEdge(0, 1));
  EXPECT_TRUE(rg.graph.HasEdge(2, 3));
  EXPECT_TRUE(rg.graph.HasEdge(3, 4));
  EXPECT_FALSE(rg.graph.HasEdge(1, 2));  // different short scripts are not joined
  EXPECT_EQ(rg.graph.edges.size(), 3u);
  EXPECT_EQ(rg.graph.nodes[2].room_types, (std::vector<std::string>{"living room"}));
  for (std::size_t i = 0; i < ls.keyframes.size(); ++i) {
    const Keyframe& k = ls.keyframes[i];
    ASSERT_GE(rg.keyframe_node[i], 0);
    EXPECT_EQ(rg.graph.nodes[rg.keyframe_node[i]].category, k.furniture);
  }
  // Per-segment graphs keep only their own nodes.
  EXPECT_EQ(BuildRequiredGraph(ls, {0}).graph.size(), 2);
}

// A substitute must afford what the script does on the node: an armchair may stand in for a
// sofa sat on, not for one lain on, so a script that lies on the sofa goes to the room with one
// (the library's armchair once stood in for a sofa in a lie keyframe no policy could run).
TEST(SceneGraphTest, SubstitutesMustAffordTheScriptsSkills) {
  const LongScript sit = Script(R"({"scene": "study", "keyframes": [
      {"skill": "loco", "furniture": "sofa"}, {"skill": "sit", "furniture": "sofa"}]})");
  const LongScript lie = Script(R"({"scene": "study", "keyframes": [
      {"skill": "loco", "furniture": "sofa"}, {"skill": "sit", "furniture": "sofa"},
      {"skill": "liedown", "furniture": "sofa"}]})");
  const GraphNode sofa_sat = BuildRequiredGraph(sit).graph.nodes.at(0);
  const GraphNode sofa_lain = BuildRequiredGraph(lie).graph.nodes.at(0);
  EXPECT_EQ(sofa_lain.uses, (std::vector<Skill>{Skill::kWalk, Skill::kSit, Skill::kLie}));
  GraphNode armchair;
  armchair.category = "armchair";
  const EditCosts c = RetrievalCosts(MatchCostConfig{}, Vocabulary::Default());
  EXPECT_TRUE(std::isfinite(c.substitute(sofa_sat, armchair)));
  EXPECT_TRUE(std::isinf(c.substitute(sofa_lain, armchair)));
  EXPECT_TRUE(std::isinf(c.substitute(armchair, sofa_lain)));

  LayoutDatabase db;
  for (const scene::Scene& s :
       {Room("my_study", "study", 4, 4, {Box("armchair", "armchair_0", 2, 2, 0.8, 0.8, 0.8)}),
        Room("my_living", "living room", 5, 4,
             {Box("couch", "sofa_0", 2.5, 3.2, 2.0, 0.9, 0.8)})}) {
    LayoutSource src;
    src.kind = "scene_file";
    src.path = src.name = s.name;
    for (LayoutEntry& e : MakeLayoutEntries(s, src)) db.layouts.push_back(e);
  }
  const LayoutMatch m = MatchLayouts(lie, db);
  ASSERT_EQ(m.bindings.size(), 3u);
  EXPECT_EQ(m.bindings[2].object, "sofa_0");
  EXPECT_EQ(m.layout.name, "my_living");
}

TEST(LayoutTest, PicksTheMatchingRoomAndBindsEveryKeyframe) {
  LayoutDatabase db = HandMadeDatabase();
  LongScript ls = Script(R"({"scene": "bedroom", "emotion": "tired", "keyframes": [
      {"skill": "loco", "furniture": "floor"}, {"skill": "sit", "furniture": "bed"},
      {"skill": "getup"}, {"skill": "touch", "caption": "reaches low with the left hand", "furniture": "bedside table"},
      {"skill": "loco", "furniture": "floor"}]})");
  LayoutMatch m = MatchLayouts(ls, db);
  EXPECT_EQ(m.layout.mode, "single");
  EXPECT_EQ(m.layout.name, "my_bedroom");
  EXPECT_TRUE(m.layout.exact);
  EXPECT_TRUE(m.warnings.empty());
  ASSERT_EQ(m.bindings.size(), ls.keyframes.size());
  std::vector<std::string> objects;
  for (const Binding& b : m.bindings) {
    EXPECT_TRUE(b.placed);
    objects.push_back(b.object);
  }
  // walk(→bed), sit, getup, inserted walk(→nightstand), reach, free walk.
  EXPECT_EQ(objects, (std::vector<std::string>{"bed_0", "bed_0", "bed_0", "ns_0", "ns_0", ""}));
  EXPECT_THAT(m.bindings.back().note, HasSubstr("free walk"));
  EXPECT_EQ(m.bindings[1].room, "my_bedroom");
}

// A get-up from the floor after a walk (a fall in the script) is placed where the character
// is: no object, while the walk before it still heads for the next object.
TEST(LayoutTest, AGetUpFromTheFloorBindsNoObject) {
  LayoutDatabase db = HandMadeDatabase();
  LongScript ls = Script(R"({"scene": "living room", "keyframes": [
      {"skill": "loco", "furniture": "floor"}, {"skill": "getup", "furniture": "floor"},
      {"skill": "loco", "furniture": "sofa"}, {"skill": "sit", "furniture": "sofa"}]})");
  LayoutMatch m = MatchLayouts(ls, db);
  ASSERT_EQ(m.bindings.size(), 4u);
  EXPECT_TRUE(m.bindings[1].placed);
  EXPECT_TRUE(m.bindings[1].object.empty());
  EXPECT_THAT(m.bindings[1].note, HasSubstr("gets up from the floor"));
  EXPECT_EQ(m.bindings[0].object, "sofa_0");
  EXPECT_EQ(m.bindings[3].object, "sofa_0");
  EXPECT_TRUE(m.warnings.empty());
}

TEST(LayoutTest, SubstitutionWhenTheCategoryIsMissing) {
  LayoutDatabase db = HandMadeDatabase();
  // No layout has an armchair; the living room's stool (stool↔armchair) or the library's chair
  // (chair↔armchair) must stand in. The sofa decides: the living room.
  LongScript ls = Script(R"({"scene": "living room", "keyframes": [
      {"skill": "loco", "furniture": "sofa"}, {"skill": "sit", "furniture": "sofa"}, {"skill": "getup"},
      {"skill": "loco", "furniture": "armchair"}, {"skill": "sit", "furniture": "armchair"}]})");
  LayoutMatch m = MatchLayouts(ls, db);
  EXPECT_EQ(m.layout.name, "my_living");
  EXPECT_EQ(m.bindings[1].object, "sofa_0");
  EXPECT_EQ(m.bindings[4].object, "stool_0");
  EXPECT_EQ(m.bindings[4].object_category, "stool");
  EXPECT_THAT(m.bindings[4].note, HasSubstr("stands in for the armchair"));
  EXPECT_TRUE(m.warnings.empty());
  // A double bed is served by the plain bed.
  LongScript bed = Script(
      R"({"keyframes": [{"skill": "loco"}, {"skill": "liedown", "furniture": "double bed"}]})");
  LayoutMatch mb = MatchLayouts(bed, db);
  EXPECT_EQ(mb.bindings[1].object, "bed_0");
  EXPECT_EQ(mb.bindings[1].object_category, "bed");
}

TEST(LayoutTest, ReportsKeyframesThatCannotBePlaced) {
  LayoutDatabase db = HandMadeDatabase();
  LongScript ls = Script(
      R"({"keyframes": [{"skill": "loco"}, {"skill": "touch", "caption": "opens the fridge", "furniture": "fridge"},
                                           {"skill": "loco"}, {"skill": "sit", "furniture": "bed"}]})");
  LayoutMatch m = MatchLayouts(ls, db);
  EXPECT_FALSE(m.bindings[1].placed);
  EXPECT_THAT(m.bindings[1].note, HasSubstr("has no fridge"));
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_THAT(m.warnings[0], HasSubstr("keyframe 1 (reach fridge) could not be placed"));
  EXPECT_TRUE(m.bindings[3].placed);
  EXPECT_EQ(m.bindings[3].object, "bed_0");
  EXPECT_THROW(MatchLayouts(ls, LayoutDatabase{}), Error);
}

// Breadth-first search over a grid of the composed floor: walls (plan segments) block.
bool Connected(const PlanLayout& layout, const std::array<double, 2>& from,
               const std::array<double, 2>& to) {
  const double res = 0.05, radius = 0.2;  // a character of 0.2 m radius
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (const PlanRoom& r : layout.rooms) {
    x0 = std::min(x0, r.footprint[0] - 0.5);
    y0 = std::min(y0, r.footprint[1] - 0.5);
    x1 = std::max(x1, r.footprint[2] + 0.5);
    y1 = std::max(y1, r.footprint[3] + 0.5);
  }
  int nx = static_cast<int>((x1 - x0) / res) + 1, ny = static_cast<int>((y1 - y0) / res) + 1;
  auto blocked = [&](double x, double y) {
    for (const PlanWall& w : layout.walls) {
      Eigen::Vector2d a(w.from[0], w.from[1]), b(w.to[0], w.to[1]), p(x, y);
      double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      if ((a + t * (b - a) - p).norm() < 0.5 * w.thickness + radius) return true;
    }
    return false;
  };
  auto cell = [&](double x, double y) {
    return std::make_pair(static_cast<int>((x - x0) / res), static_cast<int>((y - y0) / res));
  };
  std::vector<char> seen(nx * ny, 0);
  std::deque<std::pair<int, int>> q{cell(from[0], from[1])};
  auto goal = cell(to[0], to[1]);
  while (!q.empty()) {
    auto [i, j] = q.front();
    q.pop_front();
    if (i < 0 || j < 0 || i >= nx || j >= ny || seen[j * nx + i]) continue;
    seen[j * nx + i] = 1;
    if (blocked(x0 + i * res, y0 + j * res)) continue;
    if (std::make_pair(i, j) == goal) return true;
    q.push_back({i + 1, j});
    q.push_back({i - 1, j});
    q.push_back({i, j + 1});
    q.push_back({i, j - 1});
  }
  return false;
}

TEST(LayoutTest, ComposesRoomsOfDifferentTypesWhenNoSingleLayoutFits) {
  LayoutDatabase db = HandMadeDatabase();
  LongScript ls = Script(R"({"scripts": [
    {"scene": "bedroom", "emotion": "tired", "keyframes": [{"skill": "loco", "furniture": "bed"}, {"skill": "liedown", "furniture": "bed"}]},
    {"scene": "library", "emotion": "happy", "keyframes": [{"skill": "loco", "furniture": "bookshelf"},
        {"skill": "touch", "caption": "reaches up with the right hand", "furniture": "bookshelf"},
        {"skill": "loco", "furniture": "chair"}, {"skill": "sit", "furniture": "chair"}]},
    {"scene": "living room", "emotion": "sad", "keyframes": [{"skill": "loco", "furniture": "sofa"}, {"skill": "sit", "furniture": "sofa"}]}]})");
  LayoutMatch m = MatchLayouts(ls, db);
  ASSERT_EQ(m.layout.mode, "composed") << m.layout.name << " " << m.layout.cost;
  ASSERT_EQ(m.layout.rooms.size(), 3u);
  EXPECT_EQ(m.layout.rooms[0].type, "bedroom");
  EXPECT_EQ(m.layout.rooms[1].type, "library");
  EXPECT_EQ(m.layout.rooms[2].type, "living room");
  EXPECT_TRUE(m.warnings.empty());
  for (const Binding& b : m.bindings) EXPECT_TRUE(b.placed) << b.note;
  EXPECT_EQ(m.bindings[1].object, m.layout.rooms[0].id + "/bed_0");
  EXPECT_EQ(m.bindings[1].room, m.layout.rooms[0].id);
  // Rooms are disjoint, and every pair of neighbours is connected through its door.
  for (std::size_t a = 0; a < m.layout.rooms.size(); ++a)
    for (std::size_t b = a + 1; b < m.layout.rooms.size(); ++b) {
      const auto& fa = m.layout.rooms[a].footprint;
      const auto& fb = m.layout.rooms[b].footprint;
      EXPECT_TRUE(fa[2] <= fb[0] || fb[2] <= fa[0] || fa[3] <= fb[1] || fb[3] <= fa[1]);
    }
  ASSERT_EQ(m.layout.doors.size(), 2u);
  auto centre = [](const PlanRoom& r) {
    return std::array<double, 2>{0.5 * (r.footprint[0] + r.footprint[2]),
                                 0.5 * (r.footprint[1] + r.footprint[3])};
  };
  // Probe points near the floor's edge (free of furniture in these rooms).
  auto probe = [](const PlanRoom& r) {
    return std::array<double, 2>{r.footprint[0] + 0.3, r.footprint[1] + 0.3};
  };
  (void)centre;
  EXPECT_TRUE(Connected(m.layout, probe(m.layout.rooms[0]), probe(m.layout.rooms[2])));
  PlanLayout closed = m.layout;
  closed.doors.clear();
  Composition walls_only = ComposeRooms({{"a", {0, 0, 4, 4}, {}}, {"b", {0, 0, 4, 4}, {}}});
  closed.walls.clear();
  for (const PlanWall& w : walls_only.walls) closed.walls.push_back(w);
  // Bridge the door gap: with no opening the rooms are not connected.
  PlanWall plug;
  plug.from = {walls_only.doors[0].center[0], 0};
  plug.to = {walls_only.doors[0].center[0], 4};
  closed.walls.push_back(plug);
  closed.rooms.resize(2);
  closed.rooms[0].footprint = walls_only.footprints[0];
  closed.rooms[1].footprint = walls_only.footprints[1];
  EXPECT_FALSE(Connected(closed, probe(closed.rooms[0]), probe(closed.rooms[1])));

  // Materialised: objects sit inside their room, renamed, walls built.
  scene::Scene s = MaterializeLayout(m.layout, HandMadeLoader());
  EXPECT_EQ(s.rooms.size(), 3u);
  EXPECT_EQ(s.objects.size(), 9u);
  EXPECT_FALSE(s.walls.empty());
  std::set<std::string> instances;
  for (const scene::Object& o : s.objects) {
    instances.insert(o.instance);
    const PlanRoom* room = nullptr;
    for (const PlanRoom& r : m.layout.rooms)
      if (r.id == o.room) room = &r;
    ASSERT_NE(room, nullptr);
    scene::Aabb b = ObjectBounds(o);
    EXPECT_GE(b.min.x(), room->footprint[0] - 1e-9);
    EXPECT_LE(b.max.x(), room->footprint[2] + 1e-9);
    EXPECT_GE(b.min.y(), room->footprint[1] - 1e-9);
    EXPECT_LE(b.max.y(), room->footprint[3] + 1e-9);
  }
  for (const Binding& b : m.bindings) {
    if (!b.object.empty()) {
      EXPECT_TRUE(instances.count(b.object)) << b.object;
    }
  }
}

TEST(LayoutTest, DoorsAvoidFurniture) {
  // Something stands right at the middle of the shared wall: the door moves aside.
  Composition c =
      ComposeRooms({{"a", {0, 0, 4, 4}, {{3.5, 1.6, 4.0, 2.4}}}, {"b", {10, 10, 13, 14}, {}}});
  ASSERT_EQ(c.doors.size(), 1u);
  EXPECT_NEAR(c.footprints[1][0], 4.1, 1e-9);
  EXPECT_NEAR(c.offsets[1][0], 4.1 - 10, 1e-9);
  EXPECT_NEAR(c.offsets[1][1], -10, 1e-9);
  double y = c.doors[0].center[1];
  EXPECT_TRUE(y + 0.5 * c.doors[0].width <= 1.6 || y - 0.5 * c.doors[0].width >= 2.4) << y;
  EXPECT_NEAR(c.doors[0].center[0], 4.05, 1e-9);
}

TEST(LayoutTest, DatabaseRoundTripsThroughJson) {
  LayoutDatabase db = HandMadeDatabase();
  auto dir = sims::testing::TempDir("planner_layouts");
  db.Save(dir / "db.json");
  LayoutDatabase back = LayoutDatabase::Load(dir / "db.json");
  ASSERT_EQ(back.layouts.size(), db.layouts.size());
  EXPECT_EQ(back.layouts[1].nodes[0].category, "sofa");
  EXPECT_EQ(back.layouts[1].edges, db.layouts[1].edges);
  std::ofstream(dir / "bad.json")
      << R"({"version": 1, "layouts": [{"name": "x", "nodes": [], "edges": [[0, 3]]}]})";
  try {
    LayoutDatabase::Load(dir / "bad.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.json"));
    EXPECT_THAT(e.what(), HasSubstr("layouts[0].edges[0]"));
  }
}

TEST(LayoutTest, IndexesThreeDFrontFoldersAndReloadsThem) {
  auto front = sims::testing::TestData("scene/front3d/3D-FRONT");
  auto future = sims::testing::TestData("scene/front3d/3D-FUTURE-model");
  auto broken = sims::testing::TempDir("planner_front3d");
  std::ofstream(broken / "broken.json") << "{\"furniture\": 3}";
  std::vector<std::string> log;
  LayoutDatabase db =
      BuildLayoutDatabase(false, false, {front, broken}, future, LayoutConfig{}, &log);
  ASSERT_FALSE(db.layouts.empty());
  std::set<std::string> categories;
  for (const LayoutEntry& e : db.layouts) {
    EXPECT_EQ(e.source.kind, "front3d");
    for (const LayoutNode& n : e.nodes) categories.insert(n.category);
  }
  EXPECT_TRUE(categories.count("sofa")) << ::testing::PrintToString(categories);
  bool skipped = false;
  for (const std::string& l : log) skipped = skipped || l.find("skipped") != std::string::npos;
  EXPECT_TRUE(skipped) << ::testing::PrintToString(log);
  // A plan on it materialises through the 3D-FRONT loader again.
  LongScript ls =
      Script(R"({"keyframes": [{"skill": "loco"}, {"skill": "sit", "furniture": "sofa"}]})");
  LayoutMatch m = MatchLayouts(ls, db);
  ASSERT_TRUE(m.bindings[1].placed);
  scene::Scene s = MaterializeLayout(m.layout);
  bool found = false;
  for (const scene::Object& o : s.objects) found = found || o.instance == m.bindings[1].object;
  EXPECT_TRUE(found) << m.bindings[1].object;
  EXPECT_THROW(BuildLayoutDatabase(false, false, {broken / "nope"}, future, LayoutConfig{}, &log),
               Error);
}

TEST(LayoutTest, BuiltinHouseServesAThemeAndMaterialises) {
  std::vector<std::string> log;
  LayoutDatabase db = BuildLayoutDatabase(true, false, {}, {}, LayoutConfig{}, &log);
  ASSERT_FALSE(db.layouts.empty());
  ScriptDatabase scripts = ScriptDatabase::Load();
  ThemePlanner planner(scripts, Vocabulary::Default(), EmotionLexicon::Default());
  LongScript ls = planner.Plan("a tired person goes to bed, then reads happily in the library",
                               Difficulty::kHard, 3);
  LayoutMatch m = MatchLayouts(ls, db);
  scene::Scene s = MaterializeLayout(m.layout);
  std::set<std::string> instances;
  for (const scene::Object& o : s.objects) instances.insert(o.instance);
  for (std::size_t i = 0; i < m.bindings.size(); ++i) {
    const Binding& b = m.bindings[i];
    if (!b.placed) continue;
    if (!b.object.empty()) {
      EXPECT_TRUE(instances.count(b.object)) << b.object;
    }
  }
  EXPECT_FALSE(m.layout.rooms.empty());
}

}  // namespace
}  // namespace sims::planner
