// Adding a skill = one class + one registry line (README "Add a skill"): a toy skill defined
// here, registered with task::RegisterSkill and nothing else, trains (train_policy's job),
// evaluates (eval_policy's code path) and runs as a story instruction through the FSM.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "common/tiny_training.h"
#include "sims/eval/policy_eval.h"
#include "sims/fsm/policy_set.h"
#include "sims/fsm/story_runner.h"
#include "sims/humanoid/features.h"
#include "sims/learning/train_run.h"
#include "sims/scene/builtin.h"
#include "sims/task/skill.h"

namespace sims::story {
namespace {

namespace fs = std::filesystem;

// The toy skill's own settings: declared in its SkillInfo, so SkillConfig needs no member.
struct StandParams {
  double radius = 0.3;  // success distance (m)
  double kernel = 4.0;  // reward exp(−kernel·d²)

  template <class A>
  void Serialize(A* a) {
    a->Visit(MakeNameValue("toy_stand_radius", &radius));
    a->Visit(MakeNameValue("toy_stand_kernel", &kernel));
  }
  void Validate() const { Require(radius > 0, "toy_stand_radius", "a positive distance (m)"); }
};

// Stand: keep the pelvis at standing height over the spot where the task began.
class StandSkill : public task::Skill {
 public:
  StandSkill(const task::SkillConfig& c, const task::SkillContext& ctx)
      : Skill(c, ctx), params_(task::SkillParams<StandParams>(c)) {}
  const StandParams& params() const { return params_; }
  std::string name() const override { return "toy_stand"; }
  void OnReset(const sim::EnvView& view, Rng&) override { Aim(view); }
  bool BeginInstruction(const sim::EnvView& view, const task::InstructionTarget&) override {
    Aim(view);
    return true;
  }
  sim::TaskStepResult Step(const sim::EnvView& view) override {
    const double d = (view.pose->root_pos - goal(view.env_id, humanoid::kCjPelvis)).norm();
    sim::TaskStepResult r;
    r.reward = static_cast<float>(std::exp(-params_.kernel * d * d));
    r.success = d < params_.radius;
    return r;
  }

