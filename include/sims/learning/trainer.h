// The PPO + (conditional) AMP learner over any VecEnv. libtorch stays behind the pimpl so apps
// and other modules include this header without torch.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sims/learning/config.h"
#include "sims/learning/distributed.h"
#include "sims/learning/vec_env.h"

namespace sims::learning {

/// What one iteration (rollout + update) measured.
struct IterationStats {
  int64_t iteration = 0;              ///< Iterations completed (after this one).
  int64_t samples = 0;                ///< Environment transitions so far.
  double task_reward = 0;             ///< Mean task reward per step.
  double style_reward = 0;            ///< Mean style reward per step.
  double total_reward = 0;            ///< Mean combined reward per step.
  double episode_return = 0;          ///< Mean combined return of episodes ended this iteration.
  double episode_length = 0;          ///< Mean length (steps) of those episodes.
  int64_t episodes = 0;               ///< Episodes ended this iteration.
  double success_rate = 0;            ///< Fraction of those episodes the task completed.
  double fall_rate = 0;               ///< Fraction of those episodes that ended by a fall/blow-up.
  double force_end_rate = 0;          ///< Fraction the task terminated (e.g. contact force).
  double reference_start_share = 0;   ///< Fraction that began from a reference state.
  double success_rate_reference = 0;  ///< success_rate of reference-start episodes (NaN: none).
  double success_rate_default = 0;    ///< success_rate of default-start episodes (NaN: none).
  double actor_loss = 0;              ///< Mean clipped surrogate loss.
  double critic_loss = 0;             ///< Mean value loss.
  double bounds_loss = 0;             ///< Mean bounds loss.
  /// Mean (μ(s_t) − μ(s_t+1))² per action dim over consecutive rollout states (chatter).
  double smooth_loss = 0;
  double disc_loss = 0;            ///< Mean discriminator classification loss.
  double grad_penalty = 0;         ///< Mean gradient penalty.
  double disc_acc_demo = 0;        ///< Discriminator accuracy on demo windows.
  double disc_acc_agent = 0;       ///< Discriminator accuracy on policy/replay windows.
  double clip_fraction = 0;        ///< Fraction of clipped ratios.
  double kl = 0;                   ///< Mean KL(old ‖ new) per minibatch step.
  double learning_rate = 0;        ///< The learning rate after this update.
  double curriculum_level = 0;     ///< Mean curriculum level after the rollout (NaN: none).
  double env_samples_per_s = 0;    ///< Collection throughput (incl. policy inference).
  double train_samples_per_s = 0;  ///< Update throughput (samples × epochs / s).
  double update_gflop = 0;         ///< Estimated GFLOP spent in the update.
  double update_seconds = 0;       ///< Time spent in the update (PPO and discriminator).
  double env_seconds = 0;          ///< Rollout time inside VecEnv::Step.
  double inference_seconds = 0;    ///< Rollout time outside it (policy, value, buffers).
  double disc_seconds = 0;         ///< Style rewards + discriminator loss forward/backward.
  double ppo_seconds = 0;          ///< Advantages, PPO forward/backward, optimiser steps.
  double iteration_seconds = 0;    ///< Wall time of the iteration.
};

/// PPO + AMP trainer.
class Trainer {
 public:
  /// `demo` may be null when AMP is disabled. Initialises networks from config.seed.
  /// With `comm` (data-parallel), this trainer is one rank: `env` holds this rank's share of
  /// the environments (same count on every rank; global env id = rank × num_envs + i), batch
  /// sizes in `config` are per rank, rank 0's weights are broadcast, gradients and normaliser
  /// statistics are all-reduced, and a parameter checksum is compared every `check_every`
  /// iterations. The update equals that of one process over all ranks' environments.
  Trainer(std::shared_ptr<VecEnv> env, std::shared_ptr<const DemoSource> demo,
          const LearnerConfig& config, std::shared_ptr<Communicator> comm = nullptr,
          int check_every = 10);
  ~Trainer();
  Trainer(const Trainer&) = delete;
  Trainer& operator=(const Trainer&) = delete;

  /// Collects horizon × num_envs transitions and runs the PPO (+ discriminator) update.
  IterationStats RunIteration();
  /// Iterations completed.
  int64_t iteration() const;
  /// The learning rate the next update uses (the adaptive schedule moves it).
  double learning_rate() const;
  /// Writes a checkpoint atomically: networks, normalisers, RNG, environment state, counters
  /// and, when `full`, the optimiser's moments and the AMP replay buffer. A compact one (not
  /// full) is ~30× smaller: what a training campaign commits between sessions. Resuming from it
  /// is exact except that the replay buffer refills from the next rollouts and Adam's moments
  /// restart from zero (the learning rate is kept).
  void SaveCheckpoint(const std::filesystem::path& path, bool full = true) const;
  /// Restores SaveCheckpoint() output (full or compact); throws sims::Error naming the file on
  /// mismatch.
  void LoadCheckpoint(const std::filesystem::path& path);
  /// Copies rank 0's learner state (networks, normalisers, optimiser, counters) to every
  /// rank; call on all ranks after rank 0 alone loaded a checkpoint or policy. No-op alone.
  void Synchronize();
  /// Starts from another skill's exported policy: actor, critic and observation normaliser
  /// (same observation layout and network sizes); the rest keeps its fresh state.
  void InitFromPolicy(const std::filesystem::path& policy_file);
  /// Writes the small inference file (actor, critic, observation normaliser, layout);
  /// `extra_json` (an object, e.g. the skill and env configs) is stored under "extra".
  void ExportPolicy(const std::filesystem::path& path, const std::string& extra_json = "") const;
  /// All network parameters flattened (tests compare runs with it).
  std::vector<float> FlatParameters() const;
  /// Deterministic actions (the Gaussian mean) for observations [n, obs_dim].
  void ActMean(const float* obs, int n, float* actions) const;
  /// The resolved config.
  const LearnerConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Inference-only policy loaded from an ExportPolicy() file (what eval and the FSM run).
class Policy {
 public:
  /// Loads the file; throws sims::Error naming it when missing or malformed.
  explicit Policy(const std::filesystem::path& path);
  ~Policy();
  Policy(Policy&&) noexcept;
  Policy& operator=(Policy&&) noexcept;
  /// Observation width the policy expects.
  int obs_dim() const;
  /// Action width.
  int action_dim() const;
  /// Deterministic actions [n, action_dim] for observations [n, obs_dim].
  void Act(const float* obs, int n, float* actions) const;
  /// What Act gives each row alone, to the bit, in as few Act calls as the BLAS allows: a batch
  /// goes in chunks of RowExactRows() rows.
  void ActRowExact(const float* obs, int n, float* actions) const;
  /// The most rows one Act call takes while giving every row exactly what Act gives it alone.
  /// A BLAS blocks a batch's rows (OpenBLAS 0.3.21 on this x86: blocks of four rows, then a
  /// tail of 1-3 rows computed like a single row), and a block rounds unlike a lone row, so
  /// this is probed once per policy on random rows (1 to 64 rows; at least 1).
  int RowExactRows() const;
  /// Metadata stored with the policy (skill name, config, layout).
  const std::string& metadata_json() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sims::learning
