#include "sims/fsm/story_runner.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "common/tiny_training.h"
#include "sims/core/error.h"
#include "sims/learning/train_run.h"
#include "sims/learning/trainer.h"
#include "sims/scene/builtin.h"
#include "sims/scene/loaders.h"
#include "sims/task/object_skill.h"

namespace sims::fsm {
namespace {

// Trains `skill` for one tiny iteration into dir/<skill>/policy.pt: a real policy file the
// FSM loads, whose actions the tests replace with scripted ones where it matters.
void TrainTinyPolicy(const std::string& skill, const std::filesystem::path& dir) {
  const learning::TrainConfig c = sims::testing::TinyTrainConfig(skill);
  learning::TrainOptions o;
  o.out_dir = dir / skill;
  learning::RunTraining(c, o);
}

// A real (barely trained) walk policy written by the training job, shared by the tests.
const std::filesystem::path& TinyPolicySet() {
  static const std::filesystem::path set = [] {
    const auto dir = sims::testing::TempDir("policies");
    TrainTinyPolicy("walk", dir);
    std::ofstream(dir / "policies.json") << R"({"policies": {"walk": "walk/policy.pt"}})";
    return dir / "policies.json";
  }();
  return set;
}

// The tiny walk policy plus an equally tiny get-up policy, so the FSM's recovery path runs.
const std::filesystem::path& TinyPolicySetWithGetUp() {
  static const std::filesystem::path set = [] {
    const auto dir = TinyPolicySet().parent_path();
    TrainTinyPolicy("getup", dir);
    std::ofstream(dir / "policies_getup.json")
        << R"({"policies": {"walk": "walk/policy.pt", "getup": "getup/policy.pt"}})";
    return dir / "policies_getup.json";
  }();
  return set;
}

// The tiny walk policy plus a tiny sit policy, whose observation adds the object's (wider).
const std::filesystem::path& TinyPolicySetWithSit() {
  static const std::filesystem::path set = [] {
    const auto dir = TinyPolicySet().parent_path();
    learning::TrainConfig c = sims::testing::TinyTrainConfig("sit");
    c.skill.reference_init_prob = 0;  // no clips needed
    learning::TrainOptions o;
    o.out_dir = dir / "sit";
    learning::RunTraining(c, o);
    std::ofstream(dir / "policies_sit.json")
        << R"({"policies": {"walk": "walk/policy.pt", "sit": "sit/policy.pt"}})";
    return dir / "policies_sit.json";
  }();
  return set;
}

// Walk, get-up, sit and lie policies (the sit and lie ones tiny, trained without clips).
const std::filesystem::path& TinyPolicySetWithSitAndLie() {
  static const std::filesystem::path set = [] {
    const auto dir = TinyPolicySetWithGetUp().parent_path();
    TinyPolicySetWithSit();
    learning::TrainConfig c = sims::testing::TinyTrainConfig("lie");
    c.skill.reference_init_prob = 0;
    learning::TrainOptions o;
    o.out_dir = dir / "lie";
    learning::RunTraining(c, o);
    std::ofstream(dir / "policies_sit_lie.json") << R"({"policies": {"walk": "walk/policy.pt",
        "getup": "getup/policy.pt", "sit": "sit/policy.pt", "lie": "lie/policy.pt"}})";
    return dir / "policies_sit_lie.json";
  }();
  return set;
}

// A walk instruction to world point p (keyframe 0).
Instruction WalkTo(const Eigen::Vector3d& p) {
  Instruction in;
  in.keyframe = 0;
  in.skill = "walk";
  in.caption = "walk";
  in.target.point = p;
  in.target.has_point = true;
  return in;
}

class StoryRunnerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = std::make_shared<scene::Scene>(scene::BuiltinScene("chair"));
    StoryOptions o;
    o.walk_timeout_s = 2.0;
    o.success_hold_steps = 10;
    o.walk_success_hold_steps = 10;
    o.missing_policy_fails = false;  // strict: a story needing a missing policy is an error
    runner_ = std::make_unique<StoryRunner>(scene_, LoadPolicySet(TinyPolicySet()), o);
    // Scripted stand-in: hold the standing pose (the unit under test is the FSM, not a policy).
    runner_->SetActionOverride([this](const std::string&, const float*, float* a) {
      std::fill(a, a + humanoid::kNumDofs, 0.0f);
      const double standing[humanoid::kNumDofs] = {0};
      if (!collapse_)
        runner_->humanoid()->TargetsToAction(standing, a);
      else
        std::fill(a, a + humanoid::kNumDofs, -1.0f);
    });
  }
  std::shared_ptr<scene::Scene> scene_;
  std::unique_ptr<StoryRunner> runner_;
  bool collapse_ = false;
};

