// The run_story job: script / plan / theme / single instruction → plan → instructions →
// StoryRunner → outputs. Outputs are assembled in DIR.partial and renamed to DIR at the end,
// so an interrupted or failed run never leaves a directory that looks complete.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "sims/core/environment.h"
#include "sims/fsm/story_runner.h"

namespace sims::fsm {

/// What run_story was asked to do.
struct StoryJob {
  std::string input;                    ///< Script or plan JSON ("" with theme or instruction).
  std::string theme;                    ///< Plan from a theme.
  std::string instruction;              ///< LINGO-style single sentence.
  std::string scene_plan;               ///< UniHSI ScenePlan "plan.json[#id]" (scene + chain).
  std::string partnet_root;             ///< PartNet folder for it ("" = $SIMS_PARTNET_DIR,
                                        ///< data/partnet).
  std::optional<Eigen::Vector3d> goal;  ///< Optional goal location for the instruction.
  std::string difficulty = "mid";       ///< Theme difficulty.
  std::string scene = "house";          ///< Built-in scene name or scene file.
  std::string policies;                 ///< Policy-set JSON ("" = assets/policies/policies.json).
  std::filesystem::path out_dir = "out/story";  ///< Output directory.
  bool video = false;                           ///< Also render DIR/story.mp4.
  std::string style_model;  ///< Motion–text model for caption → z ("" = data/language/text_motion
                            ///< if present).
  StoryOptions options;  ///< FSM settings (seed included).
  /// Fills the LLM settings configs/planner/planner.json leaves open (--theme; see
  /// planner::WithEnvironment): run_story passes InstalledEnvironment(), the default fills
  /// nothing.
  Environment environment;
};

/// Turns a sentence into a one-interaction long-script JSON (skill and furniture found by the
/// planner vocabulary); throws sims::Error when the sentence names no known skill.
nlohmann::json InstructionToScriptJson(const std::string& sentence);

/// Runs the job and writes DIR/{result.json, motion.json, motion.bvh, scene.glb, index.html,
/// story.txt, plan.json, config.json[, story.mp4]}. Returns result.json's content.
nlohmann::json RunStoryJob(const StoryJob& job);

}  // namespace sims::fsm
