#include "sims/story/story_eval.h"

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"
#include "sims/core/progress.h"
#include "sims/eval/motion_metrics.h"
#include "sims/motion/motion_library.h"
#include "sims/sim/model_builder.h"

namespace sims::story {

namespace {

Eigen::MatrixXd ReferenceFeatures(const std::filesystem::path& manifest) {
  auto humanoid = std::make_shared<const sim::Humanoid>(sim::BuildModel());
  const auto lib = motion::MotionLibrary::Load(manifest, humanoid);
  std::vector<Eigen::MatrixXd> parts;
  for (int i = 0; i < lib.num_clips(); ++i)
    parts.push_back(eval::PoseFeatures(io::RecordFromClip(lib.clip(i), 30.0), 3));
  return eval::StackRows(parts);
}

}  // namespace

StoryInput EvalStoryInput(const StoryEvalOptions& o, const nlohmann::json& themes,
                          const std::string& difficulty, int index) {
  StoryInput in;
  in.theme = themes[index % themes.size()].get<std::string>();
  in.difficulty = difficulty;
  in.seed = o.seed + index;
  in.scene = "";  // the protocol plans on the built-in layouts
  in.style_model = o.style_model;
  in.environment = o.environment;
  return in;
}

nlohmann::json EvaluateStories(const StoryEvalOptions& o) {
  const auto themes_path = o.themes.empty() ? ConfigPath("eval/story_themes.json") : o.themes;
  const auto themes_json = ReadJsonFile(themes_path);
  if (!themes_json.contains("themes") || !themes_json["themes"].is_array() ||
      themes_json["themes"].empty())
    ThrowInputError(themes_path.string(), "themes", "a non-empty array of theme strings", "none");
  const auto policies =
      fsm::LoadPolicySet(o.policies.empty() ? fsm::DefaultPolicySetPath() : o.policies);
  fsm::StoryOptions story = o.story;
  story.missing_policy_fails = true;
  const Eigen::MatrixXd reference =
      o.reference_manifest.empty() ? Eigen::MatrixXd() : ReferenceFeatures(o.reference_manifest);

  nlohmann::json rows = nlohmann::json::array(), per = nlohmann::json::object();
  std::vector<Eigen::MatrixXd> all_features;
  ProgressReporter progress("eval_story",
                            static_cast<int64_t>(o.difficulties.size()) * o.stories_per_difficulty,
                            "stories", 5.0);
  int64_t done = 0;
  for (const auto& difficulty : o.difficulties) {
    double sr = 0, ce = 0, ss = 0, pen = 0, depth = 0, slide = 0;
    int n = 0;
    std::vector<Eigen::MatrixXd> features;
    for (int i = 0; i < o.stories_per_difficulty; ++i) {
      const StoryInput input = EvalStoryInput(o, themes_json["themes"], difficulty, i);
      const std::string& theme = input.theme;
      nlohmann::json row = {{"difficulty", difficulty}, {"theme", theme}, {"seed", input.seed}};
      try {
        story.seed = input.seed;
        const StoryRun run = RunStory(PrepareStory(input), policies, story);
        if (!o.outputs_dir.empty())
          WriteStoryRun(o.outputs_dir / (difficulty + "_" + std::to_string(i)), run);
        const fsm::StoryResult& result = run.result;
        const io::MotionRecord& record = run.record;
        const scene::SceneOccupancy occupancy(*run.story.scene);
        const auto p =
            eval::MotionPenetration(record, occupancy, eval::BodySamplePoints(*run.humanoid));
        const auto s = eval::MeasureFootSliding(record);
        features.push_back(eval::PoseFeatures(record, 3));
        row["keyframes"] = result.keyframes.size();
        row["success_rate"] = result.success_rate;
        row["contact_error"] = result.mean_contact_error;
        row["success_steps"] = result.success_steps;
        row["falls"] = result.falls;
        row["penetration_fraction"] = p.fraction_inside;
        row["penetration_mean_depth"] = p.mean_depth;
        row["penetration_max_depth"] = p.max_depth;
        row["foot_sliding_m_per_s"] = s.mean_speed;
        row["style_z"] = !run.story.styles.empty();  // captions were turned into z
        sr += result.success_rate, ce += result.mean_contact_error, ss += result.success_steps;
        pen += p.fraction_inside, depth = std::max(depth, p.max_depth), slide += s.mean_speed;
        ++n;
      } catch (const Error& e) {
        row["error"] = e.what();
        spdlog::warn("story {} '{}' ({}) failed to run: {}", i, theme, difficulty, e.what());
      }
      rows.push_back(row);
      progress.Update(++done);
    }
    nlohmann::json d = {{"stories", n}};
    if (n) {
      d["success_rate"] = sr / n;
      d["contact_error"] = ce / n;
      d["success_steps"] = ss / n;
      d["penetration_fraction"] = pen / n;
      d["penetration_max_depth"] = depth;
      d["foot_sliding_m_per_s"] = slide / n;
      const Eigen::MatrixXd gen = eval::StackRows(features);
      d["apd"] = eval::AveragePairwiseDistance(gen);
      if (reference.rows() > 1) d["fid"] = eval::FrechetDistance(gen, reference);
      all_features.insert(all_features.end(), features.begin(), features.end());
    }
    per[difficulty] = d;
  }
  nlohmann::json out = {
      {"per_difficulty", per},
      {"stories", rows},
      {"policies", policies.source.string()},
      {"ablation", ConfigToJson(o.story.ablation)},
      {"feature",
       "per-frame heading-frame body positions (42) + joint rotations (72), every 3rd frame"}};
  if (!all_features.empty()) {
    const Eigen::MatrixXd gen = eval::StackRows(all_features);
    out["apd"] = eval::AveragePairwiseDistance(gen);
    if (reference.rows() > 1) {
      out["fid"] = eval::FrechetDistance(gen, reference);
      out["reference_apd"] = eval::AveragePairwiseDistance(reference);
    }
  }
  return out;
}

}  // namespace sims::story