TEST_F(StoryRunnerTest, SwitchesAfterSuccessHeldForTheHoldTime) {
  const Eigen::Vector3d start(3, 0, 0);
  io::MotionRecordBuilder rec(runner_->humanoid());
  const auto r = runner_->Run({WalkTo(start), WalkTo(start)}, start, 0.0, &rec);
  ASSERT_EQ(r.keyframes.size(), 2u);
  EXPECT_TRUE(r.keyframes[0].success);
  EXPECT_NEAR(r.keyframes[0].end_time, 10.0 / 30.0, 1e-6) << "switch exactly after 10 held steps";
  EXPECT_TRUE(r.keyframes[1].success);
  EXPECT_EQ(r.success_steps, 2);
  EXPECT_EQ(rec.num_frames(), 21);
}

// A walk succeeds within the story's walk_success_radius of its goal, whatever radius the
// walk policy trained with: a character standing 1 m from its goal arrives with a 1.2 m
// radius and times out with the default 0.5 m.
TEST(StoryWalkRadiusTest, TheStoryDecidesWhenAWalkHasArrived) {
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("empty"));
  auto run = [&](double radius) {
    StoryOptions o;
    o.walk_timeout_s = 1.0;
    o.walk_success_radius = radius;
    StoryRunner runner(scene, LoadPolicySet(TinyPolicySet()), o);
    runner.SetActionOverride([&](const std::string&, const float*, float* a) {
      const double standing[humanoid::kNumDofs] = {0};
      runner.humanoid()->TargetsToAction(standing, a);
    });
    return runner.Run({WalkTo({3, 1, 0})}, {3, 0, 0}, 0.0, nullptr).keyframes.at(0);
  };
  const KeyframeOutcome wide = run(1.2), strict = run(0.5);
  EXPECT_TRUE(wide.success) << wide.note;
  EXPECT_NEAR(wide.contact_error, 1.0, 0.05);
  EXPECT_FALSE(strict.success);
  EXPECT_NE(strict.note.find("time-out"), std::string::npos) << strict.note;
}

TEST_F(StoryRunnerTest, TimeOutRecordsAFailureAndTheStoryGoesOn) {
  const Eigen::Vector3d start(3, 0, 0);
  const auto r = runner_->Run({WalkTo({3, 4, 0}), WalkTo({3, 4.2, 0})}, start, 0.0, nullptr);
  ASSERT_EQ(r.keyframes.size(), 2u);
  EXPECT_FALSE(r.keyframes[0].success);
  EXPECT_NE(r.keyframes[0].note.find("time-out"), std::string::npos);
  EXPECT_NEAR(r.keyframes[0].end_time - r.keyframes[0].start_time, 2.0, 1.0 / 30.0 + 1e-9);
  EXPECT_NEAR(r.keyframes[0].contact_error, 4.0, 0.3);
  EXPECT_EQ(r.keyframes.size(), 2u) << "the second keyframe still ran";
  EXPECT_EQ(r.success_steps, 0);
}

TEST_F(StoryRunnerTest, FallIsDetectedAndRecoveryNeedsAGetUpPolicy) {
  collapse_ = true;
  const auto r = runner_->Run({WalkTo({3, 4, 0})}, {3, 0, 0}, 0.0, nullptr);
  ASSERT_EQ(r.keyframes.size(), 1u);
  EXPECT_EQ(r.keyframes[0].falls, 1);
  EXPECT_FALSE(r.keyframes[0].success);
  EXPECT_NE(r.keyframes[0].note.find("could not get up"), std::string::npos);
}

TEST_F(StoryRunnerTest, WithoutGetUpTheCharacterIsResetStandingAndTheStoryGoesOn) {
  collapse_ = true;
  io::MotionRecordBuilder rec(runner_->humanoid());
  const auto r = runner_->Run({WalkTo({3, 4, 0}), WalkTo({3, 4.2, 0})}, {3, 0, 0}, 0.0, &rec);
  ASSERT_EQ(r.keyframes.size(), 2u);
  EXPECT_NE(r.keyframes[0].note.find("reset standing"), std::string::npos) << r.keyframes[0].note;
  const auto& frames = rec.record().frames;
  // The frame after the fall stands at the default height, and every frame stays on the clock.
  const int first_after = static_cast<int>(std::round(r.keyframes[0].end_time * 30.0));
  ASSERT_LT(first_after, static_cast<int>(frames.size()));
  EXPECT_NEAR(frames[first_after].root_pos.z(), humanoid::kDefaultRootHeight, 1e-6);
  EXPECT_LT(frames[first_after - 1].root_pos.z(), 0.4) << "it had fallen";
  for (size_t f = 0; f < frames.size(); ++f) EXPECT_NEAR(frames[f].time, f / 30.0, 1e-9);
}

