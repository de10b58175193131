#include "sims/eval/policy_eval.h"

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/eval/motion_metrics.h"
#include "sims/io/motion_record.h"
#include "sims/learning/sim_vec_env.h"
#include "sims/learning/train_run.h"
#include "sims/learning/trainer.h"
#include "sims/motion/motion_library.h"
#include "sims/motion/synthetic.h"
#include "sims/task/handoff.h"

namespace sims::eval {
namespace {

namespace fs = std::filesystem;

// A policy after one tiny PPO iteration on 2 envs, exported with train_policy's metadata.
fs::path TinyPolicy(const task::SkillConfig& sc, int episode_length, const std::string& tag) {
  sim::EnvConfig ec;
  ec.num_envs = 2;
  ec.threads = 2;
  ec.seed = 1;
  ec.episode_length = episode_length;
  auto setup = task::CreateSkill(sc, ec.num_envs, ec.seed);
  auto env = std::make_shared<sim::BatchedEnv>(setup.context.humanoid, ec, setup.skill);
  learning::LearnerConfig lc;
  lc.network.actor_hidden = {16};
  lc.network.critic_hidden = {16};
  lc.network.disc_hidden = {8};
  lc.network.heightmap_hidden = {8};
  lc.ppo.horizon = 4;
  lc.ppo.minibatch_size = 8;
  lc.ppo.mini_epochs = 1;
  lc.amp.enabled = false;
  learning::Trainer trainer(std::make_shared<learning::SimVecEnv>(env), nullptr, lc);
  trainer.RunIteration();
  const fs::path path = sims::testing::TempDir(tag) / "policy.pt";
  const nlohmann::json extra = {{"skill", ConfigToJson(sc)}, {"env", ConfigToJson(ec)}};
  trainer.ExportPolicy(path, extra.dump());
  return path;
}

task::SkillConfig WalkConfig() {
  task::SkillConfig sc;
  sc.skill = "walk";
  return sc;
}

void ExpectError(const std::function<void()>& f, const std::vector<std::string>& words) {
  try {
    f();
    FAIL() << "no error";
  } catch (const Error& e) {
    for (const auto& w : words)
      EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what() << " / " << w;
  }
}

// `trials` trials of `policy` on 2 envs and 2 threads.
PolicyEvalOptions TwoEnvOptions(const fs::path& policy, int trials) {
  PolicyEvalOptions o;
  o.checkpoint = policy;
  o.trials = trials;
  o.num_envs = 2;
  o.threads = 2;
  o.num_objects = 0;  // the tiny policies' own grounds (2 pieces) keep the tests quick
  return o;
}

TEST(PolicyEvalTest, WalkSmokeAndDeterminism) {
  const fs::path policy = TinyPolicy(WalkConfig(), 40, "eval_walk");
  PolicyEvalOptions o = TwoEnvOptions(policy, 3);
  o.seed = 5;
  const PolicyEvalReport r = EvaluatePolicy(o);
  EXPECT_EQ(r.skill, "walk");
  ASSERT_EQ(r.results.size(), 3u);
  for (const auto& t : r.results) {
    EXPECT_GT(t.length, 0);
    EXPECT_LE(t.length, 40);
    EXPECT_EQ(t.num_steps, 1);
    // Targets are 3–5 m away; an untrained policy ends 2.5 m or more from them.
    EXPECT_GT(t.contact_error, 2.0);
    EXPECT_FALSE(t.success);
  }
  EXPECT_EQ(r.success_rate, 0.0);
  const nlohmann::json j = r.ToJson();
  for (const char* key : {"success_rate", "fall_rate", "contact_error", "success_steps",
                          "time_to_success_s", "results", "trials"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["results"].size(), 3u);
  EXPECT_EQ(EvaluatePolicy(o).ToJson().dump(), j.dump());  // same seed, same report
}

// --record: the first trials' motions, one frame per control step plus the start, with the
// outcome as their keyframe, and a glTF of scene and character beside each; later trials and
// the report itself are unchanged by recording.
TEST(PolicyEvalTest, RecordWritesTheFirstTrialsMotions) {
  task::SkillConfig sc;
  sc.skill = "sit";
  sc.object.num_objects = 2;
  const fs::path policy = TinyPolicy(sc, 12, "eval_record");
  PolicyEvalOptions o = TwoEnvOptions(policy, 3);
  const std::string plain = EvaluatePolicy(o).ToJson().dump();
  o.record_dir = sims::testing::TempDir("eval_record_out");
  o.record_trials = 2;
  const PolicyEvalReport r = EvaluatePolicy(o);
  EXPECT_EQ(r.ToJson().dump(), plain);
  for (int k = 0; k < 2; ++k) {
    const fs::path motion = o.record_dir / ("trial_" + std::to_string(k) + ".json");
    ASSERT_TRUE(fs::exists(motion)) << motion;
    EXPECT_GT(fs::file_size(o.record_dir / ("trial_" + std::to_string(k) + ".glb")), 1000u);
    const io::MotionRecord m = io::LoadMotionRecord(motion);
    EXPECT_EQ(m.num_frames(), r.results[k].length) << "the start and every step but the last";
    ASSERT_EQ(m.keyframes.size(), 1u);
    EXPECT_EQ(m.keyframes[0].skill, "sit");
    EXPECT_EQ(m.keyframes[0].success, r.results[k].success);
    EXPECT_NE(m.keyframes[0].detail.find("steps"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(o.record_dir / "trial_2.json"));

  // The report's foot sliding pools every trial's steps: the same figure as the motion metric
  // over all recorded trials (their positions are stored to 6 decimals).
  o.record_dir = sims::testing::TempDir("eval_record_all");
  o.record_trials = 3;
  const PolicyEvalReport all = EvaluatePolicy(o);
  double total = 0;
  int pairs = 0;
  for (int k = 0; k < 3; ++k) {
    const FootSliding s = MeasureFootSliding(
        io::LoadMotionRecord(o.record_dir / ("trial_" + std::to_string(k) + ".json")));
    total += s.mean_speed * s.contact_pairs;
    pairs += s.contact_pairs;
  }
  ASSERT_GT(pairs, 0);
  EXPECT_NEAR(all.foot_sliding, total / pairs, 1e-3);
  EXPECT_GT(all.foot_sliding, 0.0);
  EXPECT_TRUE(all.ToJson().contains("foot_sliding_m_per_s"));
  // The untrained policy's targets move from step to step.
  EXPECT_GT(all.action_rate_rms, 0.0);
  EXPECT_TRUE(all.ToJson().contains("action_rate_rms"));
}

// --end-states keeps where each sit trial that did not fall ended, relative to its seat.
TEST(PolicyEvalTest, EndStatesAreKeptRelativeToTheSeat) {
  task::SkillConfig sc;
  sc.skill = "sit";
  sc.object.num_objects = 2;
  const fs::path policy = TinyPolicy(sc, 12, "eval_end_states");
  PolicyEvalOptions o = TwoEnvOptions(policy, 4);
  const std::string plain = EvaluatePolicy(o).ToJson().dump();
  o.end_states = sims::testing::TempDir("eval_end_states_out") / "ends.json";
  const PolicyEvalReport r = EvaluatePolicy(o);
  EXPECT_EQ(r.ToJson().dump(), plain) << "recording changes nothing";
  const std::vector<task::HandoffState> ends = task::LoadHandoffStates(o.end_states);
  int kept = 0;
  for (const TrialResult& t : r.results) {
    kept += !t.fell && !t.force_end;
    // Each trial names its piece, its size and how far from it the character started.
    EXPECT_EQ(t.object.rfind("chair_", 0) == 0 || t.object.rfind("armchair_", 0) == 0 ||
                  t.object.rfind("sofa_", 0) == 0 || t.object.rfind("stool_", 0) == 0,
              true)
        << t.object;
    EXPECT_GT(t.object_extent.minCoeff(), 0.2);
    EXPECT_GT(t.start_distance, 0.5);
    EXPECT_LT(t.start_distance, 6.0);
  }
  EXPECT_TRUE(r.ToJson()["results"][0].contains("object_extent"));
  ASSERT_GT(kept, 0);
  ASSERT_EQ(static_cast<int>(ends.size()), kept);
  for (const task::HandoffState& e : ends) {
    EXPECT_EQ(e.skill, "sit");
    EXPECT_EQ(e.part, std::string(task::kSeatPart));
    // A 12-step trial ends where it started: standing 1-5 m from the object, on the floor.
    const double d = (e.pose.root_pos.head<2>() - e.part_O.center().head<2>()).norm();
    EXPECT_GT(d, 0.3);
    EXPECT_LT(d, 6.0);
    EXPECT_GT(e.pose.root_pos.z(), 0.5);
  }
  // The evaluation ground's size is the option's, not the training's: 2 pieces given
  // explicitly are the policy's own ground, 3 a different test set.
  o.end_states.clear();
  o.num_objects = 2;
  EXPECT_EQ(EvaluatePolicy(o).ToJson().dump(), plain);
  o.num_objects = 3;
  EXPECT_NE(EvaluatePolicy(o).ToJson().dump(), plain);
  o.num_objects = -1;
  ExpectError([&] { EvaluatePolicy(o); }, {"--objects", "non-negative"});
  o.num_objects = 0;
  o.end_states = sims::testing::TempDir("eval_end_states_out") / "ends.json";
  o.checkpoint = TinyPolicy(WalkConfig(), 12, "eval_end_states_walk");
  ExpectError([&] { EvaluatePolicy(o); }, {"--end-states", "walk"});
}

// The success path: a walk task whose success radius reaches past the 3–5 m evaluation
// targets is met from the first control step by any policy that has not fallen, so an untrained
// policy completes every trial once it has held for success_hold_steps (3 here); a radius
// inside that range splits the trials by target distance. Episodes of 10 steps (1/3 s) end
// before an untrained humanoid can fall or move far.
TEST(PolicyEvalTest, SuccessesAreCountedAndTimed) {
  task::SkillConfig sc = WalkConfig();
  sc.walk.success_radius = 6.0;
  sc.success_hold_steps = 3;
  const fs::path policy = TinyPolicy(sc, 10, "eval_success");
  PolicyEvalOptions o = TwoEnvOptions(policy, 6);
  o.seed = 2;
  const PolicyEvalReport all = EvaluatePolicy(o);
  for (const auto& t : all.results) {
    EXPECT_TRUE(t.success);
    EXPECT_FALSE(t.fell);
    EXPECT_EQ(t.success_step, 3);  // completed once success held for 3 steps
    EXPECT_EQ(t.steps_completed, 1);
    EXPECT_EQ(t.length, 9);           // ended by time: the reset state is the first of the 10
    EXPECT_GT(t.contact_error, 2.5);  // still far from the target: success came from the radius
  }
  EXPECT_EQ(all.success_rate, 1.0);
  EXPECT_EQ(all.success_steps, 1.0);
  EXPECT_DOUBLE_EQ(all.time_to_success, 3 * all.control_dt);
  EXPECT_DOUBLE_EQ(all.ToJson()["time_to_success_s"].get<double>(), 3 * all.control_dt);

  // Same policy, radius 4 m (a config replacing the metadata): trials whose target lies within
  // 4 m succeed at once, the others never do; the aggregates count only the successes.
  learning::TrainConfig tc;
  tc.skill = sc;
  tc.skill.walk.success_radius = 4.0;
  tc.env = learning::ReadPolicyConfigs(learning::Policy(policy), policy.string()).env.value();
  const fs::path cfg = sims::testing::TempDir("eval_success_cfg") / "walk.json";
  SaveConfig(cfg, tc);
  o.config = cfg;
  const PolicyEvalReport some = EvaluatePolicy(o);
  int successes = 0;
  for (const auto& t : some.results) {
    successes += t.success;
    EXPECT_EQ(t.success_step, t.success ? 3 : -1);
    EXPECT_EQ(t.steps_completed, t.success ? 1 : 0);
    if (t.success)
      EXPECT_LT(t.contact_error, 4.2);
    else
      EXPECT_GT(t.contact_error, 3.8);
  }
  ASSERT_GT(successes, 0);
  ASSERT_LT(successes, 6) << "pick a seed whose targets fall on both sides of 4 m";
  EXPECT_DOUBLE_EQ(some.success_rate, successes / 6.0);
  EXPECT_DOUBLE_EQ(some.success_steps, successes / 6.0);
  EXPECT_DOUBLE_EQ(some.time_to_success, 3 * some.control_dt);  // mean over successes only
}

TEST(PolicyEvalTest, BadInputNamesTheProblem) {
  const fs::path policy = TinyPolicy(WalkConfig(), 20, "eval_bad");
  PolicyEvalOptions o;
  o.checkpoint = policy;
  o.trials = 1;
  o.skill = "sit";
  ExpectError([&] { EvaluatePolicy(o); }, {"policy.pt", "'sit'", "'walk'"});
  o.skill.clear();
  // A config whose heightmap differs from the policy's layout.
  learning::TrainConfig tc;
  tc.skill = WalkConfig();
  tc.skill.heightmap.size_x = tc.skill.heightmap.size_y = 8;
  const fs::path cfg = sims::testing::TempDir("eval_cfg") / "walk.json";
  SaveConfig(cfg, tc);
  o.config = cfg;
  ExpectError([&] { EvaluatePolicy(o); }, {"policy.pt", "obs_dim", "metadata"});
  o.config.clear();
  o.scene_plan = sims::testing::TestData("scene/sceneplan.json").string();
  ExpectError([&] { EvaluatePolicy(o); }, {"unified", "'walk'"});
  o.scene_plan.clear();
  o.checkpoint = policy.parent_path() / "missing.pt";
  EXPECT_THROW(EvaluatePolicy(o), Error);
}

// --style-eval on a style-conditioned walk policy: trial k walks with the z of a held-out
// caption of emotion k mod E (the bundled motion-text model embeds it), its motion is labelled
// by the classifier trained on the catalogue's first variants, and the accuracy is the share of
// trials labelled as their emotion. The classifier's own held-out score comes with it.
TEST(PolicyEvalTest, StyleEvalCyclesEmotionsAndScoresTheMotion) {
  motion::SyntheticOptions so;
  so.variants = 2;
  so.skills = {"walk"};
  const fs::path manifest = motion::WriteMotionDataset(
      motion::GenerateSyntheticClips(so), sims::testing::TempDir("eval_style_clips"), "walk");
  task::SkillConfig sc = WalkConfig();
  sc.motion.manifest = manifest.string();
  sc.motion.skills = {"walk"};
  sc.style_conditioned = true;
  const fs::path policy = TinyPolicy(sc, 100, "eval_style");
  PolicyEvalOptions o = TwoEnvOptions(policy, 12);
  o.seed = 2;
  o.style_eval = true;
  const PolicyEvalReport r = EvaluatePolicy(o);
  ASSERT_TRUE(r.style.has_value());
  const StyleEvalReport& st = *r.style;
  ASSERT_GE(st.emotions.size(), 6u);
  EXPECT_GT(st.classifier_heldout.total, 0);
  EXPECT_GT(st.classifier_heldout.accuracy, 0.8);
  int right = 0;
  for (size_t k = 0; k < r.results.size(); ++k) {
    const TrialResult& t = r.results[k];
    EXPECT_EQ(t.emotion, st.emotions[k % st.emotions.size()]) << k;
    EXPECT_FALSE(t.caption.empty());
    right += t.style == t.emotion;
  }
  EXPECT_DOUBLE_EQ(st.accuracy, right / 12.0);
  const nlohmann::json j = r.ToJson();
  for (const char* key :
       {"style_accuracy", "style_per_emotion", "style_chance", "style_classifier_heldout"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(j["results"][0].contains("caption"));
  // A caption file without captions of two emotions is refused, naming it.
  const fs::path bad = sims::testing::TempDir("eval_style_bad") / "captions.json";
  WriteJsonFile(bad, {{"queries", {{{"caption", "a person walks"}, {"clip", "walk_normal"}}}}});
  o.style_captions = bad;
  ExpectError([&] { EvaluatePolicy(o); }, {"captions.json", "two emotions"});
}

TEST(PolicyEvalTest, SitOnHeldOutObjects) {
  task::SkillConfig sc;
  sc.skill = "sit";
  sc.object.num_objects = 2;
  const fs::path policy = TinyPolicy(sc, 30, "eval_sit");
  PolicyEvalOptions o = TwoEnvOptions(policy, 2);
  const PolicyEvalReport r = EvaluatePolicy(o);
  EXPECT_EQ(r.skill, "sit");
  EXPECT_EQ(r.scene, "training_ground_sit");
  for (const auto& t : r.results) {
    EXPECT_LE(t.length, 30);
    EXPECT_GT(t.contact_error, 0.5);  // it starts ≥ 1 m beyond the seat's footprint
    // The pelvis is the one goal joint (no back rest): its offset measures the same distance.
    EXPECT_NEAR(t.goal_offset.norm(), t.contact_error, 1e-9);
  }
  EXPECT_EQ(r.ToJson()["results"][0]["goal_offset"].size(), 3u);
  EXPECT_EQ(r.ToJson()["clutter"], 0.0);
  // --clutter puts a table before the pieces; it needs the policy's target categories.
  o.clutter = 1;
  ExpectError([&] { EvaluatePolicy(o); }, {"object_categories", "clutter_share"});
  sc.object.object_categories = {"chair"};
  o.checkpoint = TinyPolicy(sc, 30, "eval_sit_clutter");
  const PolicyEvalReport cluttered = EvaluatePolicy(o);
  EXPECT_EQ(cluttered.clutter, 1.0);
  EXPECT_EQ(cluttered.results.size(), 2u);
  o.clutter = 1.5;
  ExpectError([&] { EvaluatePolicy(o); }, {"--clutter", "[0, 1]"});
}

// Get-up trials are grouped by how they started (seat, bed, floor clip, fall state): every
// trial carries its label, the groups add up to the trials and their rates to the totals.
TEST(PolicyEvalTest, GetUpTrialsAreGroupedByStart) {
  task::SkillConfig sc;
  sc.skill = "getup";
  sc.object.num_objects = 2;
  sc.object.object_categories = {"chair", "bed"};
  motion::SyntheticOptions so;
  so.variants = 1;
  so.skills = {"getup"};
  sc.motion.manifest =
      motion::WriteMotionDataset(motion::GenerateSyntheticClips(so),
                                 sims::testing::TempDir("eval_getup_clips"), "getup")
          .string();
  sc.motion.skills = {"getup"};
  sc.getup.fall_states = 8;
  const fs::path policy = TinyPolicy(sc, 15, "eval_getup");
  PolicyEvalOptions o = TwoEnvOptions(policy, 12);
  o.reference_starts = 0.5;
  const PolicyEvalReport r = EvaluatePolicy(o);
  ASSERT_FALSE(r.by_start.empty());
  int trials = 0;
  double falls = 0;
  for (const auto& [label, g] : r.by_start) {
    EXPECT_TRUE(label == "seat" || label == "bed" || label == "floor" || label == "fall") << label;
    trials += g.trials;
    falls += g.fall_rate * g.trials;
  }
  EXPECT_EQ(trials, 12);
  EXPECT_NEAR(falls / 12, r.fall_rate, 1e-12);
  EXPECT_GE(r.by_start.size(), 2u) << "both clip and fall-state starts";
  for (const auto& t : r.results) EXPECT_FALSE(t.start.empty());
  EXPECT_TRUE(r.ToJson().contains("by_start"));
  // An untrained policy started on the floor is still lying there in its last second: more than
  // its feet touch the scene ("touching"), which is why such a trial cannot count.
  int on_floor = 0;
  for (const auto& t : r.results) {
    if (t.start != "fall" && t.start != "floor") continue;
    ++on_floor;
    EXPECT_FALSE(t.touching.empty());
  }
  EXPECT_GT(on_floor, 0);
  EXPECT_TRUE(r.ToJson()["results"][0].contains("touching"));
  // A skill without start kinds reports none.
  const PolicyEvalReport walk =
      EvaluatePolicy(TwoEnvOptions(TinyPolicy(WalkConfig(), 10, "eval_nostart"), 2));
  EXPECT_TRUE(walk.by_start.empty());
  EXPECT_FALSE(walk.ToJson().contains("by_start"));
}

TEST(PolicyEvalTest, UnifiedOnAScenePlan) {
  task::SkillConfig sc;
  sc.skill = "unified";
  sc.object.num_objects = 2;
  const fs::path policy = TinyPolicy(sc, 30, "eval_unified");
  PolicyEvalOptions o = TwoEnvOptions(policy, 2);
  o.scene_plan = sims::testing::TestData("scene/sceneplan.json").string() + "#0000";
  o.partnet_root = sims::testing::TestData("scene/partnet");
  const PolicyEvalReport r = EvaluatePolicy(o);
  EXPECT_EQ(r.skill, "unified");
  EXPECT_NE(r.scene.find("sceneplan"), std::string::npos);
  EXPECT_EQ(r.mean_num_steps, 2.0);
  for (const auto& t : r.results) {
    EXPECT_EQ(t.num_steps, 2);
    EXPECT_LE(t.length, 2 * 300);  // n steps within n × 10 s
    EXPECT_LE(t.steps_completed, 2);
  }
  o.scene_plan = sims::testing::TestData("scene/sceneplan.json").string() + "#0001";
  ExpectError([&] { EvaluatePolicy(o); }, {"sceneplan.json", "0001", "no steps"});
}

TEST(SkillConfigsTest, ShippedConfigsLoadAndCreateTheirSkills) {
  for (const char* name : {"walk", "sit", "lie", "reach", "getup", "unified"}) {
    SCOPED_TRACE(name);
    auto tc =
        LoadConfig<learning::TrainConfig>(ConfigPath(std::string("skills/") + name + ".json"));
    EXPECT_EQ(tc.skill.skill, name);
    EXPECT_LE(tc.env.num_envs, 128);   // CPU-sized
    tc.skill.motion.manifest.clear();  // the synthetic clips are generated at setup time
    tc.skill.object.num_objects =
        static_cast<int>(std::max<size_t>(1, tc.skill.object.object_categories.size()));
    const auto setup = task::CreateSkill(tc.skill, 1, 1);
    EXPECT_EQ(setup.skill->name(), name);
  }
}

}  // namespace
}  // namespace sims::eval
