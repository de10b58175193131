#include "sims/story/story.h"

#include <cstdlib>
#include <fstream>
#include <set>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/language/motion_text.h"
#include "sims/language/text_encoder.h"
#include "sims/story/story_eval.h"
#include "sims/task/styles.h"

namespace sims::story {
namespace {

// The bundled policies (walk and reach, no sit, lie, get-up or unified policy).
fsm::PolicySet BundledPolicies() { return fsm::LoadPolicySet(fsm::DefaultPolicySetPath()); }

// Short time-outs: the tests check the pipeline, not how well the policies do.
fsm::StoryOptions ShortOptions() {
  fsm::StoryOptions o;
  o.walk_timeout_s = 1.0;
  o.skill_timeout_s = 1.0;
  return o;
}

// A motion–text model folder (model.pt, model.json, bank.json) trained for a few steps on random
// features with the built-in text encoder, so StyleEmbedder::Load works on it; "" when the
// encoder's word vectors are not prepared (build/bin/prepare_assets).
std::filesystem::path TinyStyleModel() {
  static const std::filesystem::path dir = []() -> std::filesystem::path {
    if (!language::BuiltinTextEncoder::DataAvailable()) return {};
    const auto out = sims::testing::TempDir("story_style_model");
    language::MotionTextTrainConfig c;
    c.model.feature_dim = 6;
    c.model.seq_frames = 12;
    c.model.frames_per_token = 3;
    c.model.d_model = 16;
    c.model.num_heads = 2;
    c.model.encoder_layers = 1;
    c.model.decoder_layers = 1;
    c.model.ff_dim = 32;
    c.model.z_dim = task::kStyleDim;  // what the policies are conditioned on
    c.model.mlp_hidden = {16};
    c.out_dir = out.string();
    c.steps = 2;
    c.batch_size = 2;
    c.threads = 1;
    std::vector<language::CaptionedSequence> data(2);
    for (int i = 0; i < 2; ++i) {
      data[i].clip_name = i ? "sad_walk" : "happy_walk";
      data[i].features = Eigen::MatrixXf::Random(20, 6);
      data[i].captions = {i ? "walks sadly with the head bowed" : "walks happily"};
    }
    language::TrainMotionText(c, data, language::BuiltinTextEncoder(c.text_encoder));
    return out;
  }();
  return dir;
}

TEST(PrepareStoryTest, NeedsExactlyOneInput) {
  StoryInput in;
  EXPECT_NE(sims::testing::ErrorOf([&] { PrepareStory(in); }).find("exactly one of"),
            std::string::npos);
  in.theme = "a person relaxes";
  in.instruction = "sit on the chair";
  EXPECT_NE(sims::testing::ErrorOf([&] { PrepareStory(in); }).find("2 given"), std::string::npos);
}

TEST(PrepareStoryTest, InstructionWithGoalAndStyle) {
  StoryInput in;
  in.instruction = "walk to the chair slowly";
  in.scene = "chair";
  in.goal = Eigen::Vector3d(1, 2, 0);
  const PreparedStory p = PrepareStory(in);
  ASSERT_EQ(p.instructions.size(), 1u);
  EXPECT_EQ(p.instructions[0].skill, "walk");
  EXPECT_TRUE(p.instructions[0].target.has_point);
  EXPECT_TRUE(p.instructions[0].target.point.isApprox(Eigen::Vector3d(1, 2, 0)));
  EXPECT_EQ(p.plan.planner, "instruction");
  EXPECT_EQ(p.title, "walk to the chair slowly");
  if (TinyStyleModel().empty()) GTEST_SKIP() << "word vectors not prepared: no style model";
  in.style_model = TinyStyleModel().string();
  const PreparedStory styled = PrepareStory(in);
  ASSERT_EQ(styled.styles.size(), 1u);
  EXPECT_EQ(styled.instructions[0].z.size(), task::kStyleDim);
  EXPECT_NEAR(styled.instructions[0].z.norm(), 1.f, 1e-4f);
  EXPECT_EQ(styled.styles[0]["caption"], "walk to the chair slowly");
}

TEST(PrepareStoryTest, NoSceneRetrievesABuiltinLayout) {
  StoryInput in;
  in.instruction = "sit on the sofa";
  in.scene = "";
  const PreparedStory p = PrepareStory(in);
  EXPECT_NE(p.plan.layout.mode, "given");
  EXPECT_FALSE(p.scene->objects.empty());
  ASSERT_FALSE(p.instructions.empty());
  EXPECT_EQ(p.instructions.back().skill, "sit");
}

TEST(StoryRunTest, RunsAUniHsiScenePlan) {
  const auto dir = sims::testing::TempDir("story_sceneplan");
  StoryInput in;
  in.scene_plan = sims::testing::TestData("scene/sceneplan.json").string() + "#0000";
  in.partnet_root = sims::testing::TestData("scene/partnet").string();
  // The bundled set has no unified policy: the contact step fails with a note.
  const StoryRun run = RunStory(PrepareStory(in), BundledPolicies(), ShortOptions());
  const auto r = WriteStoryRun(dir / "out", run);
  ASSERT_EQ(r["keyframes"].size(), 2u);
  EXPECT_EQ(r["keyframes"][0]["skill"], "walk");
  EXPECT_EQ(r["keyframes"][1]["skill"], "unified");
  EXPECT_NE(r["keyframes"][1]["note"].get<std::string>().find("no usable policy for 'unified'"),
            std::string::npos);
  EXPECT_EQ(r["planner"], "sceneplan");
  const auto plan = ReadJsonFile(dir / "out" / "plan.json");
  EXPECT_EQ(plan["id"], "0000");
  EXPECT_TRUE(plan["plan"].contains("contact_pairs"));
}

TEST(StoryRunTest, WritesEveryOutputOrNothing) {
  const auto dir = sims::testing::TempDir("story");
  StoryInput in;
  in.instruction = "walk to the chair";
  in.scene = "chair";
  const auto policies = BundledPolicies();
  const StoryRun run = RunStory(PrepareStory(in), policies, ShortOptions());
  const auto result = WriteStoryRun(dir / "out", run);
  for (const char* f : {"result.json", "motion.json", "motion.bvh", "scene.glb", "index.html",
                        "story.txt", "plan.json", "config.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.partial"));
  const auto saved = ReadJsonFile(dir / "out" / "result.json");
  EXPECT_EQ(saved, result);
  EXPECT_EQ(saved["keyframes"][0]["skill"], "walk");
  EXPECT_EQ(ReadJsonFile(dir / "out" / "config.json")["instruction"], "walk to the chair");

  // A skill without a policy: by default its keyframe fails with a note and the story runs.
  std::ofstream(dir / "walk_only.json")
      << nlohmann::json{{"policies", {{"walk", AssetPath("policies/walk/policy.pt").string()}}}};
  const auto walk_only = fsm::LoadPolicySet(dir / "walk_only.json");
  StoryInput sit = in;
  sit.instruction = "sit on the chair";  // no sit policy in walk_only
  const PreparedStory sit_story = PrepareStory(sit);
  const auto sat = StoryRunToJson(RunStory(sit_story, walk_only, ShortOptions()));
  ASSERT_FALSE(sat["keyframes"].empty());
  EXPECT_EQ(sat["keyframes"].back()["skill"], "sit");
  EXPECT_FALSE(sat["keyframes"].back()["success"].get<bool>());
  EXPECT_NE(sat["keyframes"].back()["note"].get<std::string>().find("no usable policy for 'sit'"),
            std::string::npos);

  // Bad inputs: clear errors.
  fsm::StoryOptions strict = ShortOptions();
  strict.missing_policy_fails = false;
  EXPECT_THROW(RunStory(sit_story, walk_only, strict), Error);
  std::ofstream(dir / "script.json")
      << R"({"keyframes": [{"skill": "sit", "furniture": "spaceship"}]})";
  StoryInput bad;
  bad.input = (dir / "script.json").string();
  EXPECT_THROW(RunStory(PrepareStory(bad), policies, strict), Error);
}

// run_story (the app) and eval_story (EvaluateStories) run the same story through the same
// pipeline: identical per-keyframe outcomes, styles and motion to the last frame. The app is run
// as a separate process, so its flags are part of what is compared.
TEST(StoryPipelineTest, EvalStoryAndRunStoryGiveTheSameResult) {
  const auto dir = sims::testing::TempDir("story_same");
  const std::filesystem::path style = TinyStyleModel();
  std::ofstream(dir / "themes.json") << R"({"themes": ["a tired person comes home and rests"]})";
  StoryEvalOptions o;
  o.policies = fsm::DefaultPolicySetPath();
  o.themes = dir / "themes.json";
  o.difficulties = {"simple"};
  o.stories_per_difficulty = 1;
  o.seed = 3;
  o.style_model = style.string();
  o.story = ShortOptions();
  o.outputs_dir = dir / "eval";
  const auto report = EvaluateStories(o);
  ASSERT_EQ(report["stories"].size(), 1u);
  ASSERT_FALSE(report["stories"][0].contains("error")) << report["stories"][0]["error"];
  EXPECT_EQ(report["stories"][0]["style_z"].get<bool>(), !style.empty());

  fsm::StoryOptions options = o.story;
  options.seed = o.seed;
  WriteJsonFile(dir / "options.json", ConfigToJson(options));
  const std::string cmd = std::string(SIMS_RUN_STORY_BIN) +
                          " --theme 'a tired person comes home and rests' --difficulty simple" +
                          " --scene '' --seed 3 --policies " + o.policies.string() + " --options " +
                          (dir / "options.json").string() +
                          (style.empty() ? "" : " --style-model " + style.string()) + " --out " +
                          (dir / "run").string() + " --log-level warn";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  const auto from_eval = ReadJsonFile(dir / "eval" / "simple_0" / "result.json");
  const auto from_run = ReadJsonFile(dir / "run" / "result.json");
  ASSERT_GE(from_run["keyframes"].size(), 2u);
  EXPECT_EQ(from_eval["keyframes"], from_run["keyframes"]);
  EXPECT_EQ(from_eval["styles"], from_run["styles"]);
  EXPECT_EQ(from_eval, from_run);
  EXPECT_EQ(from_eval["success_rate"], report["stories"][0]["success_rate"]);
  EXPECT_EQ(from_eval["falls"], report["stories"][0]["falls"]);
  if (!style.empty()) {
    EXPECT_EQ(from_run["styles"].size(), from_run["keyframes"].size());
  }
  // The motion, final pose included.
  const auto motion_eval = ReadJsonFile(dir / "eval" / "simple_0" / "motion.json");
  const auto motion_run = ReadJsonFile(dir / "run" / "motion.json");
  EXPECT_EQ(motion_eval, motion_run);
  EXPECT_EQ(ReadJsonFile(dir / "eval" / "simple_0" / "plan.json"),
            ReadJsonFile(dir / "run" / "plan.json"));
}

// Stories run together (each its own scene and seed, one policy call per policy per control
// step over all of them) give what each gives run alone: per-keyframe outcomes, falls, success
// and every motion frame; eval_story's report is the same batched or not.
TEST(StoryBatchTest, BatchedStoriesEqualSequentialRuns) {
  const auto dir = sims::testing::TempDir("story_batch");
  std::ofstream(dir / "themes.json") << R"({"themes": ["a tired person comes home and rests",
      "a person reads a book and then goes to bed", "someone waits for a friend"]})";
  StoryEvalOptions o;
  o.policies = fsm::DefaultPolicySetPath();
  o.themes = dir / "themes.json";
  o.difficulties = {"simple", "mid"};
  o.stories_per_difficulty = 2;
  o.seed = 11;
  o.style_model = TinyStyleModel().string();
  o.story = ShortOptions();
  const auto themes = ReadJsonFile(o.themes)["themes"];
  std::vector<PreparedStory> stories;
  std::vector<fsm::StoryOptions> options;
  for (const auto& d : o.difficulties)
    for (int i = 0; i < o.stories_per_difficulty; ++i) {
      const StoryInput input = EvalStoryInput(o, themes, d, i);
      stories.push_back(PrepareStory(input));
      options.push_back(o.story);
      options.back().seed = input.seed;
    }
  const auto policies = BundledPolicies();
  const std::vector<StoryRun> batched = RunStories(stories, policies, options, nullptr, 2);
  ASSERT_EQ(batched.size(), stories.size());
  std::set<std::string> scenes;
  for (size_t i = 0; i < stories.size(); ++i) {
    SCOPED_TRACE("story " + std::to_string(i));
    const StoryRun alone = RunStory(stories[i], policies, options[i]);
    const StoryRun& b = batched[i];
    scenes.insert(b.story.scene->name);
    EXPECT_EQ(fsm::StoryResultToJson(b.result), fsm::StoryResultToJson(alone.result));
    EXPECT_GE(b.result.keyframes.size(), 2u);
    EXPECT_EQ(b.options.seed, options[i].seed);
    ASSERT_EQ(b.record.num_frames(), alone.record.num_frames());
    EXPECT_GT(b.record.num_frames(), 1);
    for (int f = 0; f < b.record.num_frames(); ++f) {
      const auto &x = b.record.frames[f], &y = alone.record.frames[f];
      ASSERT_TRUE(x.root_pos == y.root_pos && x.root_rot.coeffs() == y.root_rot.coeffs() &&
                  x.dof_pos == y.dof_pos)
          << "frame " << f;
    }
    ASSERT_EQ(b.record.keyframes.size(), alone.record.keyframes.size());
    for (size_t k = 0; k < b.record.keyframes.size(); ++k) {
      EXPECT_EQ(b.record.keyframes[k].start_frame, alone.record.keyframes[k].start_frame);
      EXPECT_EQ(b.record.keyframes[k].end_frame, alone.record.keyframes[k].end_frame);
    }
  }
  EXPECT_GT(scenes.size(), 1u) << "the batch spans several scenes";

  // eval_story: the same report (timing aside) batched, in batches of 3, and one by one.
  const auto strip = [](nlohmann::json r) {
    r.erase("timing");
    r.erase("batched");
    r.erase("batch_size");
    return r;
  };
  o.batched = false;
  const auto sequential = EvaluateStories(o);
  EXPECT_FALSE(sequential["batched"].get<bool>());
  o.batched = true;
  o.batch_size = 3;
  const auto in_threes = EvaluateStories(o);
  EXPECT_TRUE(in_threes["batched"].get<bool>());
  EXPECT_EQ(in_threes["batch_size"], 3);
  ASSERT_EQ(sequential["stories"].size(), 4u);
  EXPECT_EQ(strip(in_threes), strip(sequential));
  for (const auto& row : sequential["stories"]) EXPECT_FALSE(row.contains("error")) << row;
  // The per-skill tally counts every keyframe of every story once.
  int keyframes = 0, tallied = 0;
  double succeeded = 0;
  for (const auto& row : sequential["stories"]) {
    keyframes += row["keyframes"].get<int>();
    succeeded += row["success_rate"].get<double>() * row["keyframes"].get<int>();
  }
  int tallied_success = 0;
  double contact_share = 0;
  for (const auto& [skill, t] : sequential["per_skill"].items()) {
    contact_share += t["foot_contact_share"].get<double>();
    EXPECT_GE(t["foot_sliding_m_per_s"].get<double>(), 0.0);
    tallied += t["keyframes"].get<int>();
    tallied_success += t["succeeded"].get<int>();
    EXPECT_DOUBLE_EQ(t["success_rate"].get<double>(),
                     t["succeeded"].get<double>() / t["keyframes"].get<double>());
  }
  EXPECT_EQ(tallied, keyframes);
  EXPECT_NEAR(tallied_success, succeeded, 1e-6);
  EXPECT_NEAR(contact_share, 1.0, 1e-9);  // every foot-contact pair belongs to one skill
  EXPECT_TRUE(sequential["per_skill"].contains("walk"));
  EXPECT_TRUE(in_threes["timing"].contains("run_s"));
}

