#include "sims/task/getup/getup.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sims/scene/contact_targets.h"
#include "task/task_test_util.h"

namespace sims::task {
namespace {

using testing::MakeSkillEnv;
using testing::PoseAt;
using testing::ViewOf;

SkillConfig GetUpConfig() {
  SkillConfig c;
  c.skill = "getup";
  c.object.num_objects = 2;
  c.object.object_categories = {"chair", "bed"};
  c.motion.manifest = testing::SyntheticManifest({"getup"});
  c.motion.skills = {"getup"};
  return c;
}

TEST(GetUpSkillTest, FallStatesLieOnTheFloor) {
  const auto states = GenerateFallStates(4, 7);
  ASSERT_EQ(states.size(), 4u);
  for (const auto& p : states) {
    EXPECT_TRUE(p.root_pos.allFinite());
    EXPECT_LT(p.root_pos.z(), 0.5);  // down, not standing
    EXPECT_EQ(p.root_pos.x(), 0.0);
  }
}

TEST(GetUpSkillTest, FallStartsHaveAGracePeriod) {
  SkillConfig c = GetUpConfig();
  c.reference_init_prob = 0;
  auto s = MakeSkillEnv(c, 3);
  auto* getup = dynamic_cast<GetUpSkill*>(s.setup.skill.get());
  ASSERT_NE(getup, nullptr);
  EXPECT_EQ(getup->fall_states().size(), static_cast<size_t>(kNumFallStates));
  EXPECT_EQ(s.env->obs_dim(), 223 + 60 + 256 + 64);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(getup->fall_start(i));
    EXPECT_EQ(getup->phase(i), GetUpSkill::kFeetPhase);
    EXPECT_LT(s.env->pose(i).root_pos.z(), 0.5);
    // Stand point under the start; goals: pelvis at standing height plus both feet.
    EXPECT_NEAR((getup->stand_point(i) - s.env->pose(i).root_pos.head<2>()).norm(), 0, 1e-9);
    EXPECT_EQ(getup->goal_mask(i),
              (1u << sim::kCjPelvis) | (1u << sim::kCjLeftFoot) | (1u << sim::kCjRightFoot));
    EXPECT_NEAR(getup->goal(i, sim::kCjPelvis).z(), sim::kDefaultRootHeight, 1e-12);
  }
  // Lying on the floor does not end the episode during the grace period.
  std::vector<float> zero(3 * 28, 0.0f);
  for (int t = 0; t < kFallGraceSteps - 5; ++t) {
    s.env->Step(zero.data());
    for (int i = 0; i < 3; ++i) ASSERT_FALSE(s.env->dones()[i]) << "step " << t;
  }
}

TEST(GetUpSkillTest, ReferenceStartsSeatedOrLying) {
  SkillConfig c = GetUpConfig();
  c.reference_init_prob = 1.0;
  auto s = MakeSkillEnv(c, 6);
  auto* getup = dynamic_cast<GetUpSkill*>(s.setup.skill.get());
  const auto& scene = *s.setup.context.scene;
  int on_furniture = 0;
  for (int i = 0; i < 6; ++i) {
    if (getup->fall_start(i)) continue;
    const ObjectGeometry& g = getup->geometry(i);
    const int part = g.seat >= 0 ? g.seat : g.mattress;
    const Eigen::Vector3d pelvis = s.env->bodies(i).pos[sim::kPelvis];
    const double d =
        (scene::NearestPointOnPart(scene.objects[g.object].parts[part], pelvis) - pelvis).norm();
    EXPECT_LT(d, 0.3);
    EXPECT_LT(pelvis.z(), kStandingPelvisHeight);
    // The stand point is the object's free floor point nearest to the pelvis.
    EXPECT_FALSE(g.stand_points.empty());
    ++on_furniture;
  }
  EXPECT_GE(on_furniture, 4);
}

TEST(GetUpSkillTest, RewardPhasesAndStandingSuccess) {
  EXPECT_NEAR(GetUpSkill::RiseReward(sim::kDefaultRootHeight, 1.0, {0, 0}, {0, 0}), 1.0, 1e-12);
  EXPECT_NEAR(GetUpSkill::RiseReward(0.49, 0.5, {0, 0}, {0.5, 0}),
              0.6 * std::exp(-10 * 0.16) + 0.2 * 0.5 + 0.2 * std::exp(-0.5), 1e-9);
  EXPECT_NEAR(GetUpSkill::RiseReward(1.0, -1.0, {0, 0}, {0, 0}), 0.8, 1e-12);

  SkillConfig c = GetUpConfig();
  c.reference_init_prob = 0;
  c.object.max_contact_force = 0;
  c.success_hold_steps = 2;
  auto s = MakeSkillEnv(c, 1);
  auto* getup = dynamic_cast<GetUpSkill*>(s.setup.skill.get());
  // Standing upright at the stand point: feet on the disk → rise phase, then success held.
  const Eigen::Vector2d stand = getup->stand_point(0);
  s.env->SetState(0, PoseAt(Eigen::Vector3d(stand.x(), stand.y(), 0.89)));
  auto r = getup->Step(ViewOf(*s.env, 0));
  EXPECT_EQ(getup->phase(0), GetUpSkill::kRisePhase);
  EXPECT_TRUE(r.success);
  // Feet-phase reward: half the contact reward with the feet's disk targets.
  EXPECT_LE(r.reward, 0.5 + 1e-6);
  r = getup->Step(ViewOf(*s.env, 0));
  EXPECT_NEAR(r.reward,
              0.5 + 0.5 * GetUpSkill::RiseReward(s.env->bodies(0).pos[0].z(), 1.0, stand,
                                                 s.env->bodies(0).pos[0].head<2>()),
              1e-5);
  EXPECT_TRUE(r.truncate);
  EXPECT_EQ(getup->goal_mask(0), 1u << sim::kCjPelvis);
}

TEST(GetUpSkillTest, SitThenGetUpSwitchesGoalsInOneEpisode) {
  SkillConfig c = GetUpConfig();
  c.skill = "sit_getup";
  c.object.object_categories = {"chair"};
  c.motion.manifest = testing::SyntheticManifest({"sit"});
  c.motion.skills = {"sit"};
  c.reference_init_prob = 0;
  c.object.max_contact_force = 0;
  c.success_hold_steps = 3;
  auto s = MakeSkillEnv(c, 1);
  auto* sg = dynamic_cast<GetUpSkill*>(s.setup.skill.get());
  ASSERT_NE(sg, nullptr);
  EXPECT_EQ(sg->name(), "sit_getup");
  EXPECT_EQ(sg->phase(0), GetUpSkill::kSitPhase);
  const ObjectGeometry& g = sg->geometry(0);
  s.env->SetState(0, PoseAt(g.ToWorld(g.seat_local.center()) + Eigen::Vector3d(0, 0, 0.1)));
  for (int k = 1; k <= 3; ++k) {
    const auto r = sg->Step(ViewOf(*s.env, 0));
    EXPECT_FALSE(r.success);  // sitting is not the episode's success
    EXPECT_FALSE(r.truncate);
  }
  EXPECT_EQ(sg->phase(0), GetUpSkill::kFeetPhase);
  EXPECT_NEAR(sg->goal(0, sim::kCjPelvis).z(), sim::kDefaultRootHeight, 1e-12);
  // The stand point is in front of the chair.
  const Eigen::Vector3d local =
      g.X_WO.inverse() * Eigen::Vector3d(sg->stand_point(0).x(), sg->stand_point(0).y(), 0);
  EXPECT_GT(local.x(), g.local.max.x());
}

}  // namespace
}  // namespace sims::task