TEST(StoryStartTest, StartIsAShortWalkFromTheFirstGoalAndTheSeedTurnsIt) {
  // A 6 m × 6 m walled floor.
  auto room = std::make_shared<scene::Scene>(scene::BuiltinScene("empty"));
  room->walls = scene::TriangleMesh::Box({-3, -3.1, 0}, {3, -3, 2});
  room->walls.Append(scene::TriangleMesh::Box({-3, 3, 0}, {3, 3.1, 2}));
  room->walls.Append(scene::TriangleMesh::Box({-3.1, -3, 0}, {-3, 3, 2}));
  room->walls.Append(scene::TriangleMesh::Box({3, -3, 0}, {3.1, 3, 2}));
  const Instruction walk = WalkTo({0.5, 0, 0});
  StoryRunner canonical_runner(room, LoadPolicySet(TinyPolicySet()), StoryOptions{});
  const Eigen::Vector3d canonical = canonical_runner.DefaultStart({walk});
  const double d0 = (canonical.head<2>() - Eigen::Vector2d(0.5, 0)).norm();
  EXPECT_GE(d0, 2.0 - 1e-9);
  EXPECT_LE(d0, 4.0 + 1e-9);
  EXPECT_TRUE(canonical.isApprox(canonical_runner.DefaultStart({walk}))) << "deterministic";
  StoryOptions o;
  o.seed = 5;
  StoryRunner seeded(room, LoadPolicySet(TinyPolicySet()), o);
  const Eigen::Vector3d turned = seeded.DefaultStart({walk});
  const double d1 = (turned.head<2>() - Eigen::Vector2d(0.5, 0)).norm();
  EXPECT_GE(d1, 2.0 - 1e-9);
  EXPECT_LE(d1, 4.0 + 1e-9);
  EXPECT_GT((turned - canonical).norm(), 0.1) << "another seed starts elsewhere";
}

TEST(StoryRecoveryTest, AFallHandsOverToTheGetUpPolicyBeforeTheStoryGoesOn) {
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("chair"));
  StoryOptions o;
  o.walk_timeout_s = 2.0;
  o.skill_timeout_s = 1.0;
  StoryRunner runner(scene, LoadPolicySet(TinyPolicySetWithGetUp()), o);
  // Scripted stand-ins: the walk collapses, the get-up holds the standing targets (which
  // cannot lift a lying body, so the recovery times out).
  std::vector<std::string> skills_seen;
  runner.SetActionOverride([&](const std::string& skill, const float*, float* a) {
    if (skills_seen.empty() || skills_seen.back() != skill) skills_seen.push_back(skill);
    const double standing[humanoid::kNumDofs] = {0};
    if (skill == "walk")
      std::fill(a, a + humanoid::kNumDofs, -1.0f);
    else
      runner.humanoid()->TargetsToAction(standing, a);
  });
  const Instruction walk = WalkTo({3, 4, 0});
  const auto r = runner.Run({walk}, {3, 0, 0}, 0.0, nullptr);
  ASSERT_EQ(r.keyframes.size(), 1u);
  EXPECT_EQ(r.keyframes[0].falls, 1);
  EXPECT_EQ(skills_seen, (std::vector<std::string>{"walk", "getup"}));
  EXPECT_NE(r.keyframes[0].note.find("could not get up"), std::string::npos);
  // One walk attempt until the fall, then at most the get-up's time-out.
  EXPECT_LE(r.keyframes[0].end_time, 2.0 + 1.0 + 2.0 / 30.0);
  EXPECT_GT(r.keyframes[0].end_time, 1.0) << "the get-up ran for its time-out";
}

// A get-up that succeeds hands the keyframe back for another attempt. Scripted: the fall
// heights are above a standing character's, so every walk attempt "falls" at its first step,
// and the get-up holds the standing pose (standing, upright, only the feet touching the
// floor: the get-up's success). max_retries = 1: walk, get-up, walk again, get-up, and then
// the retries are exhausted; max_retries = 0: one walk, one get-up, exhausted.
TEST(StoryRecoveryTest, ASuccessfulGetUpRetriesTheKeyframeUntilRetriesRunOut) {
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("chair"));
  for (const int max_retries : {1, 0}) {
    StoryOptions o;
    o.walk_timeout_s = 2.0;
    o.skill_timeout_s = 3.0;
    o.max_retries = max_retries;
    o.fallen_head_height = 2.0;
    o.fallen_pelvis_height = 2.0;
    StoryRunner runner(scene, LoadPolicySet(TinyPolicySetWithGetUp()), o);
    std::vector<std::string> skills_seen;
    runner.SetActionOverride([&](const std::string& skill, const float*, float* a) {
      if (skills_seen.empty() || skills_seen.back() != skill) skills_seen.push_back(skill);
      const double standing[humanoid::kNumDofs] = {0};
      runner.humanoid()->TargetsToAction(standing, a);
    });
    const Instruction walk = WalkTo({3, 4, 0});
    const auto r = runner.Run({walk}, {3, 0, 0}, 0.0, nullptr);
    ASSERT_EQ(r.keyframes.size(), 1u);
    const KeyframeOutcome& k = r.keyframes[0];
    EXPECT_EQ(k.retries, max_retries);
    EXPECT_EQ(k.falls, max_retries + 1);
    EXPECT_FALSE(k.success);
    EXPECT_EQ(k.note, "fell; retries exhausted");
    std::vector<std::string> expected;
    for (int attempt = 0; attempt <= max_retries; ++attempt) {
      expected.push_back("walk");
      expected.push_back("getup");
    }
    EXPECT_EQ(skills_seen, expected);
    // Each get-up ended by its success (held), well before its 3 s time-out.
    EXPECT_LT(k.end_time, (max_retries + 1) * 2.0) << "the get-ups timed out";
  }
}

