#include "sims/task/unified/unified.h"

#include <cmath>
#include <cstring>
#include <set>

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "sims/scene/contact_targets.h"
#include "sims/scene/loaders.h"
#include "task/task_test_util.h"

namespace sims::task {
namespace {

using testing::MakeSkillEnv;
using testing::PoseAt;
using testing::ViewOf;

TEST(AdaptiveWeightsTest, HandComputed) {
  const double r[3] = {0.2, 0.6, 1.0};
  double w[3];
  const double total = AdaptiveCombine(r, 3, w);
  const double denom = 3 - 1.8 + 1e-4;
  EXPECT_NEAR(w[0], 0.8 / denom, 1e-12);
  EXPECT_NEAR(w[1], 0.4 / denom, 1e-12);
  EXPECT_NEAR(w[2], 0.0, 1e-12);
  EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-4);  // (n − Σr)/(n − Σr + 1e-4)
  EXPECT_NEAR(total, (0.8 * 0.2 + 0.4 * 0.6) / denom, 1e-12);
  // All satisfied: reward 0 weights, total 0 (UniHSI's form; a perfect step still has r = 1
  // terms elsewhere).
  const double ones[2] = {1.0, 1.0};
  EXPECT_NEAR(AdaptiveCombine(ones, 2), 0.0, 1e-12);
  // Random vectors: weights sum to 1 up to the 1e-4 regulariser.
  Rng rng(3);
  for (int k = 0; k < 20; ++k) {
    double v[15], ww[15], sum_w = 0, sum_r = 0;
    for (double& x : v) x = rng.Uniform(), sum_r += x;
    AdaptiveCombine(v, 15, ww);
    for (double x : ww) sum_w += x;
    EXPECT_NEAR(sum_w, (15 - sum_r) / (15 - sum_r + 1e-4), 1e-12);
  }
}

TEST(ContactPairRewardTest, ContactDirectionAndNotContact) {
  JointPair p;
  p.type = ContactType::kContact;
  p.target = {0, 0, 0.5};
  p.joint = {0, 0, 0.8};  // 0.3 m above: direction "up" holds
  p.direction = {0, 0, 1};
  const double rc = std::exp(-10 * 0.09);
  PairReward r = ContactPairReward(p);
  EXPECT_NEAR(r.contact, rc, 1e-12);
  EXPECT_NEAR(r.direction, 1.0, 1e-12);
  EXPECT_NEAR(r.reward, (1 - rc) * rc / (2 - rc - 1 + 1e-4), 1e-12);
  EXPECT_NEAR(r.err2, 0.09, 1e-12);
  p.joint = {0, 0, 0.2};  // below: direction fails, success blocked
  r = ContactPairReward(p);
  EXPECT_NEAR(r.direction, 0.0, 1e-12);
  EXPECT_NEAR(r.reward, ((1 - rc) * rc + 1.0 * 0.0) / (2 - rc + 1e-4), 1e-12);
  EXPECT_NEAR(r.err2, 1.09, 1e-12);
  p.type = ContactType::kNotContact;  // direction ignored
  r = ContactPairReward(p);
  EXPECT_NEAR(r.contact, 1 - rc, 1e-12);
  EXPECT_NEAR(r.direction, 1.0, 1e-12);
  EXPECT_NEAR(r.err2, 0.09, 1e-12);
  p.type = ContactType::kNone;
  EXPECT_NEAR(ContactPairReward(p).reward, 1.0, 1e-12);
  EXPECT_NEAR(PairContactError(ContactType::kNotContact, 0.1), 0.2, 1e-12);
  EXPECT_NEAR(PairContactError(ContactType::kContact, 0.1), 0.1, 1e-12);
}

TEST(UniHsiStepRewardTest, WalkingContactAndReach) {
  std::array<JointPair, humanoid::kNumContactJoints> pairs;
  const Eigen::Vector3d root(0, 0, 0.89);
  // Walking: velocity and facing hold, only the position term is weak.
  StepReward s = UniHsiStepReward(pairs, root, {1, 0, 0}, {1, 0}, {3, 0, 0.89});
  const double rp = std::exp(-0.5 * 9);
  EXPECT_TRUE(s.walking);
  EXPECT_NEAR(s.walk_err2, 9, 1e-12);
  EXPECT_NEAR(s.reward, (1 - rp) * rp / (3 - rp - 2 + 1e-4), 1e-12);
  // Near the stand point velocity and facing count as met.
  s = UniHsiStepReward(pairs, root, {0, 0, 0}, {0, 1}, {0.3, 0, 0.89});
  const double rp2 = std::exp(-0.5 * 0.09);
  EXPECT_NEAR(s.reward, (1 - rp2) * rp2 / (3 - rp2 - 2 + 1e-4), 1e-12);
  // One pelvis contact: joints adaptively (14 others count 1), then with facing (1).
  pairs[humanoid::kCjPelvis].type = ContactType::kContact;
  pairs[humanoid::kCjPelvis].joint = {0, 0, 0.6};
  pairs[humanoid::kCjPelvis].target = {0, 0, 0.5};
  const double rc = std::exp(-0.1);
  const double pair = (1 - rc) * rc / (1 - rc + 1e-4);
  const double near = (1 - pair) * pair / (15 - 14 - pair + 1e-4);
  s = UniHsiStepReward(pairs, root, {0, 0, 0}, {1, 0}, {9, 9, 9});
  EXPECT_FALSE(s.walking);
  EXPECT_NEAR(s.err2[0], 0.01, 1e-12);
  EXPECT_NEAR(s.reward, (1 - near) * near / (2 - near - 1 + 1e-4), 1e-12);
  // A lone hand contact: facing the target (+x from the root) is rewarded adaptively.
  pairs[humanoid::kCjPelvis].type = ContactType::kNone;
  pairs[humanoid::kCjRightHand].type = ContactType::kContact;
  pairs[humanoid::kCjRightHand].joint = {0.5, 0, 1.2};
  pairs[humanoid::kCjRightHand].target = {0.5, 0, 1.0};
  const double rh = std::exp(-0.4);
  const double hand = (1 - rh) * rh / (1 - rh + 1e-4);
  const double near_h = (1 - hand) * hand / (1 - hand + 1e-4);
  EXPECT_NEAR(UniHsiStepReward(pairs, root, {0, 0, 0}, {1, 0}, {9, 9, 9}).reward,
              (1 - near_h) * near_h / (1 - near_h + 1e-4), 1e-12);
  EXPECT_NEAR(UniHsiStepReward(pairs, root, {0, 0, 0}, {0, 1}, {9, 9, 9}).reward,
              (1 - near_h) * near_h / (2 - near_h + 1e-4), 1e-12);
}

TEST(UniHsiStepRuleTest, TriggerAndAdvanceThresholds) {
  std::array<ContactType, humanoid::kNumContactJoints> types;
  types.fill(ContactType::kNone);
  types[humanoid::kCjPelvis] = ContactType::kContact;
  types[humanoid::kCjTorso] = ContactType::kNotContact;
  StepReward r;
  r.err2[humanoid::kCjPelvis] = 0.05;
  r.err2[humanoid::kCjTorso] = 0.2;
  EXPECT_FALSE(CheckUniHsiStep(types, r, false, 10).triggered);  // still for only 10 steps
  StepCheck c = CheckUniHsiStep(types, r, false, 11);
  EXPECT_TRUE(c.triggered && c.advance);
  EXPECT_FALSE(CheckUniHsiStep(types, r, true, 11).triggered);  // excessive force
  r.err2[humanoid::kCjPelvis] = 0.2;                            // loose only: done, not passed
  c = CheckUniHsiStep(types, r, false, 11);
  EXPECT_TRUE(c.triggered);
  EXPECT_FALSE(c.advance);
  r.err2[humanoid::kCjPelvis] = 0.05;
  r.err2[humanoid::kCjTorso] = 0.07;  // not contact needs ≥ 0.1 to trigger
  EXPECT_FALSE(CheckUniHsiStep(types, r, false, 11).triggered);
  StepReward walk;
  walk.walking = true;
  walk.walk_err2 = 0.09;
  EXPECT_TRUE(CheckUniHsiStep({}, walk, false, 11).advance);
  walk.walk_err2 = 0.11;
  EXPECT_FALSE(CheckUniHsiStep({}, walk, false, 11).triggered);
}

TEST(ContactPlanTest, ScenePlanFixtureBecomesSteps) {
  const auto json = sims::testing::TestData("scene/sceneplan.json");
  const scene::Scene s =
      scene::LoadScenePlan(json, sims::testing::TestData("scene/partnet"), "0000");
  const ContactPlan plan = LoadContactPlan(json, s, "0000");
  EXPECT_EQ(plan.id, "0000");
  ASSERT_EQ(plan.steps.size(), 2u);
  // Step 1: ["chair000", "none", "none", "none", "none"] — walk to the stand point.
  EXPECT_TRUE(plan.steps[0].walking());
  EXPECT_EQ(plan.steps[0].object, 0);
  EXPECT_EQ(plan.steps[0].mask(), 0u);
  EXPECT_TRUE(plan.steps[0].stand_point.isApprox(Eigen::Vector3d(2.5, 2, 0.86)));
  // Step 2: pelvis on seat_soft_surface2, contact, from above.
  const ContactStep& sit = plan.steps[1];
  ASSERT_EQ(sit.pairs.size(), 1u);
  EXPECT_EQ(sit.mask(), 1u << humanoid::kCjPelvis);
  EXPECT_EQ(sit.pairs[0].type, ContactType::kContact);
  EXPECT_EQ(sit.pairs[0].object, 0);
  EXPECT_EQ(s.objects[0].parts[sit.pairs[0].part].name, "seat soft surface");
  EXPECT_TRUE(sit.pairs[0].direction.isApprox(Eigen::Vector3d(0, 0, 1)));
  EXPECT_EQ(sit.types()[humanoid::kCjPelvis], ContactType::kContact);
  EXPECT_EQ(sit.types()[humanoid::kCjHead], ContactType::kNone);
  // The default plan is the first; a plan without steps is empty.
  EXPECT_EQ(LoadContactPlan(json, s).id, "0000");
  EXPECT_TRUE(LoadContactPlan(json, s, "0001").steps.empty());
}

TEST(ContactPlanTest, ResolveStepGivesGoalsTypesAndDirections) {
  const auto json = sims::testing::TestData("scene/sceneplan.json");
  const scene::Scene s =
      scene::LoadScenePlan(json, sims::testing::TestData("scene/partnet"), "0000");
  const ContactPlan plan = LoadContactPlan(json, s, "0000");
  const humanoid::Humanoid h(humanoid::BuildModel());
  humanoid::MjDataPtr d = humanoid::MakeData(h.model());
  humanoid::BodyStates b;
  humanoid::ForwardKinematics(h, PoseAt(Eigen::Vector3d(0.9, 2.0, 1.5)), d.get(), &b);
  const auto pairs = ResolveStep(plan.steps[1], s, b);
  const auto& seat = s.objects[0].parts[plan.steps[1].pairs[0].part];
  for (int j = 0; j < humanoid::kNumContactJoints; ++j) {
    if (j != humanoid::kCjPelvis) {
      EXPECT_EQ(pairs[j].type, ContactType::kNone);
      continue;
    }
    EXPECT_EQ(pairs[j].type, ContactType::kContact);
    EXPECT_TRUE(pairs[j].joint.isApprox(b.pos[humanoid::kPelvis]));
    EXPECT_TRUE(pairs[j].target.isApprox(scene::NearestSamplePoint(seat, pairs[j].joint)));
    EXPECT_TRUE(pairs[j].direction.isApprox(Eigen::Vector3d(0, 0, 1)));
  }
  for (const auto& p : ResolveStep(plan.steps[0], s, b)) EXPECT_EQ(p.type, ContactType::kNone);
}

TEST(ContactPlanTest, BadPlansNameTheField) {
  const auto json = sims::testing::TestData("scene/sceneplan.json");
  const scene::Scene s =
      scene::LoadScenePlan(json, sims::testing::TestData("scene/partnet"), "0000");
  auto expect_error = [&](const char* pair, std::vector<std::string> words) {
    const nlohmann::json plan =
        nlohmann::json::parse(std::string("{\"contact_pairs\": [[") + pair + "]]}");
    try {
      ContactPlanFromJson(plan, s, "plan.json", "7");
      FAIL() << pair;
    } catch (const Error& e) {
      for (const auto& w : words)
        EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what() << " / " << w;
    }
  };
  expect_error(R"(["sofa000", "seat_soft_surface2", "pelvis", "contact", "up"])",
               {"plan.json", "7.contact_pairs[0][0][0]", "chair000", "sofa000"});
  expect_error(R"(["chair000", "armrest9", "pelvis", "contact", "up"])",
               {"[0][0][1]", "seat_soft_surface2", "armrest9"});
  expect_error(R"(["chair000", "seat_soft_surface2", "tail", "contact", "up"])",
               {"[0][0][2]", "right_hand", "tail"});
  expect_error(R"(["chair000", "seat_soft_surface2", "pelvis", "touch", "up"])",
               {"[0][0][3]", "not contact"});
  expect_error(R"(["chair000", "seat_soft_surface2", "pelvis", "contact", "sideways"])",
               {"[0][0][4]", "front"});
  expect_error(R"(["chair000", "seat_soft_surface2"])", {"[0][0]", "joint"});
}

SkillConfig UnifiedConfig() {
  SkillConfig c;
  c.skill = "unified";
  c.object.num_objects = 3;
  c.object.object_categories = {"armchair", "bed", "table"};
  return c;
}

TEST(UnifiedSkillTest, RandomChainsAndObservation) {
  auto s = MakeSkillEnv(UnifiedConfig(), 6);
  auto* u = dynamic_cast<UnifiedSkill*>(s.setup.skill.get());
  ASSERT_NE(u, nullptr);
  const int base = 60 + 256 + 64;
  EXPECT_EQ(s.env->obs_dim(), 223 + base + kContactPairObsDim);
  const auto segs = u->obs_segments();
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_EQ(segs[3].name, "contact_pairs");
  EXPECT_EQ(segs[3].offset, base);
  for (int i = 0; i < 6; ++i) {
    const auto& chain = u->steps(i);
    ASSERT_FALSE(chain.empty());
    ASSERT_LE(chain.size(), 3u);
    EXPECT_EQ(u->step_index(i), 0);
    const ContactStep& st = chain[0];
    const float* o = s.env->observations() + i * s.env->obs_dim() + 223;
    if (st.walking()) {
      EXPECT_EQ(u->goal_mask(i), 1u << humanoid::kCjPelvis);
      EXPECT_TRUE(u->goal(i, humanoid::kCjPelvis).isApprox(st.stand_point));
    } else {
      EXPECT_EQ(u->goal_mask(i), st.mask());
    }
    for (const auto& p : st.pairs) {
      EXPECT_EQ(o[base + p.joint], p.type == ContactType::kContact ? 1.0f : -1.0f);
      const float* d = o + base + humanoid::kNumContactJoints + 3 * p.joint;
      EXPECT_NEAR(Eigen::Vector3d(d[0], d[1], d[2]).norm(), p.direction.norm(), 1e-5);
    }
  }
  // Chains cover the templates of each object kind.
  Rng rng(5);
  std::set<std::string> labels;
  for (int k = 0; k < 3; ++k)
    for (int n = 0; n < 40; ++n)
      for (const auto& st : u->RandomChain(k, rng)) labels.insert(st.label);
  for (const char* l : {"walk", "sit", "sit, lean back", "sit upright",
                        "sit, hands on the arm rests", "sit, hands on the knees", "lie on the bed",
                        "sit on the bed", "touch the top with the right hand"})
    EXPECT_TRUE(labels.count(l)) << l;
}

TEST(UnifiedSkillTest, StepsAdvanceWithinTheEpisode) {
  SkillConfig c = UnifiedConfig();
  c.object.max_contact_force = 0;
  auto s = MakeSkillEnv(c, 1);
  auto* u = dynamic_cast<UnifiedSkill*>(s.setup.skill.get());
  const ObjectGeometry& g = u->objects()[0];
  ContactStep walk;
  walk.object = g.object;
  walk.stand_point = Eigen::Vector3d(g.center.x() + 3, g.center.y(), 0.89);
  ContactStep sit;
  sit.object = g.object;
  ContactPairSpec p;
  p.joint = humanoid::kCjPelvis;
  p.object = g.object;
  p.part = g.part_index(kSeatPart);
  p.direction = {0, 0, 1};
  sit.pairs = {p};
  u->SetPlan({walk, sit});
  s.env->Reset();
  EXPECT_TRUE(u->steps(0)[0].walking());
  // Standing still on the stand point: the step advances after more than 10 still steps.
  s.env->SetState(0, PoseAt(walk.stand_point));
  for (int k = 1; k <= 11; ++k) {
    const auto r = u->Step(ViewOf(*s.env, 0));
    ASSERT_EQ(r.success, k == 11) << k;
    EXPECT_FALSE(r.truncate);
  }
  EXPECT_EQ(u->step_index(0), 1);
  EXPECT_EQ(u->steps_completed(0), 1);
  EXPECT_EQ(u->goal_mask(0), 1u << humanoid::kCjPelvis);  // now the seat
  // Sitting still above the seat passes the last step: success ends the episode.
  const scene::Aabb& seat = g.part_local(kSeatPart);
  const Eigen::Vector3d mid = seat.center();
  s.env->SetState(0, PoseAt(g.ToWorld(Eigen::Vector3d(mid.x(), mid.y(), seat.max.z() + 0.2))));
  sim::TaskStepResult r;
  for (int k = 0; k < 11; ++k) r = u->Step(ViewOf(*s.env, 0));
  EXPECT_TRUE(r.success);
  EXPECT_TRUE(r.truncate);
  EXPECT_EQ(u->steps_completed(0), 2);
  EXPECT_NEAR(u->contact_error(0), 0.2, 0.03);  // nearest seat sample under the pelvis
}

TEST(UnifiedSkillTest, BeginInstructionRunsOneContactStep) {
  const auto loaded =
      LoadScenePlanRef(sims::testing::TestData("scene/sceneplan.json").string() + "#0000",
                       sims::testing::TestData("scene/partnet"));
  const ContactPlan& plan = loaded.plan;
  SkillConfig c;
  c.skill = "unified";
  auto setup = CreateSkill(c, 1, 4, loaded.scene);
  auto* u = dynamic_cast<UnifiedSkill*>(setup.skill.get());
  sim::EnvConfig ec;
  ec.num_envs = 1;
  ec.threads = 1;
  sim::BatchedEnv env(setup.context.humanoid, ec, setup.skill);
  env.Reset();
  ASSERT_EQ(plan.steps.size(), 2u);
  InstructionTarget t;
  t.contact_step = std::make_shared<const ContactStep>(plan.steps[1]);  // pelvis on the seat
  ASSERT_TRUE(u->BeginInstruction(ViewOf(env, 0), t));
  ASSERT_EQ(u->steps(0).size(), 1u);
  EXPECT_EQ(u->step_index(0), 0);
  EXPECT_FALSE(u->steps(0)[0].walking());
  // The pelvis goal is on the seat (not the walking step's stand point), the hands have none.
  const Eigen::Vector3d seat = u->goal(0, humanoid::kCjPelvis);
  EXPECT_FALSE(seat.isApprox(plan.steps[0].stand_point));
  EXPECT_GT(seat.z(), 0.2);
  EXPECT_TRUE(u->goal_mask(0) & (1u << humanoid::kCjPelvis));
  EXPECT_FALSE(u->goal_mask(0) & (1u << humanoid::kCjLeftHand));
  InstructionTarget missing = t;
  auto other = plan.steps[1];
  other.object = 7;  // not in the scene
  missing.contact_step = std::make_shared<const ContactStep>(other);
  EXPECT_FALSE(u->BeginInstruction(ViewOf(env, 0), missing));
}

TEST(UnifiedSkillTest, RunsAScenePlanAndRestoresSnapshots) {
  const auto json = sims::testing::TestData("scene/sceneplan.json");
  auto scene = std::make_shared<const scene::Scene>(
      scene::LoadScenePlan(json, sims::testing::TestData("scene/partnet"), "0000"));
  SkillConfig c;
  c.skill = "unified";
  auto setup = CreateSkill(c, 2, 4, scene);
  auto* u = dynamic_cast<UnifiedSkill*>(setup.skill.get());
  u->SetPlan(LoadContactPlan(json, *scene, "0000").steps);
  sim::EnvConfig ec;
  ec.num_envs = 2;
  ec.threads = 2;
  ec.seed = 9;
  sim::BatchedEnv env(setup.context.humanoid, ec, setup.skill);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(u->steps(i).size(), 2u);
    EXPECT_TRUE(u->goal(i, humanoid::kCjPelvis).isApprox(Eigen::Vector3d(2.5, 2, 0.86)));
  }
  std::vector<float> act(2 * 28, 0.05f);
  for (int t = 0; t < 4; ++t) env.Step(act.data());
  const std::string snap = env.SaveState();
  auto setup2 = CreateSkill(c, 2, 4, scene);
  sim::BatchedEnv env2(setup2.context.humanoid, ec, setup2.skill);
  env2.LoadState(snap);
  for (int t = 0; t < 6; ++t) {
    env.Step(act.data());
    env2.Step(act.data());
  }
  EXPECT_EQ(
      0, std::memcmp(env.observations(), env2.observations(), sizeof(float) * 2 * env.obs_dim()));
}

}  // namespace
}  // namespace sims::task
