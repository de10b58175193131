#include "sims/task/reach/reach.h"

#include <cmath>

#include <gtest/gtest.h>

#include "task/task_test_util.h"

namespace sims::task {
namespace {

using testing::MakeSkillEnv;
using testing::PoseAt;
using testing::ViewOf;

SkillConfig ReachConfig() {
  SkillConfig c;
  c.skill = "reach";
  c.object.num_objects = 3;
  c.object.object_categories = {"shelf", "table", "cabinet"};
  c.motion.manifest = testing::SyntheticManifest({"reach"});
  c.motion.skills = {"reach"};
  return c;
}

TEST(ReachSkillTest, TargetsOnTheFrontInHeightBands) {
  SkillConfig c = ReachConfig();
  c.reference_init_prob = 0;
  auto s = MakeSkillEnv(c, 8);
  auto* reach = dynamic_cast<ReachSkill*>(s.setup.skill.get());
  ASSERT_NE(reach, nullptr);
  EXPECT_EQ(s.env->obs_dim(), 223 + 60 + kObjectObsDim + 256 + 64);
  // The shelf has targets at all three heights.
  for (int b = 0; b < 3; ++b) EXPECT_FALSE(reach->candidates(0, b).empty()) << b;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d t = reach->target(i);
    EXPECT_GE(t.z(), kReachBandEdges[0]);
    EXPECT_LT(t.z(), kReachBandEdges[3]);
    const ObjectGeometry& g = reach->geometry(i);
    const Eigen::Vector3d local = g.X_WO.inverse() * t;
    EXPECT_GE(local.x(), g.local.max.x() - 0.12 - 1e-9);
    EXPECT_EQ(reach->goal_mask(i), 1u << reach->hand(i));
    EXPECT_NEAR((reach->goal(i, reach->hand(i)) - t).norm(), 0, 1e-12);
  }
  // Evaluation groups trials by the target's band.
  const char* kBands[] = {"low", "medium", "high"};
  for (int b = 0; b < 3; ++b) {
    reach->SetTarget(0, humanoid::kCjRightHand, reach->candidates(0, b).front());
    EXPECT_EQ(reach->start_label(0), kBands[b]);
  }
}

TEST(ReachSkillTest, ReferenceInitFacesTheTarget) {
  SkillConfig c = ReachConfig();
  c.reference_init_prob = 1.0;
  c.reference_init_max_fraction = 0.01;  // the clip's first frame: standing before the target
  auto s = MakeSkillEnv(c, 8);
  auto* reach = dynamic_cast<ReachSkill*>(s.setup.skill.get());
  int placed = 0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector2d to_target =
        reach->target(i).head<2>() - s.env->pose(i).root_pos.head<2>();
    if (!reach->reference_start(i)) continue;  // default init (no fitting clip or blocked floor)
    ++placed;
    EXPECT_LT(to_target.norm(), 3.0);  // at most an approach composite's walk-up away
    const ObjectGeometry& g = reach->geometry(i);
    // Facing the object's front (object −x).
    const double heading = humanoid::HeadingAngle(s.env->pose(i).root_rot);
    EXPECT_GT(std::cos(heading - (g.yaw + M_PI)), 0.9);
    EXPECT_GT(to_target.normalized().dot(Eigen::Vector2d(std::cos(heading), std::sin(heading))),
              0.5);
  }
  EXPECT_GE(placed, 4);
}