// A script's get-up from the floor (no object) while the character stands succeeds at once:
// standing clear is the get-up's success, so the get-up policy never acts (scripted here to
// collapse, which it would do had it run) and the walk after it starts at time 0.
TEST(StoryRecoveryTest, AGetUpFromTheFloorWhileStandingSucceedsAtOnce) {
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("chair"));
  StoryOptions o;
  o.skill_timeout_s = 3.0;
  o.walk_timeout_s = 0.5;
  StoryRunner runner(scene, LoadPolicySet(TinyPolicySetWithGetUp()), o);
  std::vector<std::string> skills_seen;
  runner.SetActionOverride([&](const std::string& skill, const float*, float* a) {
    if (skills_seen.empty() || skills_seen.back() != skill) skills_seen.push_back(skill);
    const double standing[humanoid::kNumDofs] = {0};
    if (skill == "getup")
      std::fill(a, a + humanoid::kNumDofs, -1.0f);
    else
      runner.humanoid()->TargetsToAction(standing, a);
  });
  Instruction up;
  up.skill = "getup";
  up.caption = "gets up from the floor after falling";
  const auto r = runner.Run({up, WalkTo({3, 2, 0})}, {3, 0, 0}, 0.0, nullptr);
  ASSERT_EQ(r.keyframes.size(), 2u);
  EXPECT_TRUE(r.keyframes[0].success) << r.keyframes[0].note;
  EXPECT_EQ(r.keyframes[0].note, "accomplished at its start");
  EXPECT_EQ(r.keyframes[0].falls, 0);
  EXPECT_EQ(r.keyframes[0].end_time, 0.0);
  EXPECT_EQ(r.keyframes[1].start_time, 0.0);
  EXPECT_EQ(skills_seen, std::vector<std::string>{"walk"});
}

// A lie or a walk (skills whose policies start standing) after a sit on the bed, or after a
// get-up that timed out, runs the get-up first; after a walk the lie starts at once. Scripted:
// the sit collapses (falls are not detected), the get-up holds the standing targets, which
// cannot lift the collapsed body, so it runs to its time-out, and the lie or walk still gets
// its own whole time-out.
TEST(StoryPreparationTest, SkillsThatStartStandingGetUpFirst) {
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("bed"));
  StoryOptions o;
  o.skill_timeout_s = 1.0;
  o.walk_timeout_s = 0.5;
  o.fallen_head_height = 0;
  o.fallen_pelvis_height = 0;
  StoryRunner runner(scene, LoadPolicySet(TinyPolicySetWithSitAndLie()), o);
  std::vector<std::string> skills_seen;
  runner.SetActionOverride([&](const std::string& skill, const float*, float* a) {
    if (skills_seen.empty() || skills_seen.back() != skill) skills_seen.push_back(skill);
    const double standing[humanoid::kNumDofs] = {0};
    if (skill == "sit")
      std::fill(a, a + humanoid::kNumDofs, -1.0f);
    else
      runner.humanoid()->TargetsToAction(standing, a);
  });
  auto on_bed = [](const std::string& skill, int keyframe) {
    Instruction in;
    in.keyframe = keyframe;
    in.skill = skill;
    in.caption = skill;
    in.object_name = "bed_0";
    in.target.object = 0;
    return in;
  };
  const Eigen::Vector3d start(2.0, 0, 0);
  const auto r = runner.Run({on_bed("sit", 0), on_bed("lie", 1)}, start, M_PI, nullptr);
  ASSERT_EQ(r.keyframes.size(), 2u);
  EXPECT_EQ(skills_seen, (std::vector<std::string>{"sit", "getup", "lie"}));
  const KeyframeOutcome& lie = r.keyframes[1];
  EXPECT_NEAR(lie.end_time - lie.start_time, 2.0, 2.0 / 30.0) << "get-up and lie time-outs";
  EXPECT_EQ(lie.falls, 0);

  skills_seen.clear();
  const auto direct = runner.Run({WalkTo(start), on_bed("lie", 1)}, start, M_PI, nullptr);
  ASSERT_EQ(direct.keyframes.size(), 2u);
  EXPECT_EQ(skills_seen, (std::vector<std::string>{"walk", "lie"}));
  EXPECT_NEAR(direct.keyframes[1].end_time - direct.keyframes[1].start_time, 1.0, 2.0 / 30.0);

  skills_seen.clear();
  const auto again =
      runner.Run({on_bed("sit", 0), on_bed("getup", 1), WalkTo(start)}, start, M_PI, nullptr);
  ASSERT_EQ(again.keyframes.size(), 3u);
  EXPECT_FALSE(again.keyframes[1].success);
  EXPECT_EQ(skills_seen, (std::vector<std::string>{"sit", "getup", "walk"}));
  const KeyframeOutcome& walk = again.keyframes[2];
  EXPECT_NEAR(walk.end_time - walk.start_time, 1.5, 2.0 / 30.0) << "get-up and walk time-outs";
}

