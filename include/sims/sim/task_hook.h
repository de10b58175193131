// The interface through which skills (task/) add observations, rewards, terminations and
// initial states to the batched environment without touching it. Calls for different
// environments run concurrently (OpenMP), so an implementation may only touch per-env slots.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/core/rng.h"
#include "sims/humanoid/state.h"

namespace sims::sim {

/// Read-only view of one environment after physics (or right after a reset).
struct EnvView {
  int env_id = 0;                                ///< Environment index.
  const humanoid::Humanoid* humanoid = nullptr;  ///< Shared humanoid layout/model.
  const mjData* data = nullptr;  ///< This env's MuJoCo data (positions/velocities fresh).
  const humanoid::HumanoidPose* pose = nullptr;  ///< Generalised state.
  const humanoid::BodyStates* bodies = nullptr;  ///< World-frame body states.
  int progress = 0;                              ///< Control steps since the reset.
  double control_dt = 1.0 / 30.0;                ///< Seconds per control step.
};

/// The initial state of an episode; the env fills a default that the task may replace.
struct InitialState {
  humanoid::HumanoidPose pose;  ///< State to start from.
  std::vector<humanoid::HumanoidPose>
      history;                      ///< Optional poses at t − k·dt, k = 1..9 (AMP history).
  int termination_grace_steps = 0;  ///< Steps during which falls do not terminate (get-up).
  bool reference = false;           ///< True when taken from a motion clip.
};

/// What a task reports after each control step of one env.
struct TaskStepResult {
  float reward = 0.0f;   ///< Task reward r_task.
  bool success = false;  ///< Success condition holds at this step.
  /// The task is accomplished: success has held as long as the skill requires (the figure
  /// training logs and evaluation count as a successful episode).
  bool completed = false;
  bool terminate = false;  ///< End the episode as a failure (no bootstrap).
  bool truncate = false;   ///< End the episode without failure (bootstrap), e.g. success held.
};

/// A named slice of the task observation, so networks can route it (e.g. a heightmap to a
/// convolutional or MLP encoder, the style embedding z past the normaliser).
struct ObsSegment {
  /// How a network should treat the slice.
  enum class Kind { kVector, kHeightmap, kStyle };
  std::string name;           ///< e.g. "contact_goal", "heightmap", "z".
  Kind kind = Kind::kVector;  ///< Routing.
  int offset = 0;             ///< Offset within the task observation.
  int size = 0;               ///< Number of floats.
  int rows = 0, cols = 0;     ///< Heightmap grid shape (rows·cols = size).
};

/// The input ablations of the papers (SIMS, UniHSI): a policy run with part of what it was
/// trained to see withheld.
struct ObsAblation {
  bool no_text = false;       ///< Style z zeroed (what an unconditioned policy sees).
  bool no_heightmap = false;  ///< Heightmap zeroed (flat, open floor).

  /// True when something is withheld.
  bool any() const { return no_text || no_heightmap; }
  /// Zeroes the withheld segments (`segments`: the task layout) in `n` observation rows of
  /// width `obs_dim` (223 self values, then the task observation).
  void Apply(const std::vector<ObsSegment>& segments, int n, int obs_dim, float* obs) const;

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(no_text));
    a->Visit(SIMS_NVP(no_heightmap));
  }
};

/// A skill plugged into the environment.
class TaskHook {
 public:
  virtual ~TaskHook() = default;
  /// Task observation size appended after the 223 self-observation values.
  virtual int obs_dim() const = 0;
  /// Layout of the task observation (default: one vector segment).
  virtual std::vector<ObsSegment> obs_segments() const;
  /// Chooses the initial state (may leave the env's default); runs before physics state is set.
  virtual void SampleInitialState(int env_id, Rng& rng, InitialState* init) = 0;
  /// Samples goals/objects once the initial state is in place.
  virtual void OnReset(const EnvView& view, Rng& rng) = 0;
  /// Reward, success and termination after a control step.
  virtual TaskStepResult Step(const EnvView& view) = 0;
  /// Writes obs_dim() task observation values.
  virtual void Observe(const EnvView& view, float* out) const = 0;
  /// Bitmask of AMP bodies allowed to touch the ground/scene without counting as a fall.
  virtual uint32_t contact_body_mask() const;
  /// Style (clip) id of the env's episode for conditional AMP, or −1.
  virtual int style_id(int env_id) const {
    (void)env_id;
    return -1;
  }
  /// Env `env_id`'s curriculum level in [0, 1] (spawn distance, backplay window...) for the
  /// training log; NaN when the skill runs no curriculum.
  virtual double curriculum_level(int env_id) const {
    (void)env_id;
    return std::numeric_limits<double>::quiet_NaN();
  }
  /// Per-env task state (goals, counters) so training can resume bit-exactly.
  virtual std::vector<double> SaveEnvState(int env_id) const {
    (void)env_id;
    return {};
  }
  /// Restores SaveEnvState() output.
  virtual void LoadEnvState(int env_id, const std::vector<double>& state) {
    (void)env_id;
    (void)state;
  }
};

/// Feet only (ASE's default contact bodies).
uint32_t FeetContactMask();

}  // namespace sims::sim