// The HTML table beside eval_story's JSON: one row per difficulty with its figures, the paper's
// success rate beside ours, and a dash for a metric the report lacks.
TEST(StoryEvalHtmlTest, OneRowPerDifficultyWithItsFigures) {
  nlohmann::json report = {{"policies", "p.json"},
                           {"ablation", {{"no_text", false}}},
                           {"per_difficulty",
                            {{"simple",
                              {{"stories", 30},
                               {"success_rate", 0.275},
                               {"success_steps", 0.8},
                               {"contact_error", 0.9367},
                               {"penetration_fraction", 0.009},
                               {"penetration_max_depth", 0.047},
                               {"foot_sliding_m_per_s", 0.4197},
                               {"fid", 3.335},
                               {"apd", 1.384}}},
                             {"hard", {{"stories", 2}, {"success_rate", 0.5}}}}}};
  report["per_skill"]["sit"] = {{"keyframes", 8},
                                {"succeeded", 2},
                                {"success_rate", 0.25},
                                {"falls", 1},
                                {"foot_sliding_m_per_s", 0.5121},
                                {"foot_contact_share", 0.4}};
  report["reference_foot_sliding_m_per_s"] = 0.0312;
  const std::string html = StoryEvalHtml(report);
  EXPECT_NE(html.find("demonstration clips by the same measure: 0.031 m/s"), std::string::npos)
      << html;
  EXPECT_NE(html.find("<table>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>simple</td><td>30</td><td>27.5 %</td><td>74.3 %</td><td>0.80</td>"
                      "<td>0.937</td><td>0.90 %</td><td>0.047</td><td>0.420</td><td>3.33</td>"
                      "<td>1.38</td></tr>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<tr><td>hard</td><td>2</td><td>50.0 %</td><td>31.5 %</td><td>–</td>"),
            std::string::npos)
      << html;
  EXPECT_EQ(html.find("mid"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>sit</td><td>8</td><td>2</td><td>25.0 %</td><td>1</td><td>0.512</td>"
                      "<td>40.0 %</td></tr>"),
            std::string::npos)
      << html;
}

}  // namespace
}  // namespace sims::story
