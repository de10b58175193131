// The dual-aware finite state machine: runs one simulated character through a story's
// instructions with the per-skill policies. A skill hands over to the next when its success
// condition has held for `success_hold_steps` (InterScene/SIMS rule); every skill has a
// time-out; a fall triggers get-up and then a retry; a failed step is recorded and the story
// goes on. All skills share one observation layout, so switching a skill only switches the
// task hook's goals and the policy (each policy keeps its own normaliser).
#pragma once

#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/fsm/instruction.h"
#include "sims/fsm/policy_set.h"
#include "sims/io/motion_record.h"
#include "sims/scene/navigation.h"
#include "sims/scene/scene.h"
#include "sims/sim/task_hook.h"

namespace sims::fsm {

/// FSM settings.
struct StoryOptions {
  int success_hold_steps = 20;        ///< Success must hold this long before switching (steps).
  double walk_timeout_s = 25.0;       ///< Time-out of a walk instruction, plus ...
  double walk_seconds_per_m = 2.0;    ///< ... this per metre of planned path beyond 5 m.
  double skill_timeout_s = 10.0;      ///< Time-out of the other skills (SIMS: 10 s per step).
  int max_retries = 1;                ///< Retries of an instruction after a fall.
  bool reset_after_fall = true;       ///< No get-up: put the character back on its feet.
  double fallen_head_height = 0.4;    ///< Head below this ...
  double fallen_pelvis_height = 0.4;  ///< ... and pelvis below this = fallen (m).
  double lookahead = 1.0;             ///< Walks chase a path point this far ahead (m).
  int walk_success_hold_steps = 5;    ///< A walk only needs to arrive, not to stay (steps).
  /// A walk arrives within this distance of its goal (m), whatever radius its policy was
  /// trained with (the open-floor walk 0.5 m, the furnished-room walk 0.3 m): the next skill
  /// takes over from there, and stories stay comparable across walk policies.
  double walk_success_radius = 0.5;
  scene::NavigationConfig navigation;  ///< Free-space grid and waypoints.
  bool missing_policy_fails = true;    ///< Keyframes of skills without a policy fail (else: error).
  uint64_t seed = 0;                   ///< Env seed and start placement (0: canonical start).
  int threads = 1;                     ///< Environment threads.
  sim::ObsAblation ablation;           ///< Inputs withheld from every policy (--no-text, ...).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(success_hold_steps));
    a->Visit(SIMS_NVP(walk_timeout_s));
    a->Visit(SIMS_NVP(walk_seconds_per_m));
    a->Visit(SIMS_NVP(skill_timeout_s));
    a->Visit(SIMS_NVP(max_retries));
    a->Visit(SIMS_NVP(reset_after_fall));
    a->Visit(SIMS_NVP(fallen_head_height));
    a->Visit(SIMS_NVP(fallen_pelvis_height));
    a->Visit(SIMS_NVP(lookahead));
    a->Visit(SIMS_NVP(walk_success_hold_steps));
    a->Visit(SIMS_NVP(walk_success_radius));
    a->Visit(SIMS_NVP(navigation));
    a->Visit(SIMS_NVP(missing_policy_fails));
    a->Visit(SIMS_NVP(seed));
    a->Visit(SIMS_NVP(threads));
    a->Visit(SIMS_NVP(ablation));
  }
  /// Positive times and counts.
  void Validate() const;
};

/// What happened to one instruction.
struct KeyframeOutcome {
  int keyframe = -1;         ///< Plan keyframe (−1 for FSM-inserted recoveries).
  std::string skill;         ///< Skill.
  std::string caption;       ///< Caption.
  std::string emotion;       ///< Emotion.
  std::string object;        ///< Bound object.
  double start_time = 0;     ///< Seconds since the story start.
  double end_time = 0;       ///< Seconds since the story start.
  bool success = false;      ///< Success held for the hold time.
  double contact_error = 0;  ///< Final distance the success test measures (m).
  int falls = 0;             ///< Falls during the instruction.
  int retries = 0;           ///< Retries after falls.
  std::string note;          ///< Time-out, unplaced, skill could not start, ...
};

