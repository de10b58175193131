// The one story pipeline. run_story and eval_story both go through these three steps, so the
// stories eval_story measures are the stories run_story shows:
//
//   PreparedStory p = PrepareStory(input);          // plan, scene, instructions, style z
//   StoryRun run = RunStory(p, policies, options);  // the FSM over the instructions
//   WriteStoryRun("out/story", run);                // result.json, motion, viewer, ...
//
// The FSM (fsm/) only runs instructions; planning, captions → z and output files live here.
#pragma once

#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "sims/core/config.h"
#include "sims/core/environment.h"
#include "sims/fsm/instruction.h"
#include "sims/fsm/policy_set.h"
#include "sims/fsm/story_runner.h"
#include "sims/humanoid/model_builder.h"
#include "sims/io/motion_record.h"
#include "sims/planner/plan.h"
#include "sims/scene/scene.h"

namespace sims::story {

/// What story to prepare: exactly one of input, theme, instruction, scene_plan.
struct StoryInput {
  std::string input;                    ///< Script or plan JSON file.
  std::string theme;                    ///< Plan from a theme.
  std::string instruction;              ///< LINGO-style single sentence.
  std::string scene_plan;               ///< UniHSI ScenePlan "plan.json[#id]" (scene + chain).
  std::string partnet_root;             ///< PartNet folder for it ("" = data/partnet).
  std::optional<Eigen::Vector3d> goal;  ///< Optional goal of the last instruction.
  std::string difficulty = "mid";       ///< Theme difficulty (simple | mid | hard).
  /// Built-in scene name or scene file the story is placed in; "" = retrieve a layout from the
  /// built-in layout database (what plan_story and eval_story do).
  std::string scene = "house";
  /// Motion–text model folder for caption → z ("" = data/language/text_motion if present;
  /// no z without one).
  std::string style_model;
  uint64_t seed = 0;  ///< Theme planning seed (the apps pass the FSM seed).
  /// Fills the LLM settings configs/planner/planner.json leaves open (--theme; see
  /// planner::WithEnvironment): the apps pass InstalledEnvironment(), the default fills nothing.
  Environment environment;
};

/// A story ready to run: everything that does not depend on the policies or the FSM settings.
struct PreparedStory {
  StoryInput input;          ///< What it was prepared from.
  planner::Plan plan;        ///< The plan (for a ScenePlan: planner "sceneplan", no keyframes).
  nlohmann::json plan_json;  ///< plan.json content.
  std::shared_ptr<const scene::Scene> scene;   ///< The scene the instructions are bound in.
  std::vector<fsm::Instruction> instructions;  ///< Bound instructions, style z filled in.
  /// Per instruction, how its caption was understood (nearest training captions and clips);
  /// empty without a style model.
  nlohmann::json styles = nlohmann::json::array();
  std::string title;  ///< Motion title: the theme, else the instruction or input file.
};

/// Plans (or loads) the story, loads its scene, binds instructions and turns their captions into
/// style vectors z. Throws sims::Error naming the input on anything invalid.
PreparedStory PrepareStory(const StoryInput& input);

/// A finished story run.
struct StoryRun {
  PreparedStory story;             ///< The story that ran.
  std::filesystem::path policies;  ///< The policy-set file.
  fsm::StoryOptions options;       ///< FSM settings (seed included).
  fsm::StoryResult result;         ///< Per-keyframe outcomes and totals.
  io::MotionRecord record;         ///< The motion with keyframe annotations.
  /// The run's physics geometry, kept so a video reuses it instead of compiling the scene again.
  std::shared_ptr<const humanoid::StaticGeometry> geometry;
  std::shared_ptr<const humanoid::Humanoid> humanoid;  ///< The humanoid the motion is of.
};

/// Runs the prepared story with the FSM: one character from the runner's default start.
/// Throws sims::Error when a needed policy is missing and options.missing_policy_fails is false.
StoryRun RunStory(const PreparedStory& story, const fsm::PolicySet& policies,
                  const fsm::StoryOptions& options);

/// Runs several prepared stories at once, story i with options[i] (its seed): each gets its own
/// runner (its scene, environment and start), and all advance in lock-step with one policy call
/// per policy per control step (fsm::RunStoriesBatched; the environments step on `threads`
/// threads, 0 = ThreadCount()). runs[i] equals RunStory(stories[i], policies, options[i]). A
/// story that cannot be set up or run gets its exception in (*errors)[i] and an empty run (its
/// `story` filled in) while the others go on; without `errors` the first one is rethrown.
std::vector<StoryRun> RunStories(const std::vector<PreparedStory>& stories,
                                 const fsm::PolicySet& policies,
                                 const std::vector<fsm::StoryOptions>& options,
                                 std::vector<std::exception_ptr>* errors = nullptr,
                                 int threads = 0);

/// result.json content: the FSM result plus planner, scene, seed, policies and styles.
nlohmann::json StoryRunToJson(const StoryRun& run);

/// Which optional outputs WriteStoryRun renders.
struct StoryWriteOptions {
  bool video = false;  ///< Also render DIR/story.mp4.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(video));
  }
};

/// Writes DIR/{result.json, motion.json, motion.bvh, scene.glb, index.html, story.txt,
/// plan.json, config.json[, story.mp4]}. Everything is assembled in DIR.partial and renamed to
/// DIR at the end, so an interrupted or failed run never leaves a directory that looks complete.
/// Returns result.json's content.
nlohmann::json WriteStoryRun(const std::filesystem::path& dir, const StoryRun& run,
                             const StoryWriteOptions& options = {});

}  // namespace sims::story
