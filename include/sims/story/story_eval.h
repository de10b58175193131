// eval_story: SIMS Table 2 protocol. For each difficulty (simple, mid, hard) N scripts are
// planned from themes on the built-in layouts and run with a policy set; reported are the
// success rate, contact error and success steps, plus penetration and foot sliding over the
// motion and FID/APD of the generated poses against the reference clips. Each story goes through
// the same pipeline as run_story (story.h: PrepareStory → RunStory), style z included.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/core/environment.h"
#include "sims/fsm/story_runner.h"
#include "sims/story/story.h"

namespace sims::story {

/// What to evaluate.
struct StoryEvalOptions {
  std::filesystem::path policies;            ///< Policy set ("" = default).
  std::filesystem::path themes;              ///< Theme list ("" = configs/eval/story_themes.json).
  std::filesystem::path reference_manifest;  ///< Clips for FID ("" = no FID).
  std::vector<std::string> difficulties = {"simple", "mid", "hard"};  ///< Difficulties.
  int stories_per_difficulty = 5;                                     ///< N.
  uint64_t seed = 0;                                                  ///< Story i uses seed + i.
  /// Motion–text model for caption → z, as StoryInput::style_model ("" = data/language/
  /// text_motion if present).
  std::string style_model;
  /// When set, each story's run_story outputs go to DIR/<difficulty>_<i> (WriteStoryRun).
  std::filesystem::path outputs_dir;
  fsm::StoryOptions story;  ///< FSM settings; missing skill policies count as failures.
  /// Run the stories together (story::RunStories: one policy call per policy per control step
  /// over all of them) instead of one after another; the results are the same.
  bool batched = true;
  /// At most this many stories run together (0 = all); bounds the memory of their scenes
  /// (30 stories of the built-in layouts: ~0.7 GB).
  int batch_size = 32;
  /// LLM fall-backs for planning the themes (planner::PlanRequest::environment); eval_story
  /// passes InstalledEnvironment(), the default fills nothing.
  Environment environment;
};

/// What story `index` of `difficulty` is: its theme (the list cycles), seed + index, no fixed
/// scene (a built-in layout is retrieved) and the style model; run_story --theme THEME
/// --difficulty D --seed S --scene '' prepares the same story.
StoryInput EvalStoryInput(const StoryEvalOptions& options, const nlohmann::json& themes,
                          const std::string& difficulty, int index);

/// Runs the protocol; returns per-difficulty and overall metrics, keyframes per skill
/// ("per_skill": keyframes, succeeded, success_rate, falls), per-story rows, and how the
/// stories ran ("batched", "batch_size", "timing": seconds to prepare, run and measure).
nlohmann::json EvaluateStories(const StoryEvalOptions& options);

/// The report's per-difficulty metrics as a small self-contained HTML page (one table row per
/// difficulty, SIMS Table 2's columns, the paper's success rates for comparison; then one row
/// per skill); eval_story writes it beside its --out JSON.
std::string StoryEvalHtml(const nlohmann::json& report);

/// Times the protocol's stories (options.difficulties × stories_per_difficulty, planned as
/// EvaluateStories plans them) run one after another (RunStory each) and batched (RunStories,
/// ThreadCount() threads); checks that both give the same outcomes and motion to the bit.
/// Returns {"stories", "sequential_s", "batched_s", "speedup", "identical", "threads", ...}.
nlohmann::json BenchStories(const StoryEvalOptions& options);

}  // namespace sims::story