TEST_F(StoryRunnerTest, MissingSkillPolicyIsAClearError) {
  Instruction sit;
  sit.skill = "sit";
  sit.target.object = 0;
  try {
    runner_->CheckPolicies({sit});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("policies.sit"), std::string::npos) << e.what();
  }
}

// Equal to the bit: outcomes (as result.json has them), keyframe annotations and every frame.
void ExpectSameRun(const StoryResult& a, const io::MotionRecord& ra, const StoryResult& b,
                   const io::MotionRecord& rb) {
  EXPECT_EQ(StoryResultToJson(a), StoryResultToJson(b));
  ASSERT_EQ(ra.num_frames(), rb.num_frames());
  for (int f = 0; f < ra.num_frames(); ++f) {
    const auto &x = ra.frames[f], &y = rb.frames[f];
    ASSERT_TRUE(x.root_pos == y.root_pos && x.root_rot.coeffs() == y.root_rot.coeffs() &&
                x.dof_pos == y.dof_pos)
        << "frame " << f;
  }
  ASSERT_EQ(ra.keyframes.size(), rb.keyframes.size());
  for (size_t k = 0; k < ra.keyframes.size(); ++k) {
    EXPECT_EQ(ra.keyframes[k].start_frame, rb.keyframes[k].start_frame);
    EXPECT_EQ(ra.keyframes[k].end_frame, rb.keyframes[k].end_frame);
    EXPECT_EQ(ra.keyframes[k].success, rb.keyframes[k].success);
    EXPECT_EQ(ra.keyframes[k].detail, rb.keyframes[k].detail);
  }
}

// Characters in different scenes run in lock-step (one policy call per policy per control step
// over all of them, the environments on two threads) do exactly what each does alone; a
// scripted character (an action override) that falls, tries to get up and is reset standing
// mixes with policy-driven ones.
TEST(StoryBatchTest, BatchedStoriesEqualStoriesRunOneAtATime) {
  const PolicySet policies = LoadPolicySet(TinyPolicySetWithGetUp());
  auto walk_to = [](double x, double y) {
    Instruction in;
    in.keyframe = 0;
    in.skill = "walk";
    in.caption = "walk";
    in.target.point = {x, y, 0};
    in.target.has_point = true;
    return in;
  };
  struct Case {
    std::string scene;
    uint64_t seed;
    std::vector<Instruction> instructions;
    Eigen::Vector3d start;
    double heading;
    bool scripted;
  };
  const std::vector<Case> cases = {
      {"chair", 0, {walk_to(3, 4), walk_to(1, 1)}, {3, 0, 0}, 0.5, false},
      {"empty", 7, {walk_to(1, 0), walk_to(-1, 1)}, {0, 0, 0}, -1.0, false},
      {"chair", 0, {walk_to(3, 4), walk_to(3, 0)}, {3, 0, 0}, 0.0, true},
      {"chair", 5, {walk_to(3, 0.5)}, {3, 0, 0}, 2.0, false},
  };
  StoryOptions o;
  o.walk_timeout_s = 2.0;
  o.skill_timeout_s = 0.5;
  std::vector<std::unique_ptr<StoryRunner>> runners;
  auto make_runner = [&](const Case& c) {
    StoryOptions co = o;
    co.seed = c.seed;
    auto r = std::make_unique<StoryRunner>(
        std::make_shared<scene::Scene>(scene::BuiltinScene(c.scene)), policies, co);
    if (c.scripted) {
      const StoryRunner* self = r.get();
      // The walk collapses, the get-up holds the standing targets (and times out).
      r->SetActionOverride([self](const std::string& skill, const float*, float* a) {
        const double standing[humanoid::kNumDofs] = {0};
        if (skill == "walk")
          std::fill(a, a + humanoid::kNumDofs, -1.0f);
        else
          self->humanoid()->TargetsToAction(standing, a);
      });
    }
    return r;
  };
  std::vector<StoryResult> alone;
  std::vector<io::MotionRecord> alone_records;
  for (const Case& c : cases) {
    auto r = make_runner(c);
    io::MotionRecordBuilder rec(r->humanoid());
    alone.push_back(r->Run(c.instructions, c.start, c.heading, &rec));
    alone_records.push_back(rec.Finish());
  }
  std::vector<std::unique_ptr<io::MotionRecordBuilder>> recorders;
  std::vector<StoryJob> jobs;
  for (const Case& c : cases) {
    runners.push_back(make_runner(c));
    recorders.push_back(std::make_unique<io::MotionRecordBuilder>(runners.back()->humanoid()));
    jobs.push_back(
        {runners.back().get(), &c.instructions, c.start, c.heading, recorders.back().get()});
  }
  const std::vector<StoryResult> batched = RunStoriesBatched(jobs, 2);
  ASSERT_EQ(batched.size(), cases.size());
  int falls = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("story " + std::to_string(i));
    ExpectSameRun(alone[i], alone_records[i], batched[i], recorders[i]->Finish());
    falls += alone[i].falls;
  }
  EXPECT_GT(falls, 0) << "the get-up path ran in the batch";
  // A runner runs its next story from scratch.
  io::MotionRecordBuilder again(runners[0]->humanoid());
  const StoryResult rerun =
      runners[0]->Run(cases[0].instructions, cases[0].start, cases[0].heading, &again);
  ExpectSameRun(alone[0], alone_records[0], rerun, again.Finish());
}

