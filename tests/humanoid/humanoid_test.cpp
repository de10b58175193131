#include "sims/humanoid/humanoid.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "sims/humanoid/model_builder.h"
#include "sims/humanoid/state.h"

namespace sims::humanoid {
namespace {

constexpr double kDeg = M_PI / 180.0;

class HumanoidTest : public ::testing::Test {
 protected:
  HumanoidTest() : humanoid_(BuildModel()) {}
  Humanoid humanoid_;
};

TEST_F(HumanoidTest, LayoutMatchesAmp) {
  const mjModel* m = humanoid_.model();
  EXPECT_EQ(m->nbody, 1 + kNumBodies);
  EXPECT_EQ(m->nu, kNumDofs);
  EXPECT_EQ(m->nq, 7 + kNumDofs);
  EXPECT_NEAR(m->opt.timestep, 1.0 / 120.0, 1e-9);
  for (int b = 0; b < kNumBodies; ++b) EXPECT_EQ(humanoid_.body_id(b), b + 1) << BodyNames()[b];
  EXPECT_EQ(humanoid_.root_qpos_adr(), 0);
  for (int i = 0; i < kNumDofs; ++i) {
    EXPECT_EQ(humanoid_.dof_qpos_adr(i), 7 + i);
    EXPECT_EQ(humanoid_.actuator_id(i), i) << "actuators follow qpos order";
  }
}

TEST_F(HumanoidTest, GainsAndTorqueLimitsAsListed) {
  struct Expect {
    const char* dof;
    double kp, kd, limit;
  };
  const Expect table[] = {
      {"abdomen_y", 1000, 100, 200},      {"neck_x", 100, 10, 50},
      {"right_shoulder_z", 400, 40, 100}, {"left_elbow", 300, 30, 70},
      {"right_hip_y", 500, 50, 200},      {"left_knee", 500, 50, 150},
      {"right_ankle_x", 400, 40, 90},
  };
  for (const auto& e : table) {
    int i = 0;
    while (std::string(DofNames()[i]) != e.dof) ++i;
    EXPECT_DOUBLE_EQ(humanoid_.kp()[i], e.kp) << e.dof;
    EXPECT_DOUBLE_EQ(humanoid_.kd()[i], e.kd) << e.dof;
    EXPECT_DOUBLE_EQ(humanoid_.torque_limit()[i], e.limit) << e.dof;
  }
}

TEST_F(HumanoidTest, PdMappingAtLimits) {
  float plus[kNumDofs], minus[kNumDofs], beyond[kNumDofs];
  for (int i = 0; i < kNumDofs; ++i) plus[i] = 1.0f, minus[i] = -1.0f, beyond[i] = 5.0f;
  double tp[kNumDofs], tm[kNumDofs], tb[kNumDofs];
  humanoid_.ActionToTargets(plus, tp);
  humanoid_.ActionToTargets(minus, tm);
  humanoid_.ActionToTargets(beyond, tb);
  // ASE's PD action ranges: abdomen 108°, neck 72°, shoulder 180°, hip 168°, ankle 66°,
  // elbow −80° ± 112°, knee +80° ± 112°.
  EXPECT_NEAR(tp[0], 108 * kDeg, 1e-9);
  EXPECT_NEAR(tm[0], -108 * kDeg, 1e-9);
  EXPECT_NEAR(tp[3], 72 * kDeg, 1e-9);
  EXPECT_NEAR(tp[6], M_PI, 1e-9);
  EXPECT_NEAR(tp[9], 32 * kDeg, 1e-9);
  EXPECT_NEAR(tm[9], -192 * kDeg, 1e-9);
  EXPECT_NEAR(tp[15], 168 * kDeg, 1e-9);
  EXPECT_NEAR(tm[17], -32 * kDeg, 1e-9);
  EXPECT_NEAR(tp[17], 192 * kDeg, 1e-9);
  EXPECT_NEAR(tp[19], 66 * kDeg, 1e-9);
  for (int i = 0; i < kNumDofs; ++i) EXPECT_DOUBLE_EQ(tb[i], tp[i]) << "actions are clamped";
  float back[kNumDofs];
  humanoid_.TargetsToAction(tp, back);
  for (int i = 0; i < kNumDofs; ++i) EXPECT_NEAR(back[i], 1.0f, 1e-6);
}

TEST_F(HumanoidTest, ContactJointsResolve) {
  EXPECT_EQ(ContactJointByName("right_hand"), kCjRightHand);
  EXPECT_EQ(ContactJointBodies()[kCjLeftKnee], kLeftShin);
  EXPECT_THROW(ContactJointByName("tail"), Error);
}

double PelvisHeightAfter(const Humanoid& h, double seconds, bool actuated) {
  MjDataPtr d = MakeData(h.model());
  mjModel* m = mj_copyModel(nullptr, h.model());
  if (!actuated) m->opt.disableflags |= mjDSBL_ACTUATION;
  for (int i = 0; i < kNumDofs; ++i) d->ctrl[i] = 0.0;  // PD targets = standing default pose
  const int steps = static_cast<int>(seconds / m->opt.timestep);
  for (int t = 0; t < steps; ++t) mj_step(m, d.get());
  const double z = d->qpos[2];
  mj_deleteModel(m);
  return z;
}

TEST_F(HumanoidTest, StandsWithPdAndCollapsesWithout) {
  EXPECT_GT(PelvisHeightAfter(humanoid_, 1.0, true), 0.8);
  EXPECT_LT(PelvisHeightAfter(humanoid_, 5.0, false), 0.4);
}

TEST_F(HumanoidTest, PoseRoundTripThroughMjData) {
  MjDataPtr d = MakeData(humanoid_.model());
  HumanoidPose p;
  p.root_pos = {1, 2, 0.9};
  p.root_rot = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 0.3, 1).normalized());
  p.root_lin_vel = {0.1, -0.2, 0.3};
  p.root_ang_vel = {0.4, 0.5, -0.6};
  for (int i = 0; i < kNumDofs; ++i) p.dof_pos[i] = 0.01 * i, p.dof_vel[i] = -0.02 * i;
  WritePose(humanoid_, p, d.get());
  HumanoidPose q;
  ReadPose(humanoid_, d.get(), &q);
  EXPECT_TRUE(q.root_pos.isApprox(p.root_pos));
  EXPECT_TRUE(q.root_rot.isApprox(p.root_rot));
  EXPECT_TRUE(q.root_ang_vel.isApprox(p.root_ang_vel, 1e-12));
  EXPECT_TRUE(q.dof_vel.isApprox(p.dof_vel));
  // The root body's angular velocity from FK equals the pose's world angular velocity.
  BodyStates bs;
  ForwardKinematics(humanoid_, p, d.get(), &bs);
  EXPECT_TRUE(bs.ang_vel[kPelvis].isApprox(p.root_ang_vel, 1e-9));
  EXPECT_TRUE(bs.lin_vel[kPelvis].isApprox(p.root_lin_vel, 1e-9));
}

TEST(ModelBuilderTest, BadModelsGiveClearErrors) {
  EXPECT_THROW(BuildModel({}, "/nonexistent/humanoid.xml"), Error);
  try {
    ComposeModelXml("<mujoco/>", {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("SIMS_SCENE_ASSETS"), std::string::npos);
  }
  StaticGeometry g;
  StaticGeom box;
  box.name = "table_top";
  box.X_WG.translation() = Eigen::Vector3d(2, 0, 0.7);
  box.half_size = {0.5, 0.4, 0.02};
  g.geoms.push_back(box);
  StaticGeom hull;
  hull.type = StaticGeom::Type::kConvexMesh;
  hull.name = "seat";
  hull.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  g.geoms.push_back(hull);
  MjModelPtr m = BuildModel(g);
  EXPECT_EQ(m->ngeom, 19 + 2);
  Humanoid h(m);  // humanoid indices resolve regardless of scene geoms
  EXPECT_EQ(h.geom_body(mj_name2id(m.get(), mjOBJ_GEOM, "seat")), -1);
  EXPECT_EQ(h.geom_body(mj_name2id(m.get(), mjOBJ_GEOM, "head")), kHead);
}

}  // namespace
}  // namespace sims::humanoid