TEST(ReachSkillTest, RewardAndThreshold) {
  SkillConfig c = ReachConfig();
  c.reference_init_prob = 0;
  auto s = MakeSkillEnv(c, 1);
  auto* reach = dynamic_cast<ReachSkill*>(s.setup.skill.get());
  const ObjectGeometry& g = reach->geometry(0);
  // Stand on the far anchor of a front target, facing the object.
  const int band = reach->candidates(reach->object(0), 1).empty() ? 0 : 1;
  const Eigen::Vector3d front = reach->candidates(reach->object(0), band).front();
  reach->SetTarget(0, humanoid::kCjRightHand, front);
  const Eigen::Vector3d a_O =
      g.X_WO.inverse() * Eigen::Vector3d(reach->anchor(0).x(), reach->anchor(0).y(), 0);
  EXPECT_NEAR(a_O.x(), g.local.max.x() + kStandDistance, 1e-9);
  EXPECT_NEAR(a_O.y(), (g.X_WO.inverse() * front).y(), 1e-9);
  s.env->SetState(
      0, PoseAt(Eigen::Vector3d(reach->anchor(0).x(), reach->anchor(0).y(), 0.89), g.yaw + M_PI));
  const Eigen::Vector3d hand =
      humanoid::ContactJointPosition(s.env->bodies(0), humanoid::kCjRightHand);
  for (double d : {0.15, 0.25}) {
    reach->SetTarget(0, humanoid::kCjRightHand, hand + Eigen::Vector3d(0, 0, d));
    const auto r = reach->Step(ViewOf(*s.env, 0));
    EXPECT_EQ(r.success, d < 0.2);
    EXPECT_NEAR(reach->goal_error(0), d, 1e-9);
    // Within √0.5 m of the anchor: r_far = 1.
    ASSERT_LT((reach->anchor(0) - s.env->pose(0).root_pos.head<2>()).squaredNorm(), kFarDistanceSq);
    EXPECT_NEAR(r.reward, 0.7 * std::exp(-10 * d * d) + 0.3, 1e-5);
  }
}

// wide_near_share and precise_near_share split r_near between exp(−Σ), exp(−10Σ), exp(−100Σ):
// a hand 0.6 m below a high target earns 0.7·(0.3·exp(−0.36) + 0.5·exp(−3.6) + 0.2·exp(−36)) + 0.3.
TEST(ReachSkillTest, NearKernelSharesFromTheConfig) {
  SkillConfig c = ReachConfig();
  c.reference_init_prob = 0;
  c.object.wide_near_share = 0.3;
  c.object.precise_near_share = 0.2;
  auto s = MakeSkillEnv(c, 1);
  auto* reach = dynamic_cast<ReachSkill*>(s.setup.skill.get());
  const ObjectGeometry& g = reach->geometry(0);
  reach->SetTarget(0, humanoid::kCjRightHand,
                   reach->candidates(reach->object(0), 0).empty()
                       ? reach->candidates(reach->object(0), 1).front()
                       : reach->candidates(reach->object(0), 0).front());
  s.env->SetState(
      0, PoseAt(Eigen::Vector3d(reach->anchor(0).x(), reach->anchor(0).y(), 0.89), g.yaw + M_PI));
  const Eigen::Vector3d hand =
      humanoid::ContactJointPosition(s.env->bodies(0), humanoid::kCjRightHand);
  reach->SetTarget(0, humanoid::kCjRightHand, hand + Eigen::Vector3d(0, 0, 0.6));
  const auto r = reach->Step(ViewOf(*s.env, 0));
  EXPECT_NEAR(r.reward,
              0.7 * (0.3 * std::exp(-0.36) + 0.5 * std::exp(-3.6) + 0.2 * std::exp(-36.0)) + 0.3,
              1e-5);
  c.object.wide_near_share = 0.9;  // 0.9 + 0.2 > 1
  EXPECT_THROW(c.object.Validate(), Error);
}

TEST(ReachSkillTest, StartsAreBeforeContactAndInFront) {
  SkillConfig c = ReachConfig();
  c.reference_init_prob = 0.5;
  c.object.spawn_arc_deg = 180;
  auto s = MakeSkillEnv(c, 8);
  auto* reach = dynamic_cast<ReachSkill*>(s.setup.skill.get());
  const auto& lib = *s.setup.context.motions;
  for (int clip : lib.Find("reach")) {
    // The clips reach at 1.5 s and hold until 2.6 s of their 4.3 s (the approach composites
    // walk up first); the window ends before the hand arrives.
    SCOPED_TRACE(lib.clip(clip).meta().name);
    EXPECT_GT(reach->pre_contact_time(clip), kMinPreContactTime);
    EXPECT_LT(reach->pre_contact_time(clip), lib.clip(clip).duration() - 2.8);
  }
  for (int round = 0; round < 5; ++round) {
    for (int i = 0; i < 8; ++i) {
      s.env->ResetEnv(i);
      EXPECT_GT(reach->goal_error(i), c.object.contact_success_threshold);
      // Default starts lie in the half-plane in front of the object.
      const ObjectGeometry& g = reach->geometry(i);
      const Eigen::Vector2d p = s.env->pose(i).root_pos.head<2>() - g.center;
      EXPECT_GT(p.dot(Eigen::Vector2d(std::cos(g.yaw), std::sin(g.yaw))), -1e-9);
    }
  }
}

}  // namespace
}  // namespace sims::task