// A story that cannot start (a missing policy, strict options) stops alone; the others finish.
TEST(StoryBatchTest, AFailingStoryDoesNotStopTheOthers) {
  const PolicySet policies = LoadPolicySet(TinyPolicySet());
  StoryOptions o;
  o.walk_timeout_s = 0.5;
  o.missing_policy_fails = false;
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("chair"));
  StoryRunner a(scene, policies, o), b(scene, policies, o);
  const Instruction walk = WalkTo({3, 2, 0});
  Instruction sit;
  sit.skill = "sit";
  sit.target.object = 0;
  const std::vector<Instruction> good = {walk}, bad = {sit};
  std::vector<std::exception_ptr> errors;
  const auto r = RunStoriesBatched(
      {{&a, &good, {3, 0, 0}, 0, nullptr}, {&b, &bad, {3, 0, 0}, 0, nullptr}}, 2, &errors);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_FALSE(errors[0]);
  ASSERT_TRUE(errors[1]);
  EXPECT_THROW(std::rethrow_exception(errors[1]), Error);
  ASSERT_EQ(r[0].keyframes.size(), 1u);
  EXPECT_TRUE(r[1].keyframes.empty());
  // Without an error list the first error is thrown.
  EXPECT_THROW(
      RunStoriesBatched({{&a, &good, {3, 0, 0}, 0, nullptr}, {&b, &bad, {3, 0, 0}, 0, nullptr}}),
      Error);
}

// Sit on object 0 (keyframe 1).
Instruction SitOnObject0() {
  Instruction in;
  in.keyframe = 1;
  in.skill = "sit";
  in.caption = "sit";
  in.target.object = 0;
  return in;
}

// Walk's policy and the wider sit policy run in one story: each policy gets its own skill's
// layout, the walk's row with nothing past its width, the sit's with the object it sits on.
TEST(StoryMixedWidthTest, EachPolicySeesItsOwnSkillsObservation) {
  const PolicySet policies = LoadPolicySet(TinyPolicySetWithSit());
  const int walk_dim = learning::Policy(policies.File("walk")).obs_dim();
  const int sit_dim = learning::Policy(policies.File("sit")).obs_dim();
  ASSERT_EQ(sit_dim, walk_dim + task::kObjectObsDim);
  StoryOptions o;
  o.walk_timeout_s = 0.5;
  o.skill_timeout_s = 0.5;
  StoryRunner runner(std::make_shared<scene::Scene>(scene::BuiltinScene("chair")), policies, o);
  std::map<std::string, int> calls;
  runner.SetActionOverride([&](const std::string& skill, const float* obs, float* a) {
    ++calls[skill];
    if (skill == "walk") {
      for (int j = walk_dim; j < sit_dim; ++j) ASSERT_EQ(obs[j], 0.0f) << "walk row, value " << j;
    } else {
      // The object slice: the target and the box corners relative to the pelvis.
      const float* object = obs + humanoid::kSelfObsDim + task::kContactGoalDim;
      double norm = 0;
      for (int j = 0; j < task::kObjectObsDim; ++j) norm += std::abs(object[j]);
      ASSERT_GT(norm, 1.0) << "the sit policy sees its object";
    }
    const double standing[humanoid::kNumDofs] = {0};
    runner.humanoid()->TargetsToAction(standing, a);
  });
  const auto r = runner.Run({WalkTo({2, 0, 0}), SitOnObject0()}, {3, 0, 0}, 0.0, nullptr);
  ASSERT_EQ(r.keyframes.size(), 2u);
  EXPECT_GT(calls["walk"], 0);
  EXPECT_GT(calls["sit"], 0);
}

