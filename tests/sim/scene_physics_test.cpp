#include "sims/sim/scene_physics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "sims/scene/builtin.h"
#include "sims/scene/loaders.h"
#include "sims/scene/ray_caster.h"

namespace sims::sim {
namespace {

using Eigen::Vector3d;
using scene::TriangleMesh;

bool BoxContains(const humanoid::StaticGeom& g, const Vector3d& p) {
  if (g.type != humanoid::StaticGeom::Type::kBox) return false;
  const Vector3d q = g.X_WG.inverse() * p;
  return (q.cwiseAbs().array() <= g.half_size.array() + 1e-9).all();
}

bool AnyBoxContains(const std::vector<humanoid::StaticGeom>& geoms, const Vector3d& p) {
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
  EXPECT_EQ(g[0].type, humanoid::StaticGeom::Type::kBox);
  EXPECT_TRUE(g[0].X_WG.translation().isApprox(Vector3d(0.5, 1, 0.25)));
  Eigen::Affine3d R(Eigen::AngleAxisd(0.5, Vector3d::UnitZ()));
  g = CompileMeshGeometry(box.Transformed(R), "r");
  ASSERT_EQ(g.size(), 1u);
  ASSERT_EQ(g[0].type, humanoid::StaticGeom::Type::kBox);
  EXPECT_NEAR(g[0].half_size.prod(), 0.5 * 1 * 0.25, 1e-9);
  EXPECT_TRUE(BoxContains(g[0], R * Vector3d(0.9, 1.9, 0.4)));
  EXPECT_FALSE(BoxContains(g[0], R * Vector3d(1.1, 1.0, 0.2)));
  // A cylinder is convex but not a box.
  g = CompileMeshGeometry(TriangleMesh::Cylinder({0, 0, 0}, 0.2, 0.5), "c");
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g[0].type, humanoid::StaticGeom::Type::kConvexMesh);
  // A flat quad gets thickness below it.
  TriangleMesh quad;
  quad.vertices = {{0, 0, 0.3}, {1, 0, 0.3}, {1, 1, 0.3}, {0, 1, 0.3}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  g = CompileMeshGeometry(quad, "q");
  ASSERT_EQ(g.size(), 1u);
  ASSERT_EQ(g[0].type, humanoid::StaticGeom::Type::kConvexMesh);
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
  const humanoid::StaticGeometry geometry = CompileSceneGeometry(s);
  // Seat (1) + four legs (4) + back (1), all boxes.
  ASSERT_EQ(geometry.geoms.size(), 6u);
  int seat = 0;
  for (const auto& g : geometry.geoms) {
    EXPECT_EQ(g.type, humanoid::StaticGeom::Type::kBox);
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
  const humanoid::StaticGeometry geometry = CompileSceneGeometry(house);
  EXPECT_GT(geometry.geoms.size(), 100u);
  // Built-in furniture and walls are made of boxes and cylinders: no voxel decomposition, and
  // each wall box stays one box geom.
  int wall_geoms = 0;
  for (const auto& g : geometry.geoms) {
    if (g.name.rfind("walls/", 0) == 0) {
      ++wall_geoms;
      EXPECT_EQ(g.type, humanoid::StaticGeom::Type::kBox);
    }
  }
  EXPECT_EQ(wall_geoms, static_cast<int>(house.walls.triangles.size() / 12));
  const humanoid::MjModelPtr model = humanoid::BuildModel(geometry);
  const humanoid::MjModelPtr bare = humanoid::BuildModel({});
  const mjModel* m = model.get();
  EXPECT_EQ(m->ngeom, static_cast<int>(geometry.geoms.size()) + bare->ngeom);
  // One static body per object plus one for the walls, so the broad phase can skip far
  // furniture; every geom keeps its world pose (bodies sit at their geoms' centre).
  int static_objects = 0;
  for (const auto& o : house.objects) static_objects += o.is_static ? 1 : 0;
  EXPECT_EQ(m->nbody, bare->nbody + static_objects + 1);
  humanoid::MjDataPtr data = humanoid::MakeData(m);
  mj_forward(m, data.get());
  const mjData* d = data.get();
  int meshes = 0;
  for (const auto& g : geometry.geoms) {
    const int id = mj_name2id(m, mjOBJ_GEOM, g.name.c_str());
    ASSERT_GE(id, 0) << g.name;
    const int body = m->geom_bodyid[id];
    EXPECT_NE(body, 0) << g.name;
    EXPECT_EQ(m->body_weldid[body], 0) << g.name << " must be static";
    const Eigen::Map<const Eigen::Vector3d> p_WG(d->geom_xpos + 3 * id);
    if (g.type == humanoid::StaticGeom::Type::kBox) {
      EXPECT_LT((p_WG - g.X_WG.translation()).norm(), 1e-6) << g.name;
      continue;
    }
    // Convex meshes: MuJoCo re-centres the points; mapped back they are the compiled ones.
    ++meshes;
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R_WG(d->geom_xmat +
                                                                              9 * id);
    const int mesh = m->geom_dataid[id];
    for (int v = 0; v < m->mesh_vertnum[mesh]; ++v) {
      const float* q = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + v);
      const Vector3d p = p_WG + R_WG * Vector3d(q[0], q[1], q[2]);
      double best = 1e9;
      for (const auto& w : g.vertices) best = std::min(best, (w - p).norm());
      EXPECT_LT(best, 1e-4) << g.name;
    }
  }
  EXPECT_GT(meshes, 0);
}

// Drops the humanoid in a sitting pose (hips -90°, knees +90°, forearms forward) with its
// pelvis at (x, y), facing `yaw`, thighs 2 cm above `seat_top`; holds the pose with the PD
// servos for 2 s and reports where the pelvis ended up.
struct SitResult {
  double pelvis_bottom = 0;
  Vector3d root = Vector3d::Zero();
  double root_speed = 0;
  bool seat_contact = false;
};

SitResult DropSitting(const scene::Scene& s, double x, double y, double yaw, double seat_top,
                      const std::string& seat_geom_fragment) {
  const humanoid::StaticGeometry geometry = CompileSceneGeometry(s);
  const humanoid::MjModelPtr model = humanoid::BuildModel(geometry);
  humanoid::MjDataPtr data = humanoid::MakeData(model.get());
  const mjModel* m = model.get();
  mjData* d = data.get();
  auto joint_qpos = [&](const char* name) {
    const int j = mj_name2id(m, mjOBJ_JOINT, name);
    EXPECT_GE(j, 0) << name;
    return m->jnt_qposadr[j];
  };
  d->qpos[0] = x;
  d->qpos[1] = y;
  d->qpos[2] = seat_top + 0.055 + 0.02;  // thigh capsules (radius 0.055) 2 cm above the seat
  d->qpos[3] = std::cos(yaw / 2);
  d->qpos[6] = std::sin(yaw / 2);
  for (const char* hip : {"right_hip_y", "left_hip_y"}) d->qpos[joint_qpos(hip)] = -M_PI / 2;
  for (const char* knee : {"right_knee", "left_knee"}) d->qpos[joint_qpos(knee)] = M_PI / 2;
  // Forearms forward (hands off the seat, as when resting them in front of the body).
  for (const char* elbow : {"right_elbow", "left_elbow"}) d->qpos[joint_qpos(elbow)] = -M_PI / 2;
  mj_forward(m, d);
  EXPECT_EQ(m->nu, 28);
  // Actuators follow the hinge order, so the PD targets are the hinge angles.
  for (int i = 0; i < m->nu; ++i) d->ctrl[i] = d->qpos[m->jnt_qposadr[m->actuator_trnid[2 * i]]];
  const int pelvis = mj_name2id(m, mjOBJ_GEOM, "pelvis");
  EXPECT_GE(pelvis, 0);
  const int steps = static_cast<int>(2.0 / m->opt.timestep);
  for (int i = 0; i < steps; ++i) mj_step(m, d);
  SitResult r;
  r.pelvis_bottom = d->geom_xpos[3 * pelvis + 2] - m->geom_size[3 * pelvis];
  r.root = Vector3d(d->qpos[0], d->qpos[1], d->qpos[2]);
  r.root_speed = Vector3d(d->qvel[0], d->qvel[1], d->qvel[2]).norm();
  for (int c = 0; c < d->ncon; ++c) {
    for (int k = 0; k < 2; ++k) {
      const char* name =
          mj_id2name(m, mjOBJ_GEOM, k == 0 ? d->contact[c].geom1 : d->contact[c].geom2);
      if (name && std::string(name).find(seat_geom_fragment) != std::string::npos)
        r.seat_contact = true;
    }
  }
  return r;
}

TEST(ScenePhysicsTest, SittingHumanoidRestsOnTheSeat) {
  scene::Scene s;
  s.AddObject(scene::MakeFurniture("chair", scene::DefaultFurnitureParams("chair")));
  const double seat_top = s.objects[0].FindPart("seat surface")->mesh.Bounds().max.z();
  // Facing +x (the chair's front), pelvis over the back half of the seat.
  const SitResult r = DropSitting(s, -0.06, 0.0, 0.0, seat_top, "seat surface");
  EXPECT_NEAR(r.pelvis_bottom, seat_top, 0.05)
      << "pelvis bottom " << r.pelvis_bottom << ", seat top " << seat_top;
  EXPECT_GT(r.pelvis_bottom, seat_top - 0.02) << "pelvis sank into the seat";
  // Still above the seat footprint, at rest and touching the seat.
  EXPECT_LT(std::abs(r.root.x()), 0.23);
  EXPECT_LT(std::abs(r.root.y()), 0.23);
  EXPECT_LT(r.root_speed, 0.05);
  EXPECT_TRUE(r.seat_contact);
}

// The same on a real, unsegmented MORSE chair (one connected non-convex mesh, voxel boxes):
// the seat height and the back's side come from down-casts.
TEST(ScenePhysicsTest, SittingOnAVoxelisedMorseChair) {
  const scene::Scene apartment = scene::LoadMorseApartment();
  const scene::Object* chair = apartment.FindObject("IKEA_chair_STEFAN");
  ASSERT_NE(chair, nullptr);
  scene::Scene s;
  s.AddObject(*chair);
  const scene::Aabb b = s.objects[0].Bounds();
  const scene::RayCaster rc(s);
  Eigen::Vector2d back = Eigen::Vector2d::Zero();
  double seat_sum = 0;
  int n_back = 0, n_seat = 0;
  for (double y = b.min.y(); y <= b.max.y(); y += 0.02)
    for (double x = b.min.x(); x <= b.max.x(); x += 0.02) {
      const double h = rc.HeightAt(x, y);
      if (h > 0.7) {
        back += Eigen::Vector2d(x, y);
        ++n_back;
      } else if (h > 0.3) {
        seat_sum += h;
        ++n_seat;
      }
    }
  ASSERT_GT(n_back, 0);
  ASSERT_GT(n_seat, 0);
  const double seat_top = seat_sum / n_seat;
  const Eigen::Vector2d center(b.center().x(), b.center().y());
  const Eigen::Vector2d front = (center - back / n_back).normalized();
  const Eigen::Vector2d p = center + 0.05 * front;
  const SitResult r =
      DropSitting(s, p.x(), p.y(), std::atan2(front.y(), front.x()), seat_top, "IKEA_chair");
  EXPECT_NEAR(r.pelvis_bottom, seat_top, 0.05)
      << "pelvis bottom " << r.pelvis_bottom << ", seat top " << seat_top;
  EXPECT_GT(r.pelvis_bottom, seat_top - 0.02);
  EXPECT_LT((r.root.head<2>() - center).norm(), 0.25);
  EXPECT_TRUE(r.seat_contact);
}

}  // namespace
}  // namespace sims::sim
