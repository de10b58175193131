#include "sims/sim/scene_physics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "sims/scene/builtin.h"

namespace sims::sim {
namespace {

using Eigen::Vector3d;
using scene::TriangleMesh;

bool BoxContains(const StaticGeom& g, const Vector3d& p) {
  if (g.type != StaticGeom::Type::kBox) return false;
  const Vector3d q = g.X_WG.inverse() * p;
  return (q.cwiseAbs().array() <= g.half_size.array() + 1e-9).all();
}

bool AnyBoxContains(const std::vector<StaticGeom>& geoms, const Vector3d& p) {
  for (const auto& g : geoms)
    if (BoxContains(g, p)) return true;
  return false;
}

// A closed, connected L-shaped seat+back (profile in xz extruded along y): one piece that is
// clearly not convex.
TriangleMesh LChair() {
  const std::vector<Eigen::Vector2d> profile = {{0, 0},     {0.5, 0}, {0.5, 0.1}, {0.1, 0.1},
                                                {0.1, 0.6}, {0, 0.6}, {0, 0.1}};
  TriangleMesh m;
  for (double y : {-0.2, 0.2})
    for (const auto& p : profile) m.vertices.emplace_back(p.x(), y, p.y());
  const int n = static_cast<int>(profile.size());
  // Caps (the profile split at vertex 6 = (0, 0.1)).
  const int caps[5][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 6}, {6, 3, 4}, {6, 4, 5}};
  for (const auto& t : caps) {
    m.triangles.emplace_back(t[0], t[2], t[1]);
    m.triangles.emplace_back(n + t[0], n + t[1], n + t[2]);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(i, j, n + j);
    m.triangles.emplace_back(i, n + j, n + i);
  }
  return m;
}

TEST(ScenePhysicsTest, BoxesConvexMeshesAndVoxelDecomposition) {
  // An axis-aligned and a rotated box become single box geoms.
  TriangleMesh box = TriangleMesh::Box({0, 0, 0}, {1, 2, 0.5});
  auto g = CompileMeshGeometry(box, "b");
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g[0].type, StaticGeom::Type::kBox);
  EXPECT_TRUE(g[0].X_WG.translation().isApprox(Vector3d(0.5, 1, 0.25)));
  Eigen::Affine3d R(Eigen::AngleAxisd(0.5, Vector3d::UnitZ()));
  g = CompileMeshGeometry(box.Transformed(R), "r");
  ASSERT_EQ(g.size(), 1u);
  ASSERT_EQ(g[0].type, StaticGeom::Type::kBox);
  EXPECT_NEAR(g[0].half_size.prod(), 0.5 * 1 * 0.25, 1e-9);
  EXPECT_TRUE(BoxContains(g[0], R * Vector3d(0.9, 1.9, 0.4)));
  EXPECT_FALSE(BoxContains(g[0], R * Vector3d(1.1, 1.0, 0.2)));
  // A cylinder is convex but not a box.
  g = CompileMeshGeometry(TriangleMesh::Cylinder({0, 0, 0}, 0.2, 0.5), "c");
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g[0].type, StaticGeom::Type::kConvexMesh);
  // A flat quad gets thickness below it.
  TriangleMesh quad;
  quad.vertices = {{0, 0, 0.3}, {1, 0, 0.3}, {1, 1, 0.3}, {0, 1, 0.3}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  g = CompileMeshGeometry(quad, "q");
  ASSERT_EQ(g.size(), 1u);
  ASSERT_EQ(g[0].type, StaticGeom::Type::kConvexMesh);
  double zmin = 1e9, zmax = -1e9;
  for (const auto& v : g[0].vertices) zmin = std::min(zmin, v.z()), zmax = std::max(zmax, v.z());
  EXPECT_NEAR(zmax, 0.3, 1e-12);
  EXPECT_NEAR(zmax - zmin, 0.02, 1e-9);
  // A connected L-shaped seat+back is decomposed: seat and back are solid, the space above
  // the seat in front of the back is free (its convex hull would fill it).
  const TriangleMesh l = LChair();
  ASSERT_TRUE(l.IsClosed());
  ASSERT_EQ(l.EdgeConnectedComponents().size(), 1u);
  EXPECT_FALSE(IsConvexPiece(l, 0.01));
  g = CompileMeshGeometry(l, "l");
  EXPECT_GE(g.size(), 2u);
  EXPECT_LE(g.size(), 6u);
  EXPECT_TRUE(AnyBoxContains(g, {0.3, 0, 0.05}));  // in the seat
  EXPECT_TRUE(AnyBoxContains(g, {0.05, 0, 0.4}));  // in the back
  EXPECT_FALSE(AnyBoxContains(g, {0.3, 0, 0.3}));  // where the sitter goes
}