// A policy set's action_smoothing blends each step's targets with those held before: a scripted
// walk that flips the elbow's target between −0.4 and −1.2 rad every step moves it far less with
// α = 0.5 (its targets swing a third as far, (1 − α)/(1 + α); the arm, slower than 30 Hz, about
// two thirds as far); smoothing for a skill the set has no policy for, or beyond
// kMaxActionSmoothing, is the set file's error.
TEST(StoryActionSmoothingTest, SmoothingDampsAJitteringPolicy) {
  const auto dir = TinyPolicySet().parent_path();
  std::ofstream(dir / "policies_smooth.json")
      << R"({"policies": {"walk": "walk/policy.pt"}, "action_smoothing": {"walk": 0.5}})";
  const PolicySet smooth = LoadPolicySet(dir / "policies_smooth.json");
  EXPECT_DOUBLE_EQ(smooth.action_smoothing.at("walk"), 0.5);
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("empty"));
  constexpr int kHinge = 9;  // right elbow: light, so it follows its target within a step
  auto swing = [&](const PolicySet& set) {
    StoryOptions o;
    o.walk_timeout_s = 1.0;
    StoryRunner runner(scene, set, o);
    int calls = 0;
    runner.SetActionOverride([&](const std::string&, const float*, float* a) {
      double targets[humanoid::kNumDofs] = {0};
      targets[kHinge] = (calls++ % 2 ? -1.2 : -0.4);
      runner.humanoid()->TargetsToAction(targets, a);
    });
    io::MotionRecordBuilder rec(runner.humanoid());
    runner.Run({WalkTo({3, 4, 0})}, {3, 0, 0}, 0.0, &rec);
    const io::MotionRecord m = rec.Finish();
    // After the first third: the elbow has left its start pose and only swings.
    const size_t from = m.frames.size() / 3;
    double sum = 0;
    for (size_t t = from + 1; t < m.frames.size(); ++t)
      sum += std::abs(m.frames[t].dof_pos[kHinge] - m.frames[t - 1].dof_pos[kHinge]);
    return sum / (m.frames.size() - from - 1);
  };
  const double raw = swing(LoadPolicySet(TinyPolicySet())), damped = swing(smooth);
  EXPECT_GT(raw, 0.03) << "the scripted walk jitters";
  EXPECT_LT(damped, 0.75 * raw) << "raw " << raw << " rad/step, smoothed " << damped;

  for (const char* bad : {R"({"policies": {"walk": "walk/policy.pt"},
                                     "action_smoothing": {"sit": 0.3}})",
                          R"({"policies": {"walk": "walk/policy.pt"},
                                     "action_smoothing": {"walk": 0.95}})"}) {
    std::ofstream(dir / "policies_bad_smooth.json") << bad;
    const std::string e =
        sims::testing::ErrorOf([&] { LoadPolicySet(dir / "policies_bad_smooth.json"); });
    EXPECT_NE(e.find("policies_bad_smooth.json"), std::string::npos) << e;
    EXPECT_NE(e.find("action_smoothing."), std::string::npos) << e;
  }
}

// One environment computes every policy's self observation at one control rate, so a policy
// trained at another rate is the set's mistake, named with its file.
TEST(StoryMixedWidthTest, APolicyWithOtherEnvSettingsIsRejectedByName) {
  const auto dir = TinyPolicySet().parent_path();
  learning::TrainConfig c = sims::testing::TinyTrainConfig("sit");
  c.skill.reference_init_prob = 0;
  c.env.substeps = 2;  // 60 Hz control instead of the walk policy's 30 Hz
  learning::TrainOptions o;
  o.out_dir = dir / "sit_60hz";
  learning::RunTraining(c, o);
  std::ofstream(dir / "policies_60hz.json")
      << R"({"policies": {"walk": "walk/policy.pt", "sit": "sit_60hz/policy.pt"}})";
  const PolicySet policies = LoadPolicySet(dir / "policies_60hz.json");
  try {
    StoryRunner runner(std::make_shared<scene::Scene>(scene::BuiltinScene("chair")), policies,
                       StoryOptions{});
    FAIL() << "a policy at another control rate was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sit_60hz"), std::string::npos) << what;
    EXPECT_NE(what.find("substeps"), std::string::npos) << what;
  }
}