 private:
  StandParams params_;
  void Aim(const sim::EnvView& view) {
    const Eigen::Vector3d& p = view.pose->root_pos;
    ClearGoals(view.env_id);
    SetGoal(view.env_id, humanoid::kCjPelvis, {p.x(), p.y(), humanoid::kDefaultRootHeight});
  }
};

task::SkillInfo StandSkillInfo() {
  task::SkillInfo info;
  info.traits.name = "toy_stand";
  info.traits.description = "stand still where the task begins";
  task::DeclareParams<StandParams>(&info);
  info.build_scene = [](const task::SkillConfig&, Rng&) { return scene::Scene{}; };
  info.create = [](const task::SkillConfig& c, const task::SkillContext& ctx) {
    return std::make_shared<StandSkill>(c, ctx);
  };
  return info;
}

// The one registry line (once per test process).
const task::SkillInfo& ToySkill() {
  static const task::SkillInfo& info = task::RegisterSkill(StandSkillInfo());
  return info;
}

// Trains `skill` for two tiny iterations into dir/<skill>/policy.pt.
fs::path TrainTiny(const std::string& skill, const fs::path& dir) {
  learning::TrainConfig c = sims::testing::TinyTrainConfig(skill);
  c.iterations = 2;
  learning::TrainOptions o;
  o.out_dir = dir / skill;
  learning::RunTraining(c, o);
  return dir / skill / "policy.pt";
}

TEST(ToySkillTest, RegisteredSkillTrainsEvaluatesAndRunsInAStory) {
  ASSERT_EQ(ToySkill().name(), "toy_stand");
  EXPECT_EQ(&task::FindSkill("toy_stand"), &ToySkill());
  ASSERT_NE(FindSkillTraits("toy_stand"), nullptr);

  const fs::path dir = sims::testing::TempDir("toy_skill");
  const fs::path toy = TrainTiny("toy_stand", dir);
  ASSERT_TRUE(fs::exists(toy));
  // The run's resolved config lists the toy skill's own keys, flat like every skill key.
  const nlohmann::json written = ReadJsonFile(dir / "toy_stand" / "config.json");
  EXPECT_EQ(written["skill"]["toy_stand_radius"], 0.3);
  EXPECT_EQ(written["skill"]["toy_stand_kernel"], 4.0);

  eval::PolicyEvalOptions eo;
  eo.checkpoint = toy;
  eo.trials = 2;
  eo.num_envs = 2;
  eo.threads = 1;
  const eval::PolicyEvalReport rep = eval::EvaluatePolicy(eo);
  EXPECT_EQ(rep.skill, "toy_stand");
  EXPECT_EQ(rep.trials, 2);
  EXPECT_GE(rep.success_rate, 0.0);
  EXPECT_LE(rep.success_rate, 1.0);

  // A story needs the required skills (walk) besides the toy one.
  TrainTiny("walk", dir);
  std::ofstream(dir / "policies.json")
      << R"({"policies": {"walk": "walk/policy.pt", "toy_stand": "toy_stand/policy.pt"}})";
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("chair"));
  fsm::StoryOptions so;
  so.success_hold_steps = 10;
  fsm::StoryRunner runner(scene, fsm::LoadPolicySet(dir / "policies.json"), so);
  // Hold the standing pose: the unit under test is the FSM binding, not the tiny policy.
  std::vector<std::string> ran;
  runner.SetActionOverride([&](const std::string& skill, const float*, float* a) {
    if (ran.empty() || ran.back() != skill) ran.push_back(skill);
    const double standing[humanoid::kNumDofs] = {0};
    runner.humanoid()->TargetsToAction(standing, a);
  });
  fsm::Instruction in;
  in.keyframe = 0;
  in.skill = "toy_stand";
  in.caption = "stand still";
  const Eigen::Vector3d start(3, 0, 0);
  const fsm::StoryResult r = runner.Run({in}, start, 0.0, nullptr);
  ASSERT_EQ(r.keyframes.size(), 1u);
  EXPECT_EQ(r.keyframes[0].skill, "toy_stand");
  EXPECT_TRUE(r.keyframes[0].success) << r.keyframes[0].note;
  EXPECT_NEAR(r.keyframes[0].end_time, 10.0 / 30.0, 1e-6) << "object timing: 10 held steps";
  EXPECT_EQ(ran, std::vector<std::string>{"toy_stand"});
}

// The toy skill's params are read from the flat skill config like a built-in skill's, checked
// against what it declared (unknown keys, types, ranges), and round-trip.
TEST(ToySkillTest, RegisteredSkillParamsAreLoadedCheckedAndRoundTripped) {
  ASSERT_EQ(ToySkill().name(), "toy_stand");
  EXPECT_TRUE(ToySkill().params.contains("toy_stand_radius"));
  const auto load = [](const nlohmann::json& j) {
    return ConfigFromJson<task::SkillConfig>(j, "toy.json");
  };
  const task::SkillConfig c = load({{"skill", "toy_stand"}, {"toy_stand_radius", 0.5}});
  EXPECT_EQ(task::SkillParams<StandParams>(c).radius, 0.5);
  EXPECT_EQ(task::SkillParams<StandParams>(c).kernel, 4.0);  // default
  const task::SkillConfig back = load(ConfigToJson(c));
  EXPECT_EQ(back.params, c.params);
  EXPECT_EQ(ConfigToJson(back), ConfigToJson(c));

  // The skill object built from the config sees the value.
  auto setup = task::CreateSkill(c, 1, 0);
  auto* stand = dynamic_cast<StandSkill*>(setup.skill.get());
  ASSERT_NE(stand, nullptr);
  EXPECT_EQ(stand->params().radius, 0.5);

  const auto error_of = [&](const nlohmann::json& j) {
    try {
      load(j);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string typo = error_of({{"skill", "toy_stand"}, {"toy_stand_raduis", 0.5}});
  EXPECT_NE(typo.find("toy.json"), std::string::npos) << typo;
  EXPECT_NE(typo.find("field 'toy_stand_raduis': expected a known field"), std::string::npos)
      << typo;
  EXPECT_NE(typo.find("toy_stand_radius"), std::string::npos) << typo;
  const std::string range = error_of({{"skill", "toy_stand"}, {"toy_stand_radius", -1.0}});
  EXPECT_NE(range.find("field 'toy_stand_radius': expected a positive distance"), std::string::npos)
      << range;
  const std::string type = error_of({{"skill", "toy_stand"}, {"toy_stand_kernel", "wide"}});
  EXPECT_NE(type.find("field 'toy_stand_kernel': expected a number"), std::string::npos) << type;
  // Another skill's keys are not this skill's.
  const std::string other = error_of({{"skill", "walk"}, {"toy_stand_radius", 0.5}});
  EXPECT_NE(other.find("field 'toy_stand_radius': expected a known field"), std::string::npos)
      << other;
}

}  // namespace
}  // namespace sims::story
