// The batched environment (EnvPool style): one shared read-only mjModel, one mjData per env,
// an OpenMP loop over envs, and preallocated [num_envs, dim] float buffers that libtorch can
// wrap without copying. Resets happen inside Step(): after a done, the observation row already
// belongs to the new episode and terminal_observations() keeps the last one of the old episode.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sims/core/config.h"
#include "sims/core/rng.h"
#include "sims/humanoid/features.h"
#include "sims/sim/task_hook.h"

namespace sims::sim {

/// Environment settings (configs/env.json style).
struct EnvConfig {
  int num_envs = 16;                     ///< Parallel environments.
  int substeps = 4;                      ///< Physics steps per control step (120 Hz → 30 Hz).
  int episode_length = 300;              ///< Control steps before a time-out (10 s).
  bool early_termination = true;         ///< Reset on falls.
  double termination_height = 0.15;      ///< Non-contact body below this (m) + contact = fall.
  double head_termination_height = 0.3;  ///< Head threshold (ASE uses max(0.3, ·)).
  double spawn_radius = 0.0;             ///< Default init: root xy uniform in this disc (m).
  bool random_heading = true;            ///< Default init: heading uniform in [−π, π).
  double max_velocity = 1000.0;          ///< |qvel| beyond this is treated as a blow-up.
  int amp_history = 10;                  ///< AMP observation steps stacked.
  bool root_height_obs = true;           ///< ASE rootHeightObs.
  bool local_root_obs = true;            ///< Heading-local root rotation (InterScene).
  int threads = 0;                       ///< OpenMP threads for the env loop (0 = ThreadCount()).
  uint64_t seed = 0;                     ///< Env i draws from Rng(seed + i).
  /// ASE recovery episodes: a fall ends the episode only with probability 1 − p; otherwise the
  /// env goes on with falls ignored for recovery_steps (the policy practises getting up from
  /// the fall it just had). 0 = off.
  double recovery_episode_prob = 0.0;
  int recovery_steps = 60;  ///< Grace of a recovery episode (control steps; ASE 60).
  /// Each control step's PD targets are blended with the ones the actuators held before
  /// (after a reset: the initial pose), α·held + (1 − α)·new: damps a policy whose action
  /// jumps between steps (the feet tapping in place). 0 = off; at most kMaxActionSmoothing.
  double action_smoothing = 0.0;
  /// Share w of each step's reward paid for steady PD targets: r = (1 − w)·r_task +
  /// w·exp(−action_rate_scale·mean_j Δ_j²), Δ_j the new target of joint j minus the one its
  /// actuator held (rad). Why: the trained policies chatter (targets jumping ~0.2–0.5 rad rms
  /// per step, joint velocities uncorrelated step to step), which the feet show as sliding and
  /// the discriminator as a trivial tell. 0 = off.
  double action_rate_weight = 0.0;
  double action_rate_scale = 10.0;  ///< 1/rad²: a 0.3 rad rms jump pays e^−0.9 at 10.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(num_envs));
    a->Visit(SIMS_NVP(substeps));
    a->Visit(SIMS_NVP(episode_length));
    a->Visit(SIMS_NVP(early_termination));
    a->Visit(SIMS_NVP(termination_height));
    a->Visit(SIMS_NVP(head_termination_height));
    a->Visit(SIMS_NVP(spawn_radius));
    a->Visit(SIMS_NVP(random_heading));
    a->Visit(SIMS_NVP(max_velocity));
    a->Visit(SIMS_NVP(amp_history));
    a->Visit(SIMS_NVP(root_height_obs));
    a->Visit(SIMS_NVP(local_root_obs));
    a->Visit(SIMS_NVP(threads));
    a->Visit(SIMS_NVP(seed));
    a->Visit(SIMS_NVP(recovery_episode_prob));
    a->Visit(SIMS_NVP(recovery_steps));
    a->Visit(SIMS_NVP(action_smoothing));
    a->Visit(SIMS_NVP(action_rate_weight));
    a->Visit(SIMS_NVP(action_rate_scale));
  }
  /// Throws FieldError on out-of-range values.
  void Validate() const;
};

/// Largest action smoothing accepted: at α → 1 the character would stop following its policy.
inline constexpr double kMaxActionSmoothing = 0.9;

/// Throws sims::Error naming `source` and `field` unless 0 ≤ alpha ≤ kMaxActionSmoothing.
void CheckActionSmoothing(double alpha, std::string_view source, std::string_view field);

/// Counters of why episodes ended.
struct EnvStats {
  int64_t steps = 0;          ///< Control steps summed over envs.
  int64_t episodes = 0;       ///< Completed episodes.
  int64_t falls = 0;          ///< Fall terminations.
  int64_t timeouts = 0;       ///< Episode-length truncations.
  int64_t task_ends = 0;      ///< Task terminations/truncations.
  int64_t instabilities = 0;  ///< NaN / blow-up resets.
  int64_t recoveries = 0;     ///< Falls turned into recovery episodes (not counted as falls).
};

/// Why an env's episode ended at a step (kNone: it goes on).
enum class EndReason : uint8_t {
  kNone = 0,       ///< Still running.
  kFall,           ///< Early termination: a body other than the allowed ones fell too low.
  kTimeout,        ///< Episode length reached (bootstrap).
  kTaskTerminate,  ///< The task ended it as a failure (e.g. excessive contact force).
  kTaskTruncate,   ///< The task ended it without failure (e.g. success held).
  kUnstable,       ///< The simulation blew up; the env was reset.
};

