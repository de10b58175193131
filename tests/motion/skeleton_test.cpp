#include "sims/motion/skeleton.h"

#include <gtest/gtest.h>

#include "sims/core/rng.h"
#include "sims/humanoid/state.h"

namespace sims::motion {
namespace {

DofVector RandomDofs(const HumanoidSkeleton& s, Rng& rng) {
  DofVector d;
  for (int i = 0; i < humanoid::kNumDofs; ++i) d[i] = rng.Uniform(s.lower[i], s.upper[i]);
  return d;
}

// The Eigen FK agrees with MuJoCo's for random poses.
TEST(SkeletonTest, ForwardKinematicsMatchesMujoco) {
  const auto h = HumanoidSkeleton::DefaultHumanoid();
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  humanoid::MjDataPtr d = humanoid::MakeData(h->model());
  Rng rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    humanoid::HumanoidPose pose;
    pose.root_pos = Eigen::Vector3d(rng.Uniform(-2, 2), rng.Uniform(-2, 2), rng.Uniform(0.5, 1));
    pose.root_rot =
        Eigen::Quaterniond(rng.Normal(), rng.Normal(), rng.Normal(), rng.Normal()).normalized();
    pose.dof_pos = RandomDofs(s, rng);
    humanoid::BodyStates bodies;
    humanoid::ForwardKinematics(*h, pose, d.get(), &bodies);
    SkeletonPose sp;
    SkeletonForwardKinematics(s, pose.root_pos, pose.root_rot, pose.dof_pos, &sp);
    for (int b = 0; b < humanoid::kNumBodies; ++b) {
      EXPECT_LT((sp.pos[b] - bodies.pos[b]).norm(), 1e-9) << humanoid::BodyNames()[b];
      EXPECT_LT(sp.rot[b].angularDistance(bodies.rot[b]), 1e-9) << humanoid::BodyNames()[b];
    }
  }
}

TEST(SkeletonTest, StandingHeightPutsSolesOnTheFloor) {
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  SkeletonPose sp;
  SkeletonForwardKinematics(s, Eigen::Vector3d(0, 0, s.standing_root_height()),
                            Eigen::Quaterniond::Identity(), DofVector::Zero(), &sp);
  EXPECT_NEAR(SoleHeight(s, sp, false), 0.0, 1e-12);
  EXPECT_NEAR(SoleHeight(s, sp, true), 0.0, 1e-12);
  EXPECT_NEAR(s.ankle_height(), 0.05, 1e-9);
}

// IK reaches reachable targets: solve for the FK of a random in-limit pose.
TEST(SkeletonTest, LimbIkReachesTargets) {
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  Rng rng(9);
  int reached_leg = 0, reached_arm = 0;
  const int trials = 100;
  for (int t = 0; t < trials; ++t) {
    DofVector ref = RandomDofs(s, rng);
    ref[humanoid::Joints()[7].dof_offset] = rng.Uniform(0.2, 2.0);    // right knee bent
    ref[humanoid::Joints()[10].dof_offset] = rng.Uniform(0.2, 2.0);   // left knee bent
    ref[humanoid::Joints()[3].dof_offset] = rng.Uniform(-2.0, -0.2);  // right elbow bent
    const Eigen::Vector3d root(0.1, -0.2, 0.8);
    const Eigen::Quaterniond rr(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
    SkeletonPose sp;
    SkeletonForwardKinematics(s, root, rr, ref, &sp);
    for (bool left : {false, true}) {
      DofVector d = DofVector::Zero();
      const int shin = left ? humanoid::kLeftShin : humanoid::kRightShin;
      const int foot = left ? humanoid::kLeftFoot : humanoid::kRightFoot;
      const Eigen::Vector3d knee_dir = sp.rot[shin] * Eigen::Vector3d::UnitX();
      const LimbIkResult r =
          SolveLegIk(s, left, root, rr, sp.pos[foot], sp.rot[foot], knee_dir, &d);
      if (r.position_error < 1e-6 && !r.clamped) {
        ++reached_leg;
        SkeletonPose got;
        SkeletonForwardKinematics(s, root, rr, d, &got);
        EXPECT_LT(got.rot[foot].angularDistance(sp.rot[foot]), 1e-6);
      }
    }
    DofVector d = DofVector::Zero();
    const Eigen::Vector3d elbow_dir = sp.rot[humanoid::kRightUpperArm] * -Eigen::Vector3d::UnitX();
    const LimbIkResult r = SolveArmIk(s, false, sp.pos[humanoid::kTorso], sp.rot[humanoid::kTorso],
                                      sp.pos[humanoid::kRightHand], elbow_dir, &d);
    if (r.position_error < 1e-6) ++reached_arm;
  }
  EXPECT_GT(reached_leg, 2 * trials * 8 / 10);
  EXPECT_GT(reached_arm, trials * 8 / 10);
}

}  // namespace
}  // namespace sims::motion
