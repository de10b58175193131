#include "sims/story/story_eval.h"

#include <chrono>
#include <exception>
#include <map>

#include <fmt/format.h>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/parallel.h"
#include "sims/core/paths.h"
#include "sims/core/progress.h"
#include "sims/eval/motion_metrics.h"
#include "sims/humanoid/model_builder.h"
#include "sims/motion/motion_library.h"

namespace sims::story {

namespace {

// The demonstration clips' pose features (FID) and their foot sliding by the stories' own
// measure: what a policy that moved exactly like its demos would score.
struct Reference {
  Eigen::MatrixXd features;
  eval::FootSliding sliding;
};

Reference LoadReference(const std::filesystem::path& manifest) {
  auto humanoid = std::make_shared<const humanoid::Humanoid>(humanoid::BuildModel());
  const auto lib = motion::MotionLibrary::Load(manifest, humanoid);
  std::vector<Eigen::MatrixXd> parts;
  eval::FootSlidingMeter sliding;  // pooled over every clip's frame pairs
  for (int i = 0; i < lib.num_clips(); ++i) {
    const io::MotionRecord record = io::RecordFromClip(lib.clip(i), 30.0);
    parts.push_back(eval::PoseFeatures(record, 3));
    sliding.AddRecord(record);
  }
  return {eval::StackRows(parts), sliding.Result()};
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
  const Reference ref =
      o.reference_manifest.empty() ? Reference{} : LoadReference(o.reference_manifest);
  const Eigen::MatrixXd& reference = ref.features;

  // Plan every story first, then run them (together, in batches), then measure each in the
  // order of the rows: the same stories, results and report as running them one by one.
  struct Entry {
    nlohmann::json row;
    int prepared = -1;  // index into `stories`, −1 when planning failed
  };
  std::vector<Entry> entries;
  std::vector<PreparedStory> stories;
  std::vector<fsm::StoryOptions> story_options;
  const auto t0 = std::chrono::steady_clock::now();
  for (const auto& difficulty : o.difficulties)
    for (int i = 0; i < o.stories_per_difficulty; ++i) {
      const StoryInput input = EvalStoryInput(o, themes_json["themes"], difficulty, i);
      Entry e{{{"difficulty", difficulty}, {"theme", input.theme}, {"seed", input.seed}}};
      try {
        stories.push_back(PrepareStory(input));
        story.seed = input.seed;
        story_options.push_back(story);
        e.prepared = static_cast<int>(stories.size()) - 1;
      } catch (const Error& err) {
        e.row["error"] = err.what();
        spdlog::warn("story {} '{}' ({}) failed to run: {}", i, input.theme, difficulty,
                     err.what());
      }
      entries.push_back(std::move(e));
    }
  const auto t1 = std::chrono::steady_clock::now();
  std::vector<StoryRun> runs(stories.size());
  std::vector<std::exception_ptr> errors(stories.size());
  const size_t batch = !o.batched         ? 1
                       : o.batch_size > 0 ? static_cast<size_t>(o.batch_size)
                                          : std::max<size_t>(stories.size(), 1);
  for (size_t b0 = 0; b0 < stories.size(); b0 += batch) {
    const size_t b1 = std::min(stories.size(), b0 + batch);
    const std::vector<PreparedStory> part(stories.begin() + b0, stories.begin() + b1);
    const std::vector<fsm::StoryOptions> part_options(story_options.begin() + b0,
                                                      story_options.begin() + b1);
    std::vector<std::exception_ptr> part_errors;
    auto part_runs = RunStories(part, policies, part_options, &part_errors, o.batched ? 0 : 1);
    for (size_t j = 0; j < part_runs.size(); ++j) {
      runs[b0 + j] = std::move(part_runs[j]);
      errors[b0 + j] = part_errors[j];
    }
  }
  stories.clear();  // each run holds its story
  const auto t2 = std::chrono::steady_clock::now();

  nlohmann::json rows = nlohmann::json::array(), per = nlohmann::json::object();
  std::vector<Eigen::MatrixXd> all_features;
  // Which skill the failures come from: keyframes and successes per skill, all difficulties.
  struct SkillTally {
    int keyframes = 0, succeeded = 0, falls = 0;
    eval::FootSlidingMeter sliding;  // pooled over the frames its keyframes ran
  };
  std::map<std::string, SkillTally> per_skill;
  ProgressReporter progress("eval_story", static_cast<int64_t>(entries.size()), "stories", 5.0);
  int64_t done = 0;
  size_t next = 0;
  for (const auto& difficulty : o.difficulties) {
    double sr = 0, ce = 0, ss = 0, pen = 0, depth = 0, slide = 0;
    int n = 0;
    std::vector<Eigen::MatrixXd> features;
    for (int i = 0; i < o.stories_per_difficulty; ++i) {
      Entry& e = entries[next++];
      nlohmann::json& row = e.row;
      if (e.prepared >= 0) {
        try {
          if (errors[e.prepared]) std::rethrow_exception(errors[e.prepared]);
          const StoryRun& run = runs[e.prepared];
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
          for (const auto& k : result.keyframes) {
            SkillTally& t = per_skill[k.skill];
            ++t.keyframes, t.succeeded += k.success, t.falls += k.falls;
          }
          for (const auto& a : record.keyframes)
            if (a.reached())
              per_skill[a.skill].sliding.AddRecord(record, a.start_frame, a.end_frame);
          sr += result.success_rate, ce += result.mean_contact_error, ss += result.success_steps;
          pen += p.fraction_inside, depth = std::max(depth, p.max_depth), slide += s.mean_speed;
          ++n;
        } catch (const Error& err) {
          row["error"] = err.what();
          spdlog::warn("story {} '{}' ({}) failed to run: {}", i, row["theme"].get<std::string>(),
                       difficulty, err.what());
        }
        runs[e.prepared] = StoryRun();  // its motion and scene are done with
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
  nlohmann::json skills = nlohmann::json::object();
  int contact_pairs = 0;
  for (const auto& [skill, t] : per_skill) contact_pairs += t.sliding.Result().contact_pairs;
  for (const auto& [skill, t] : per_skill) {
    const eval::FootSliding s = t.sliding.Result();
    skills[skill] = {{"keyframes", t.keyframes},
                     {"succeeded", t.succeeded},
                     {"success_rate", static_cast<double>(t.succeeded) / t.keyframes},
                     {"falls", t.falls},
                     {"foot_sliding_m_per_s", s.mean_speed},
                     {"foot_contact_share",
                      contact_pairs ? static_cast<double>(s.contact_pairs) / contact_pairs : 0.0}};
  }
  nlohmann::json out = {
      {"per_difficulty", per},
      {"per_skill", skills},
      {"stories", rows},
      {"policies", policies.source.string()},
      {"ablation", ConfigToJson(o.story.ablation)},
      {"batched", o.batched},
      {"batch_size", batch},
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
  if (ref.sliding.contact_pairs > 0) {
    out["reference_foot_sliding_m_per_s"] = ref.sliding.mean_speed;
    out["reference_foot_sliding_ratio"] = ref.sliding.sliding_ratio;
  }
  const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  out["timing"] = {{"prepare_s", seconds(t0, t1)},
                   {"run_s", seconds(t1, t2)},
                   {"measure_s", seconds(t2, std::chrono::steady_clock::now())}};
  return out;
}

nlohmann::json BenchStories(const StoryEvalOptions& o) {
  const auto themes_path = o.themes.empty() ? ConfigPath("eval/story_themes.json") : o.themes;
  const auto themes = ReadJsonFile(themes_path).at("themes");
  const auto policies =
      fsm::LoadPolicySet(o.policies.empty() ? fsm::DefaultPolicySetPath() : o.policies);
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a) {
    return std::chrono::duration<double>(Clock::now() - a).count();
  };
  std::vector<PreparedStory> stories;
  std::vector<fsm::StoryOptions> options;
  const auto t_prepare = Clock::now();
  for (const auto& difficulty : o.difficulties)
    for (int i = 0; i < o.stories_per_difficulty; ++i) {
      const StoryInput input = EvalStoryInput(o, themes, difficulty, i);
      stories.push_back(PrepareStory(input));
      options.push_back(o.story);
      options.back().missing_policy_fails = true;
      options.back().seed = input.seed;
    }
  const double prepare_s = seconds(t_prepare);
  spdlog::info("bench_story: {} stories prepared in {:.1f} s; running them one by one",
               stories.size(), prepare_s);
  std::vector<StoryRun> sequential;
  const auto t_sequential = Clock::now();
  for (size_t i = 0; i < stories.size(); ++i)
    sequential.push_back(RunStory(stories[i], policies, options[i]));
  const double sequential_s = seconds(t_sequential);
  spdlog::info("bench_story: sequential {:.1f} s; running them batched", sequential_s);
  const auto t_batched = Clock::now();
  const std::vector<StoryRun> batched = RunStories(stories, policies, options);
  const double batched_s = seconds(t_batched);
  bool identical = true;
  double simulated_s = 0;
  int64_t frames = 0;
  for (size_t i = 0; i < stories.size(); ++i) {
    const StoryRun &a = sequential[i], &b = batched[i];
    simulated_s += a.result.duration_s;
    frames += a.record.num_frames();
    bool same = fsm::StoryResultToJson(a.result) == fsm::StoryResultToJson(b.result) &&
                a.record.num_frames() == b.record.num_frames();
    for (int f = 0; same && f < a.record.num_frames(); ++f) {
      const auto &x = a.record.frames[f], &y = b.record.frames[f];
      same = x.root_pos == y.root_pos && x.root_rot.coeffs() == y.root_rot.coeffs() &&
             x.dof_pos == y.dof_pos;
    }
    if (!same) spdlog::warn("bench_story: story {} differs batched", i);
    identical = identical && same;
  }
  return {{"stories", stories.size()},
          {"difficulties", o.difficulties},
          {"seed", o.seed},
          {"threads", ThreadCount()},
          {"prepare_s", prepare_s},
          {"sequential_s", sequential_s},
          {"batched_s", batched_s},
          {"speedup", batched_s > 0 ? sequential_s / batched_s : 0.0},
          {"identical", identical},
          {"simulated_s", simulated_s},
          {"frames", frames},
          {"frames_per_s_sequential", frames / std::max(sequential_s, 1e-9)},
          {"frames_per_s_batched", frames / std::max(batched_s, 1e-9)}};
}

std::string StoryEvalHtml(const nlohmann::json& report) {
  // SIMS Table 2 (success rate of the full method), for scale.
  const std::map<std::string, double> paper = {{"simple", 0.743}, {"mid", 0.422}, {"hard", 0.315}};
  auto num = [](const nlohmann::json& d, const char* key, int decimals,
                double scale = 1.0) -> std::string {
    if (!d.contains(key) || !d[key].is_number()) return "–";
    return fmt::format("{:.{}f}{}", scale * d[key].get<double>(), decimals,
                       scale == 100.0 ? " %" : "");
  };
  std::string rows;
  const nlohmann::json per = report.value("per_difficulty", nlohmann::json::object());
  for (const auto& [difficulty, d] : per.items()) {
    const auto it = paper.find(difficulty);
    rows += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>"
        "<td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
        difficulty, d.value("stories", 0), num(d, "success_rate", 1, 100.0),
        it == paper.end() ? "–" : fmt::format("{:.1f} %", 100 * it->second),
        num(d, "success_steps", 2), num(d, "contact_error", 3),
        num(d, "penetration_fraction", 2, 100.0), num(d, "penetration_max_depth", 3),
        num(d, "foot_sliding_m_per_s", 3), num(d, "fid", 2), num(d, "apd", 2));
  }
  std::string skill_rows;
  const nlohmann::json per_skill = report.value("per_skill", nlohmann::json::object());
  for (const auto& [skill, t] : per_skill.items())
    skill_rows += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
        skill, t.value("keyframes", 0), t.value("succeeded", 0), num(t, "success_rate", 1, 100.0),
        t.value("falls", 0), num(t, "foot_sliding_m_per_s", 3),
        num(t, "foot_contact_share", 1, 100.0));
  const nlohmann::json ablation = report.value("ablation", nlohmann::json::object());
  return fmt::format(
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>eval_story</title>\n"
      "<style>body{{font-family:sans-serif}}table{{border-collapse:collapse}}"
      "td,th{{border:1px solid #999;padding:4px 8px;text-align:right}}"
      "td:first-child{{text-align:left}}</style></head><body>\n"
      "<h1>Stories per difficulty (SIMS Table 2 protocol)</h1>\n"
      "<p>Policies: {}; ablation: {}.</p>\n<table>\n"
      "<tr><th>difficulty</th><th>stories</th><th>success rate</th><th>SIMS paper</th>"
      "<th>success steps</th><th>contact error (m)</th><th>penetration</th>"
      "<th>max depth (m)</th><th>foot sliding (m/s)</th><th>FID</th><th>APD</th></tr>\n{}"
      "</table>\n<p>Success rate: keyframes succeeded / keyframes. The paper's column is its "
      "full method's success rate, for scale. Foot sliding of the demonstration clips by the "
      "same measure: {} m/s.</p>\n"
      "<h2>Keyframes per skill (all difficulties)</h2>\n<table>\n"
      "<tr><th>skill</th><th>keyframes</th><th>succeeded</th><th>success rate</th>"
      "<th>falls</th><th>foot sliding (m/s)</th><th>share of foot contact</th></tr>\n{}"
      "</table>\n<p>A skill's foot sliding pools the frames its keyframes ran (the per "
      "difficulty figure averages stories); its share is of all foot-contact frame pairs.</p>\n"
      "</body></html>\n",
      report.value("policies", std::string("?")), ablation.dump(), rows,
      num(report, "reference_foot_sliding_m_per_s", 3), skill_rows);
}

}  // namespace sims::story
