// eval_story: SIMS Table 2 protocol. For each difficulty (simple, mid, hard) N scripts are
// planned from themes on the built-in layouts and run with a policy set; reported are the
// success rate, contact error and success steps, plus penetration and foot sliding over the
// motion and FID/APD of the generated poses against the reference clips.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/core/environment.h"
#include "sims/fsm/story_runner.h"

namespace sims::eval {

/// What to evaluate.
struct StoryEvalOptions {
  std::filesystem::path policies;            ///< Policy set ("" = default).
  std::filesystem::path themes;              ///< Theme list ("" = configs/eval/story_themes.json).
  std::filesystem::path reference_manifest;  ///< Clips for FID ("" = no FID).
  std::vector<std::string> difficulties = {"simple", "mid", "hard"};  ///< Difficulties.
  int stories_per_difficulty = 5;                                     ///< N.
  uint64_t seed = 0;                                                  ///< Story i uses seed + i.
  fsm::StoryOptions story;  ///< FSM settings; missing skill policies count as failures.
  /// LLM fall-backs for planning the themes (planner::PlanRequest::environment); eval_story
  /// passes InstalledEnvironment(), the default fills nothing.
  Environment environment;
};

/// Runs the protocol; returns per-difficulty and overall metrics plus per-story rows.
nlohmann::json EvaluateStories(const StoryEvalOptions& options);

}  // namespace sims::eval