/// The batched humanoid environment.
class BatchedEnv {
 public:
  /// `task` may be null (plain humanoid: zero reward, no task observation).
  BatchedEnv(std::shared_ptr<const humanoid::Humanoid> humanoid, const EnvConfig& config,
             std::shared_ptr<TaskHook> task = nullptr);
  ~BatchedEnv();
  BatchedEnv(const BatchedEnv&) = delete;
  BatchedEnv& operator=(const BatchedEnv&) = delete;

  /// Resets every env (episode counters are not incremented).
  void Reset();
  /// Applies actions [num_envs, 28] in [−1, 1], runs `substeps` physics steps per env, computes
  /// observations, rewards and dones, and resets finished envs.
  void Step(const float* actions);
  /// Resets one env now (e.g. when a caller decides to restart it).
  void ResetEnv(int env_id);
  /// Sets one env's action smoothing α (EnvConfig::action_smoothing; a story sets its
  /// character's to the running skill's).
  void set_action_smoothing(int env_id, double alpha);

  /// Number of environments.
  int num_envs() const { return config_.num_envs; }
  /// Observation width: 223 + task obs_dim().
  int obs_dim() const { return obs_dim_; }
  /// Action width (28).
  int action_dim() const { return humanoid::kNumDofs; }
  /// AMP observation width: 125 × amp_history.
  int amp_obs_dim() const { return humanoid::kAmpObsStepDim * config_.amp_history; }
  /// Seconds per control step.
  double control_dt() const;

  /// Observations [num_envs, obs_dim()] (after auto-reset for finished envs).
  float* observations() { return obs_.data(); }
  /// Observations of the step that ended an episode [num_envs, obs_dim()], valid where done.
  const float* terminal_observations() const { return terminal_obs_.data(); }
  /// Task rewards [num_envs].
  const float* rewards() const { return rewards_.data(); }
  /// 1 where the episode ended at this step [num_envs].
  const uint8_t* dones() const { return dones_.data(); }
  /// 1 where it ended by failure (fall, blow-up, task termination): no bootstrap [num_envs].
  const uint8_t* terminated() const { return terminated_.data(); }
  /// 1 where the task's success condition held at this step [num_envs].
  const uint8_t* successes() const { return successes_.data(); }
  /// 1 where the task reported itself accomplished at this step (TaskStepResult::completed).
  const uint8_t* completions() const { return completions_.data(); }
  /// Why each env's episode ended at this step (EndReason, kNone where it goes on).
  const EndReason* end_reasons() const { return end_reason_.data(); }
  /// 1 where this step's episode began from a reference (motion clip) state [num_envs].
  const uint8_t* reference_starts() const { return episode_reference_.data(); }
  /// AMP observations of this step's transition, before any reset [num_envs, amp_obs_dim()],
  /// ordered [t, t−1, …].
  const float* amp_observations() const { return amp_obs_.data(); }

  /// Episode-end counters.
  const EnvStats& stats() const { return stats_; }
  /// The shared humanoid.
  const humanoid::Humanoid& humanoid() const { return *humanoid_; }
  /// Mutable MuJoCo data of one env (tests, tools, renderers).
  mjData* data(int env_id);
  /// Current generalised state of one env.
  const humanoid::HumanoidPose& pose(int env_id) const;
  /// Current body states of one env.
  const humanoid::BodyStates& bodies(int env_id) const;
  /// Control steps since the env's last reset.
  int progress(int env_id) const;
  /// Recomputes one env's observation row after its task's goals changed (a skill switch or a
  /// new target mid-episode), so the next action sees them.
  void RefreshTaskObservation(int env_id);
  /// Overwrites an env's state (keeps its episode running) and refreshes its observations.
  void SetState(int env_id, const humanoid::HumanoidPose& pose);
  /// Serialises every env's simulation, RNG, history and task state (binary string).
  std::string SaveState() const;
  /// Restores SaveState() output and recomputes observations; throws sims::Error on mismatch
  /// or malformed data and then leaves the environment as it was.
  void LoadState(const std::string& state);
  /// The env's task hook (may be null).
  TaskHook* task() const { return task_.get(); }
  /// The resolved config.
  const EnvConfig& config() const { return config_; }
  /// What a task hook sees of env i (its state after the last step or reset).
  EnvView View(int i) const;

 private:
  struct Slot;
  void StepEnv(int i, const float* action);
  // `sim2_stats`: counters in a SIM2 snapshot's stats (6 or 7; see env.cpp).
  void ApplyState(const std::string& state, int sim2_stats);
  void ResetSlot(int i);
  void RefreshObservation(int i, bool fill_history);
  bool Unstable(int i) const;
  bool Fallen(int i) const;

  std::shared_ptr<const humanoid::Humanoid> humanoid_;
  EnvConfig config_;
  std::shared_ptr<TaskHook> task_;
  int obs_dim_ = humanoid::kSelfObsDim;
  int threads_ = 1;
  humanoid::ObsOptions obs_options_;
  uint32_t contact_mask_ = 0;
  std::vector<std::unique_ptr<Slot>> slots_;
  std::vector<float> obs_, terminal_obs_, rewards_, amp_obs_;
  std::vector<uint8_t> dones_, terminated_, successes_, completions_, episode_reference_;
  std::vector<double> action_smoothing_;  // per env
  // Per-env end reasons from the parallel loop, summed serially afterwards.
  std::vector<EndReason> end_reason_;
  std::vector<uint8_t> recovered_;  // 1: this step's fall became a recovery episode
  EnvStats stats_;
};

}  // namespace sims::sim