TEST(ScenePhysicsTest, ChairPartsCompileToSeparateSolids) {
  scene::Scene s;
  s.AddObject(scene::MakeFurniture("chair", scene::DefaultFurnitureParams("chair")));
  const StaticGeometry geometry = CompileSceneGeometry(s);
  // Seat (1) + four legs (4) + back (1), all boxes.
  ASSERT_EQ(geometry.geoms.size(), 6u);
  int seat = 0;
  for (const auto& g : geometry.geoms) {
    EXPECT_EQ(g.type, StaticGeom::Type::kBox);
    seat += g.name.find("/seat surface#0/") != std::string::npos;
  }
  EXPECT_EQ(seat, 1);
  ScenePhysicsOptions skip;
  skip.skip_categories = {"chair"};
  EXPECT_TRUE(CompileSceneGeometry(s, skip).geoms.empty());
  ScenePhysicsOptions bad;
  bad.voxel_size = 0;
  EXPECT_THROW(CompileSceneGeometry(s, bad), Error);
}

TEST(ScenePhysicsTest, HouseCompilesIntoAMujocoModel) {
  const scene::Scene house = scene::BuiltinHouse();
  const StaticGeometry geometry = CompileSceneGeometry(house);
  EXPECT_GT(geometry.geoms.size(), 100u);
  const MjModelPtr model = BuildModel(geometry);
  const MjModelPtr bare = BuildModel({});
  EXPECT_EQ(model->ngeom, static_cast<int>(geometry.geoms.size()) + bare->ngeom);
}

// Humanoid dropped in a sitting pose onto a chair seat, holding the pose with its PD servos.
TEST(ScenePhysicsTest, SittingHumanoidRestsOnTheSeat) {
  scene::Scene s;
  s.AddObject(scene::MakeFurniture("chair", scene::DefaultFurnitureParams("chair")));
  const double seat_top = s.objects[0].FindPart("seat surface")->mesh.Bounds().max.z();
  const StaticGeometry geometry = CompileSceneGeometry(s);
  const MjModelPtr model = BuildModel(geometry);
  MjDataPtr data = MakeData(model.get());
  const mjModel* m = model.get();
  mjData* d = data.get();
  auto joint_qpos = [&](const char* name) {
    const int j = mj_name2id(m, mjOBJ_JOINT, name);
    EXPECT_GE(j, 0) << name;
    return m->jnt_qposadr[j];
  };
  // Facing +x (the chair's front), pelvis over the back half of the seat, thighs (radius
  // 0.055 m below the hip) 2 cm above the seat.
  d->qpos[0] = -0.06;
  d->qpos[1] = 0.0;
  d->qpos[2] = seat_top + 0.055 + 0.02;
  d->qpos[3] = 1.0;
  for (const char* hip : {"right_hip_y", "left_hip_y"}) d->qpos[joint_qpos(hip)] = -M_PI / 2;
  for (const char* knee : {"right_knee", "left_knee"}) d->qpos[joint_qpos(knee)] = M_PI / 2;
  // Forearms forward (hands off the seat, as when resting them in front of the body).
  for (const char* elbow : {"right_elbow", "left_elbow"}) d->qpos[joint_qpos(elbow)] = -M_PI / 2;
  mj_forward(m, d);
  ASSERT_EQ(m->nu, 28);
  // Actuators follow the hinge order, so the PD targets are the hinge angles.
  for (int i = 0; i < m->nu; ++i) d->ctrl[i] = d->qpos[m->jnt_qposadr[m->actuator_trnid[2 * i]]];
  const int pelvis = mj_name2id(m, mjOBJ_GEOM, "pelvis");
  ASSERT_GE(pelvis, 0);
  const int steps = static_cast<int>(2.0 / m->opt.timestep);
  for (int i = 0; i < steps; ++i) mj_step(m, d);
  const double lowest = d->geom_xpos[3 * pelvis + 2] - m->geom_size[3 * pelvis];
  EXPECT_NEAR(lowest, seat_top, 0.05) << "pelvis bottom " << lowest << ", seat top " << seat_top;
  EXPECT_GT(lowest, seat_top - 0.02) << "pelvis sank into the seat";
  // Still above the seat footprint and at rest.
  EXPECT_LT(std::abs(d->qpos[0]), 0.23);
  EXPECT_LT(std::abs(d->qpos[1]), 0.23);
  double speed = 0;
  for (int i = 0; i < 3; ++i) speed += d->qvel[i] * d->qvel[i];
  EXPECT_LT(std::sqrt(speed), 0.05);
  // Supported by the seat: some body geom touches a seat geom.
  bool seat_contact = false;
  for (int c = 0; c < d->ncon; ++c) {
    for (int k = 0; k < 2; ++k) {
      const char* name =
          mj_id2name(m, mjOBJ_GEOM, k == 0 ? d->contact[c].geom1 : d->contact[c].geom2);
      if (name && std::string(name).find("seat surface") != std::string::npos) seat_contact = true;
    }
  }
  EXPECT_TRUE(seat_contact);
}

}  // namespace
}  // namespace sims::sim
