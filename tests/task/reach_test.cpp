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
  EXPECT_EQ(s.env->obs_dim(), 223 + 60 + 256 + 64);
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
    if (to_target.norm() > 0.8) continue;  // default init (no fitting clip or blocked floor)
    ++placed;
    const ObjectGeometry& g = reach->geometry(i);
    // Facing the object's front (object −x).
    const double heading = sim::HeadingAngle(s.env->pose(i).root_rot);
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
  const Eigen::Vector3d hand = sim::ContactJointPosition(s.env->bodies(0), sim::kCjRightHand);
  const Eigen::Vector2d root = s.env->pose(0).root_pos.head<2>();
  for (double d : {0.15, 0.25}) {
    reach->SetTarget(0, sim::kCjRightHand, hand + Eigen::Vector3d(0, 0, d));
    const auto r = reach->Step(ViewOf(*s.env, 0));
    EXPECT_EQ(r.success, d < 0.2);
    EXPECT_NEAR(reach->goal_error(0), d, 1e-9);
    // Near form when the target is within √0.5 m of the root in xy.
    ASSERT_LT((hand.head<2>() - root).squaredNorm(), kFarDistanceSq);
    EXPECT_NEAR(r.reward, 0.6 * std::exp(-10 * d * d) + 0.4, 1e-5);
  }
}

}  // namespace
}  // namespace sims::task