// The same stories with the real (tiny) policies, batched (each policy's rows of its own
// width in one call) and one at a time, to the bit.
TEST(StoryMixedWidthTest, BatchedStoriesWithBothWidthsEqualStoriesRunAlone) {
  const PolicySet policies = LoadPolicySet(TinyPolicySetWithSit());
  const std::vector<Instruction> story = {WalkTo({2, 0, 0}), SitOnObject0()};
  StoryOptions o;
  o.walk_timeout_s = 0.5;
  o.skill_timeout_s = 0.5;
  auto scene = std::make_shared<scene::Scene>(scene::BuiltinScene("chair"));
  auto make_runner = [&](uint64_t seed) {
    StoryOptions so = o;
    so.seed = seed;
    return std::make_unique<StoryRunner>(scene, policies, so);
  };
  const std::vector<uint64_t> seeds = {0, 3, 4};
  std::vector<StoryResult> alone;
  std::vector<io::MotionRecord> alone_records;
  for (uint64_t seed : seeds) {
    auto r = make_runner(seed);
    io::MotionRecordBuilder rec(r->humanoid());
    alone.push_back(r->Run(story, {3, 0, 0}, 0.1 * seed, &rec));
    alone_records.push_back(rec.Finish());
  }
  std::vector<std::unique_ptr<StoryRunner>> runners;
  std::vector<std::unique_ptr<io::MotionRecordBuilder>> recorders;
  std::vector<StoryJob> jobs;
  for (uint64_t seed : seeds) {
    runners.push_back(make_runner(seed));
    recorders.push_back(std::make_unique<io::MotionRecordBuilder>(runners.back()->humanoid()));
    jobs.push_back({runners.back().get(), &story, {3, 0, 0}, 0.1 * seed, recorders.back().get()});
  }
  const std::vector<StoryResult> batched = RunStoriesBatched(jobs, 2);
  for (size_t i = 0; i < seeds.size(); ++i) {
    SCOPED_TRACE("story " + std::to_string(i));
    ASSERT_EQ(alone[i].keyframes.size(), 2u);
    ExpectSameRun(alone[i], alone_records[i], batched[i], recorders[i]->Finish());
  }
}

// The heightmap values a story's walk policy sees at its first step from `start` in the
// built-in chair scene (walk's layout: contact goals, then the heightmap).
std::vector<float> FirstWalkHeightmap(const std::filesystem::path& set,
                                      const Eigen::Vector3d& start) {
  StoryOptions o;
  o.walk_timeout_s = 0.1;
  StoryRunner runner(std::make_shared<scene::Scene>(scene::BuiltinScene("chair")),
                     LoadPolicySet(set), o);
  std::vector<float> heightmap;
  runner.SetActionOverride([&](const std::string&, const float* obs, float* a) {
    const float* h = obs + humanoid::kSelfObsDim + task::kContactGoalDim;
    if (heightmap.empty()) heightmap.assign(h, h + 16 * 16);
    std::fill(a, a + humanoid::kNumDofs, 0.0f);
  });
  runner.Run({WalkTo({3, 0, 0})}, start, 0.0, nullptr);
  return heightmap;
}

// A walk trained in furnished rooms (walk_rooms > 0) sees the story scene's heightmap, as in
// its training; the open-floor walk sees the flat floor's next to the same chair.
TEST(StoryHeightmapTest, AWalkTrainedAmongFurnitureSeesTheScene) {
  const auto dir = TinyPolicySet().parent_path();
  learning::TrainConfig c = sims::testing::TinyTrainConfig("walk");
  c.skill.walk.rooms = 1;
  learning::TrainOptions t;
  t.out_dir = dir / "walk_rooms";
  learning::RunTraining(c, t);
  std::ofstream(dir / "policies_rooms.json") << R"({"policies": {"walk": "walk_rooms/policy.pt"}})";
  const Eigen::Vector3d beside_chair(0.6, 0, 0);  // the chair stands at the origin
  const auto spread = [](const std::vector<float>& h) {
    return *std::max_element(h.begin(), h.end()) - *std::min_element(h.begin(), h.end());
  };
  EXPECT_EQ(spread(FirstWalkHeightmap(TinyPolicySet(), beside_chair)), 0.0f);
  EXPECT_GT(spread(FirstWalkHeightmap(dir / "policies_rooms.json", beside_chair)), 0.3f);
}

TEST(InstructionTest, ScenePlanStepsBecomeWalkAndUnifiedInstructions) {
  const auto json = sims::testing::TestData("scene/sceneplan.json");
  const auto scene = scene::LoadScenePlan(json, sims::testing::TestData("scene/partnet"), "0000");
  const auto plan = task::LoadContactPlan(json, scene, "0000");
  const auto in = BuildInstructions(plan, scene);
  ASSERT_EQ(in.size(), 2u);
  EXPECT_EQ(in[0].skill, "walk");
  EXPECT_TRUE(in[0].target.has_point);
  EXPECT_TRUE(in[0].target.point.isApprox(Eigen::Vector3d(2.5, 2, 0)));
  EXPECT_EQ(in[0].object_name, "chair000");
  EXPECT_EQ(in[1].skill, "unified");
  ASSERT_TRUE(in[1].target.contact_step);
  EXPECT_EQ(in[1].target.contact_step->mask(), 1u << humanoid::kCjPelvis);
  EXPECT_NE(in[1].caption.find("pelvis on"), std::string::npos) << in[1].caption;
}

}  // namespace
}  // namespace sims::fsm
