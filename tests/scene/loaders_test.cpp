#include "sims/scene/loaders.h"

#include <cstdlib>
#include <fstream>
#include <map>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/test_util.h"
#include "sims/core/environment.h"
#include "sims/core/error.h"
#include "sims/scene/builtin.h"

namespace sims::scene {
namespace {

using Eigen::Vector3d;
using sims::testing::TempDir;
using sims::testing::TestData;
namespace fs = std::filesystem;

// Runs `f`, expecting a sims::Error whose message contains every fragment.
template <class F>
void ExpectError(F f, std::vector<std::string> fragments) {
  try {
    f();
    ADD_FAILURE() << "no error thrown";
  } catch (const Error& e) {
    for (const auto& frag : fragments)
      EXPECT_NE(std::string(e.what()).find(frag), std::string::npos)
          << "'" << frag << "' not in: " << e.what();
  }
}

void WriteText(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

nlohmann::json ReadJ(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

void WriteJ(const fs::path& p, const nlohmann::json& j) { WriteText(p, j.dump(1)); }

// ---------------------------------------------------------------- generic meshes

TEST(MeshLoaderTest, ObjObjectsYUpToZUpWithCategories) {
  MeshLoadOptions o;
  o.category_table = TestData("scene/two_objects_categories.json").string();
  const Scene s = LoadMeshScene(TestData("scene/two_objects.obj"), o);
  ASSERT_EQ(s.objects.size(), 2u);
  const Object* chair = s.FindObject("chair_a");
  ASSERT_NE(chair, nullptr);
  EXPECT_EQ(chair->category, "chair");
  EXPECT_EQ(s.FindObject("table_b")->category, "table");
  // OBJ is Y-up: y in [0, 0.9] becomes z, z in [1, 2] becomes -y.
  const Aabb b = chair->Bounds();
  // (Assimp reads single-precision floats.)
  EXPECT_NEAR(b.min.z(), 0.0, 1e-6);
  EXPECT_NEAR(b.max.z(), 0.9, 1e-6);
  EXPECT_NEAR(b.min.y(), -2.0, 1e-6);
  EXPECT_NEAR(b.max.y(), -1.0, 1e-6);
  EXPECT_EQ(chair->parts.size(), 1u);
  EXPECT_EQ(chair->parts[0].points.size(), static_cast<std::size_t>(Object::kDefaultPointsPerPart));
  // Explicit z-up and unit scale.
  o.up_axis = "z";
  o.unit_scale = 0.5;
  o.category_table.clear();
  const Scene z = LoadMeshScene(TestData("scene/two_objects.obj"), o);
  const Aabb bz = z.FindObject("chair_a")->Bounds();
  EXPECT_NEAR(bz.max.y(), 0.45, 1e-6);
  EXPECT_NEAR(bz.max.z(), 1.0, 1e-6);
  EXPECT_EQ(z.FindObject("chair_a")->category, "object");
  // One object for the whole file.
  o.split = "single";
  EXPECT_EQ(LoadMeshScene(TestData("scene/two_objects.obj"), o).objects.size(), 1u);
}

// Real files from Debian's assimp-testmodels in several formats.
TEST(MeshLoaderTest, ReadsCommonFormats) {
  const fs::path models = "/usr/share/assimp/models";
  for (const char* file : {"glTF2/BoxTextured-glTF/BoxTextured.gltf", "FBX/box.fbx",
                           "Collada/COLLADA.dae", "PLY/cube.ply", "BLEND/box.blend"}) {
    const Scene s = LoadMeshScene(models / file);
    EXPECT_GE(s.objects.size(), 1u) << file;
    EXPECT_GT(s.TriangleCount(), 0u) << file;
  }
  // The glTF box is a unit cube; PLY is Z-up and kept as is.
  const Aabb b = LoadMeshScene(models / "glTF2/BoxTextured-glTF/BoxTextured.gltf").Bounds();
  EXPECT_NEAR(b.size().x(), 1.0, 1e-6);
  EXPECT_NEAR(LoadMeshScene(models / "PLY/cube.ply").Bounds().max.z(), 1.0, 1e-6);
}

TEST(MeshLoaderTest, BadInput) {
  ExpectError([] { LoadMeshScene("/nonexistent/room.obj"); },
              {"/nonexistent/room.obj", "no such file"});
  const fs::path dir = TempDir("mesh_bad");
  WriteText(dir / "empty.obj", "# nothing here\n");
  ExpectError([&] { LoadMeshScene(dir / "empty.obj"); }, {"empty.obj"});
  WriteText(dir / "garbage.ply", "this is not a ply file\n");
  ExpectError([&] { LoadMeshScene(dir / "garbage.ply"); }, {"garbage.ply"});
  MeshLoadOptions o;
  o.up_axis = "w";
  ExpectError([&] { LoadMeshScene(TestData("scene/two_objects.obj"), o); }, {"up_axis"});
  WriteText(dir / "table.json", R"({"categories": [{"pattern": "(", "category": "chair"}]})");
  ExpectError([&] { CategoryTable::Load(dir / "table.json"); },
              {"table.json", "categories[0].pattern"});
  WriteText(dir / "table2.json", R"({"categories": [{"pattern": "x"}]})");
  ExpectError([&] { CategoryTable::Load(dir / "table2.json"); }, {"categories[0].category"});
}

// ---------------------------------------------------------------- MORSE (Debian data)

TEST(MorseLoaderTest, ApartmentHasCategorisedFurnitureAndWalls) {
  const Scene s = LoadMorseApartment();
  std::map<std::string, int> counts;
  int categorised = 0;
  for (const auto& o : s.objects) {
    ++counts[o.category];
    categorised += o.category != "object";
  }
  EXPECT_GE(categorised, 10);
  for (const std::string c : {"bed", "sofa", "armchair", "chair", "table", "desk", "shelf"})
    EXPECT_GE(counts[c], 1) << c;
  EXPECT_EQ(counts["chair"], 4);
  EXPECT_FALSE(s.walls.empty());
  // Z-up metres: furniture stands on the floor and the bed is about 0.8 m tall.
  const Object& bed = s.objects[s.ObjectsOfCategory("bed")[0]];
  EXPECT_NEAR(bed.Bounds().min.z(), 0.0, 0.02);
  EXPECT_NEAR(bed.Bounds().max.z(), 0.8, 0.05);
  EXPECT_GE(bed.parts.size(), 2u);  // one part per material
  // The "Plane" floor and Blender lamps and helper boxes are not objects.
  EXPECT_EQ(s.FindObject("Plane"), nullptr);
  EXPECT_EQ(s.FindObject("IKEAShelf")->parts.size(), 2u);
}

TEST(MorseLoaderTest, FurniturePropsAndBadDataDir) {
  const Scene s = LoadMorseFurniture();
  int categorised = 0;
  for (const auto& o : s.objects) categorised += o.category != "object";
  EXPECT_GE(categorised, 25);
  EXPECT_FALSE(s.ObjectsOfCategory("wardrobe").empty());
  const Environment saved = InstalledEnvironment();
  Environment moved = saved;
  moved.morse_dir = "/nonexistent/morse";
  InstallEnvironment(moved);
  ExpectError([] { LoadMorseApartment(); }, {"apartment.blend", "morse-simulator-data"});
  InstallEnvironment(saved);
}

// ---------------------------------------------------------------- 3D-FRONT

TEST(Front3DLoaderTest, HouseWithFurnitureRoomsAndWalls) {
  const fs::path root = TestData("scene/front3d");
  const Scene s = LoadFront3D(root / "3D-FRONT/house.json", root / "3D-FUTURE-model");
  ASSERT_EQ(s.objects.size(), 2u);  // the third model is missing and skipped
  ASSERT_EQ(s.rooms.size(), 1u);
  EXPECT_EQ(s.rooms[0].type, "living room");
  EXPECT_EQ(s.rooms[0].id, "LivingRoom-1");
  const auto chairs = s.ObjectsOfCategory("chair");
  const auto sofas = s.ObjectsOfCategory("sofa");
  ASSERT_EQ(chairs.size(), 1u);
  ASSERT_EQ(sofas.size(), 1u);
  // Chair: Y-up box x [-0.2, 0.2], y [0, 0.9], z [-0.1, 0.3]; rot (x,y,z,w) = 90° about Y,
  // pos (1, 0, -1); then Y-up -> Z-up. Reading the quaternion as (w,x,y,z) would not give this.
  const Aabb c = s.objects[chairs[0]].Bounds();
  EXPECT_TRUE(c.min.isApprox(Vector3d(0.9, 0.8, 0.0), 1e-6)) << c.min.transpose();
  EXPECT_TRUE(c.max.isApprox(Vector3d(1.3, 1.2, 0.9), 1e-6)) << c.max.transpose();
  EXPECT_EQ(s.objects[chairs[0]].room, "LivingRoom-1");
  // Sofa scaled by 2 along x, at (3, 0, -2): x in [2, 4], y (= -z) in [1.55, 2.45].
  const Aabb so = s.objects[sofas[0]].Bounds();
  EXPECT_NEAR(so.min.x(), 2.0, 1e-6);
  EXPECT_NEAR(so.max.x(), 4.0, 1e-6);
  EXPECT_NEAR(so.min.y(), 1.55, 1e-6);
  EXPECT_TRUE(s.objects[sofas[0]].scale.isApprox(Vector3d(2, 1, 1)));
  // Floor polygon spans x [0, 4], y [0, 3]; walls hold the WallInner quad only (no ceiling).
  const Room& r = s.rooms[0];
  EXPECT_EQ(r.floor_polygon.size(), 4u);
  EXPECT_TRUE(r.Contains({3.9, 2.9}));
  EXPECT_FALSE(r.Contains({3.9, 3.1}));
  EXPECT_EQ(s.walls.triangles.size(), 2u);
  EXPECT_NEAR(s.walls.Bounds().max.z(), 2.5, 1e-9);
  EXPECT_NEAR(s.walls.Bounds().min.y(), 3.0, 1e-9);
}

TEST(Front3DLoaderTest, BadInput) {
  const fs::path root = TestData("scene/front3d");
  const fs::path dir = TempDir("front3d_bad");
  nlohmann::json house = ReadJ(root / "3D-FRONT/house.json");
  auto no_furniture = house;
  no_furniture.erase("furniture");
  WriteJ(dir / "a.json", no_furniture);
  ExpectError([&] { LoadFront3D(dir / "a.json", root / "3D-FUTURE-model"); },
              {"a.json", "furniture"});
  auto bad_rot = house;
  bad_rot["scene"]["room"][0]["children"][0]["rot"] = {0, 1, 0};
  WriteJ(dir / "b.json", bad_rot);
  ExpectError([&] { LoadFront3D(dir / "b.json", root / "3D-FUTURE-model"); },
              {"b.json", "scene.room[0].children[0].rot", "4 numbers"});
  auto bad_faces = house;
  bad_faces["mesh"][0]["faces"] = {0, 1, 9};
  WriteJ(dir / "c.json", bad_faces);
  ExpectError([&] { LoadFront3D(dir / "c.json", root / "3D-FUTURE-model"); },
              {"c.json", "mesh[0].faces"});
  ExpectError([&] { LoadFront3D(root / "3D-FRONT/house.json", dir / "nowhere"); },
              {"nowhere", "3D-FUTURE-model"});
  Front3DOptions strict;
  strict.skip_missing_models = false;
  ExpectError([&] { LoadFront3D(root / "3D-FRONT/house.json", root / "3D-FUTURE-model", strict); },
              {"missing-model", "raw_model.obj"});
  WriteText(dir / "broken.json", "{\"furniture\": [");
  ExpectError([&] { LoadFront3D(dir / "broken.json", root / "3D-FUTURE-model"); }, {"broken.json"});
}

// ---------------------------------------------------------------- ScanNet

TEST(ScanNetLoaderTest, SegmentsBecomeObjectsAlignedWithTheFloorAtZero) {
  const Scene s = LoadScanNet(TestData("scene/scannet/scene0000_00"));
  EXPECT_EQ(s.name, "scene0000_00");
  ASSERT_EQ(s.objects.size(), 1u);  // floor ignored, wall to walls
  const Object& chair = s.objects[0];
  EXPECT_EQ(chair.category, "chair");
  EXPECT_FALSE(s.walls.empty());
  // Box x [0.5, 1], y [0.2, 0.4], z [0.1, 0.6]; axisAlignment rotates 90° about z and moves
  // by (1, 2, 0); the floor (z = 0.1) moves to 0.
  const Aabb b = chair.Bounds();
  EXPECT_TRUE(b.min.isApprox(Vector3d(0.6, 2.5, 0.0), 1e-6)) << b.min.transpose();
  EXPECT_TRUE(b.max.isApprox(Vector3d(0.8, 3.0, 0.5), 1e-6)) << b.max.transpose();
  EXPECT_EQ(chair.parts[0].mesh.triangles.size(), 12u);
  // The same scan as a binary PLY.
  const fs::path dir = TempDir("scannet_bin");
  for (const auto& e : fs::directory_iterator(TestData("scene/scannet/scene0000_00")))
    fs::copy(e.path(), dir / e.path().filename());
  const TriangleMesh ascii = [&] {
    // Re-read the ASCII file's numbers to write them back in binary.
    std::ifstream in(TestData("scene/scannet/scene0000_00/scene0000_00_vh_clean_2.ply"));
    std::string line;
    int nv = 0, nf = 0;
    while (std::getline(in, line) && line != "end_header") {
      if (line.rfind("element vertex", 0) == 0) nv = std::stoi(line.substr(15));
      if (line.rfind("element face", 0) == 0) nf = std::stoi(line.substr(13));
    }
    TriangleMesh m;
    for (int i = 0; i < nv; ++i) {
      double x, y, z;
      int r, g, bb, a;
      in >> x >> y >> z >> r >> g >> bb >> a;
      m.vertices.emplace_back(x, y, z);
    }
    for (int i = 0; i < nf; ++i) {
      int n, a, b2, c;
      in >> n >> a >> b2 >> c;
      m.triangles.emplace_back(a, b2, c);
    }
    return m;
  }();
  {
    std::ofstream out(dir / "scene0000_00_vh_clean_2.ply", std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << ascii.vertices.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
           "property uchar green\nproperty uchar blue\nproperty uchar alpha\nelement face "
        << ascii.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& v : ascii.vertices) {
      const float f[3] = {static_cast<float>(v.x()), static_cast<float>(v.y()),
                          static_cast<float>(v.z())};
      const unsigned char c[4] = {1, 2, 3, 255};
      out.write(reinterpret_cast<const char*>(f), sizeof(f));
      out.write(reinterpret_cast<const char*>(c), sizeof(c));
    }
    for (const auto& t : ascii.triangles) {
      const unsigned char n = 3;
      const int idx[3] = {t[0], t[1], t[2]};
      out.write(reinterpret_cast<const char*>(&n), 1);
      out.write(reinterpret_cast<const char*>(idx), sizeof(idx));
    }
  }
  const Scene bin = LoadScanNet(dir / "scene0000_00_vh_clean_2.ply");
  ASSERT_EQ(bin.objects.size(), 1u);
  EXPECT_TRUE(bin.objects[0].Bounds().max.isApprox(b.max, 1e-6));
}

TEST(ScanNetLoaderTest, BadInput) {
  const fs::path src = TestData("scene/scannet/scene0000_00");
  auto copy = [&](const std::string& tag) {
    const fs::path dir = TempDir(tag);
    for (const auto& e : fs::directory_iterator(src)) fs::copy(e.path(), dir / e.path().filename());
    return dir;
  };
  const fs::path a = copy("scannet_segs");
  auto segs = ReadJ(a / "scene0000_00_vh_clean_2.0.010000.segs.json");
  segs["segIndices"].erase(segs["segIndices"].begin());
  WriteJ(a / "scene0000_00_vh_clean_2.0.010000.segs.json", segs);
  ExpectError([&] { LoadScanNet(a); }, {"segs.json", "segIndices", "one segment id per vertex"});
  const fs::path b = copy("scannet_agg");
  fs::remove(b / "scene0000_00.aggregation.json");
  ExpectError([&] { LoadScanNet(b); }, {"aggregation", "no such file"});
  const fs::path c = copy("scannet_label");
  auto agg = ReadJ(c / "scene0000_00.aggregation.json");
  agg["segGroups"][0].erase("label");
  WriteJ(c / "scene0000_00.aggregation.json", agg);
  ExpectError([&] { LoadScanNet(c); }, {"aggregation.json", "segGroups[0].label"});
  const fs::path d = copy("scannet_ply");
  WriteText(d / "scene0000_00_vh_clean_2.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  ExpectError([&] { LoadScanNet(d); }, {"vh_clean_2.ply", "vertex_indices"});
  ExpectError([&] { LoadScanNet(TempDir("scannet_empty")); }, {"_vh_clean_2.ply"});
}

// ---------------------------------------------------------------- PartNet and ScenePlan

TEST(PartNetLoaderTest, LeavesBecomeNamedPartsInZUp) {
  const Object o = LoadPartNet(TestData("scene/partnet/101"));
  EXPECT_EQ(o.category, "chair");
  ASSERT_EQ(o.parts.size(), 3u);
  const Part* seat = o.FindPartByKey("seat_soft_surface2");
  ASSERT_NE(seat, nullptr);
  EXPECT_EQ(seat->name, "seat soft surface");
  EXPECT_EQ(seat->id, 2);
  EXPECT_EQ(o.FindPart("leg")->mesh.triangles.size(), 24u);  // two leg objs
  EXPECT_NE(o.FindPartByKey("back_surface4"), nullptr);
  // Y-up seat y in [0.40, 0.45] becomes z; back z in [-0.25, -0.2] becomes y in [0.2, 0.25].
  EXPECT_NEAR(seat->mesh.Bounds().max.z(), 0.45, 1e-6);
  EXPECT_NEAR(o.FindPart("back surface")->mesh.Bounds().min.y(), 0.2, 1e-6);
  EXPECT_EQ(seat->points.size(), static_cast<std::size_t>(Object::kDefaultPointsPerPart));
}

TEST(PartNetLoaderTest, ScenePlanAppliesRotateScaleDropTransfer) {
  const fs::path plan = TestData("scene/sceneplan.json");
  EXPECT_EQ(ScenePlanIds(plan), (std::vector<std::string>{"0000", "0001"}));
  const Scene s = LoadScenePlan(plan, TestData("scene/partnet"), "0000");
  ASSERT_EQ(s.objects.size(), 1u);
  const Object& chair = s.objects[0];
  EXPECT_EQ(chair.instance, "chair000");
  EXPECT_EQ(chair.category, "chair");
  // rotate = [Rx(90°)], then [Rz(-90°)]: v -> (-z, -x, y). Scale 2 about the vertex centroid
  // (x̄ = 0.05625, ȳ = 0), drop to z = 0, transfer (1, 2, 0).
  const Aabb seat = chair.FindPartByKey("seat_soft_surface2")->mesh.Bounds();
  EXPECT_NEAR(seat.max.z(), 0.9, 1e-6);
  EXPECT_NEAR(seat.min.x(), 0.44375, 1e-6);
  EXPECT_NEAR(seat.max.x(), 1.44375, 1e-6);
  EXPECT_NEAR(seat.min.y(), 1.5, 1e-6);
  EXPECT_NEAR(seat.max.y(), 2.5, 1e-6);
  const Aabb back = chair.FindPart("back surface")->mesh.Bounds();
  EXPECT_NEAR(back.min.x(), 1.34375, 1e-6);
  EXPECT_NEAR(chair.Bounds().min.z(), 0.0, 1e-9);
  // Points moved with the meshes.
  for (const auto& p : chair.parts[0].points) EXPECT_GE(p.z(), -1e-9);
  // Default plan id = the first.
  EXPECT_EQ(LoadScenePlan(plan, TestData("scene/partnet")).name, "sceneplan#0000");
}

TEST(PartNetLoaderTest, BadInput) {
  const fs::path dir = TempDir("partnet_bad");
  fs::copy(TestData("scene/partnet/101"), dir / "101", fs::copy_options::recursive);
  fs::remove(dir / "101/objs/new-1.obj");
  ExpectError([&] { LoadPartNet(dir / "101"); }, {"result.json", "back_surface", "new-1.obj"});
  ExpectError([&] { LoadPartNet(dir / "nothing"); }, {"result.json"});
  WriteText(dir / "102/result.json",
            R"([{"name": "chair", "id": 0, "children": [{"name": "leg", "objs": ["a"]}]}])");
  ExpectError([&] { LoadPartNet(dir / "102"); }, {"result.json", "[0].children[0]", "id"});
  const fs::path plan = TestData("scene/sceneplan.json");
  ExpectError([&] { LoadScenePlan(plan, TestData("scene/partnet"), "9999"); },
              {"sceneplan.json", "9999", "0000, 0001"});
  ExpectError([&] { LoadScenePlan(plan, dir / "missing_root", "0000"); },
              {"0000.obj.000.id", "result.json"});
  auto j = ReadJ(plan);
  j["0000"]["obj"]["000"]["transfer"] = {1, 2};
  WriteJ(dir / "plan.json", j);
  ExpectError([&] { LoadScenePlan(dir / "plan.json", TestData("scene/partnet"), "0000"); },
              {"plan.json", "0000.obj.000.transfer", "3 numbers"});
  j = ReadJ(plan);
  j["0000"]["obj"]["000"]["rotate"] = {{1, 2}};
  WriteJ(dir / "plan2.json", j);
  ExpectError([&] { LoadScenePlan(dir / "plan2.json", TestData("scene/partnet"), "0000"); },
              {"0000.obj.000.rotate[0]"});
}

// ---------------------------------------------------------------- dispatch

TEST(SceneFileTest, DispatchesByExtensionAndContent) {
  EXPECT_EQ(LoadSceneFile("house").rooms.size(), 4u);
  EXPECT_EQ(LoadSceneFile("builtin:bedroom").name, "bedroom");
  EXPECT_EQ(LoadSceneFile(TestData("scene/partnet/101").string()).objects.size(), 1u);
  EXPECT_EQ(LoadSceneFile(TestData("scene/scannet/scene0000_00").string()).name, "scene0000_00");
  EXPECT_EQ(LoadSceneFile(TestData("scene/front3d/3D-FRONT/house.json").string()).objects.size(),
            2u);
  const Environment saved = InstalledEnvironment();
  Environment partnet = saved;
  partnet.partnet_dir = TestData("scene/partnet");
  InstallEnvironment(partnet);
  EXPECT_EQ(LoadSceneFile(TestData("scene/sceneplan.json").string() + "#0001").name,
            "sceneplan#0001");
  InstallEnvironment(saved);
  EXPECT_EQ(LoadSceneFile(TestData("scene/two_objects.obj").string()).objects.size(), 2u);
  ExpectError([] { LoadSceneFile("castle"); }, {"castle", "house"});
  ExpectError([] { LoadSceneFile("/no/such/scene.glb"); }, {"/no/such/scene.glb", "no such file"});
  const fs::path dir = TempDir("scene_file");
  WriteText(dir / "other.json", R"({"hello": 1})");
  ExpectError([&] { LoadSceneFile((dir / "other.json").string()); },
              {"other.json", "3D-FRONT", "ScenePlan"});
}

// Inputs the fuzzers (tools/fuzz.sh) found: each loads or fails with a sims::Error, nothing
// else; the sanitizer job runs this with leak checking (assimp_leak.obj: Assimp's own OBJ
// importer leaks on it, suppressed in cmake/lsan.supp).
TEST(FuzzRegressionTest, MeshInputsLoadOrFailClearly) {
  for (const char* name : {"mesh_obj/assimp_leak.obj"}) {
    SCOPED_TRACE(name);
    try {
      const TriangleMesh mesh =
          LoadTriangleMesh(sims::testing::TestData(std::string("fuzz/") + name));
      EXPECT_FALSE(mesh.empty());
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("assimp_leak.obj"), std::string::npos) << e.what();
    }
  }
  // Assimp's PLY importer loops for minutes on the first and aborts on an assertion in its
  // triangulation on the second; PLY now goes through our own reader, which rejects both.
  for (const char* name : {"assimp_hang.ply", "assimp_assert.ply"})
    ExpectError(
        [&] { LoadTriangleMesh(sims::testing::TestData(std::string("fuzz/mesh_ply/") + name)); },
        {name});
}

}  // namespace
}  // namespace sims::scene