/// A finished story.
struct StoryResult {
  std::vector<KeyframeOutcome> keyframes;  ///< One per instruction, in order.
  double success_rate = 0;                 ///< Successful instructions / instructions.
  int success_steps = 0;                   ///< Instructions completed before the first failure.
  double mean_contact_error = 0;           ///< Over instructions with an object goal.
  int falls = 0;                           ///< Total falls.
  double duration_s = 0;                   ///< Simulated seconds.
};

class StoryRunner;

/// One story of a batch: the runner that owns its scene and environment, its instructions,
/// start and (optional) motion recorder.
struct StoryJob {
  StoryRunner* runner = nullptr;                           ///< Not shared with another job.
  const std::vector<Instruction>* instructions = nullptr;  ///< Outlives the run.
  Eigen::Vector3d start = Eigen::Vector3d::Zero();         ///< Free floor point (z ignored).
  double start_heading = 0;                                ///< Radians about +z.
  io::MotionRecordBuilder* recorder = nullptr;             ///< Frames and keyframe annotations.
};

/// Runs several stories in lock-step, one character per runner (each story has its own scene,
/// so each runner has its own model and environment). Every control step makes one policy call
/// per policy over all characters whose current skill uses it, then steps the runners'
/// environments and FSMs in parallel (OpenMP over runners, `threads`; 0 = ThreadCount()); the
/// policies are never called inside the parallel loop. Each result equals what
/// StoryRunner::Run gives for that job alone, at any thread count. A job whose setup or run
/// throws stops there: with `errors` its exception lands in (*errors)[i] (others go on);
/// without, the first one (in job order) is rethrown after the others finish.
std::vector<StoryResult> RunStoriesBatched(const std::vector<StoryJob>& jobs, int threads = 0,
                                           std::vector<std::exception_ptr>* errors = nullptr);

/// Runs stories in one scene.
class StoryRunner {
 public:
  /// Compiles the scene, loads the policies the set provides and builds one skill hook per
  /// policy; throws sims::Error naming the policy file on an incompatible policy.
  StoryRunner(std::shared_ptr<const scene::Scene> scene, const PolicySet& policies,
              const StoryOptions& options);
  ~StoryRunner();

  /// Checks that every instruction's skill has a policy (and walk/getup for navigation and
  /// recovery); throws sims::Error naming the policy-set file otherwise.
  void CheckPolicies(const std::vector<Instruction>& instructions) const;
  /// Runs the instructions from `start` (a free floor point; z ignored); appends frames and
  /// keyframe annotations to `recorder` when given. RunStoriesBatched with this one job.
  StoryResult Run(const std::vector<Instruction>& instructions, const Eigen::Vector3d& start,
                  double start_heading, io::MotionRecordBuilder* recorder);
  /// A free floor point 2–4 m from the first instruction's goal with a short path to it (the
  /// direction depends on the seed), else the centre of the scene's free space.
  Eigen::Vector3d DefaultStart(const std::vector<Instruction>& instructions) const;
  /// Replaces the policies' actions (tests: scripted stand-ins for learned skills).
  using ActionOverride =
      std::function<void(const std::string& skill, const float* obs, float* action)>;
  /// Installs an action override (empty function = use the policies again).
  void SetActionOverride(ActionOverride fn);
  /// The compiled physics geometry (reused for rendering).
  const humanoid::StaticGeometry& geometry() const;
  /// The humanoid model of the scene.
  std::shared_ptr<const humanoid::Humanoid> humanoid() const;

 private:
  friend std::vector<StoryResult> RunStoriesBatched(const std::vector<StoryJob>&, int,
                                                    std::vector<std::exception_ptr>*);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// result.json content.
nlohmann::json StoryResultToJson(const StoryResult& result);

}  // namespace sims::fsm
