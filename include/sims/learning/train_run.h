// The train_policy job: config → skill + env + learner, the iteration loop with progress,
// CSV log, HTML report, atomic checkpoints every K iterations and resume.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>

#include "sims/learning/config.h"
#include "sims/learning/distributed.h"
#include "sims/learning/trainer.h"
#include "sims/sim/env.h"
#include "sims/task/skill.h"

namespace sims::learning {

/// Everything train_policy reads from configs/skills/<skill>.json.
struct TrainConfig {
  sim::EnvConfig env;         ///< Batched environment.
  task::SkillConfig skill;    ///< Skill and its motion data.
  LearnerConfig learner;      ///< PPO + AMP.
  int iterations = 1000;      ///< Total iterations of the run.
  int checkpoint_every = 25;  ///< Checkpoint + policy + report every K iterations.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(env));
    a->Visit(SIMS_NVP(skill));
    a->Visit(SIMS_NVP(learner));
    a->Visit(SIMS_NVP(iterations));
    a->Visit(SIMS_NVP(checkpoint_every));
  }
  /// Checks counts.
  void Validate() const;
};

/// Wall-clock figures of one training iteration as train_policy logs them.
struct IterationTiming {
  double interval_seconds = 0;  ///< End of the previous iteration's update to end of this one.
  double logging_seconds = 0;   ///< Of that interval: the previous row, progress, checkpoint.
  double samples_per_s = 0;     ///< Batch size / interval: the rate a user's run sees.
};

/// Command-line overrides.
struct TrainOptions {
  std::filesystem::path out_dir = "runs/train";  ///< Outputs (config, log, checkpoints).
  bool resume = false;                           ///< Continue from out_dir/checkpoint.pt.
  std::optional<int> iterations;                 ///< Override TrainConfig::iterations.
  std::optional<uint64_t> seed;                  ///< Override env and learner seeds.
  std::optional<std::string> skill;              ///< Must match the config's skill if set.
  /// Warm start from another run's checkpoint (same network and env).
  std::filesystem::path init_from;
  /// Initialise actor, critic and normaliser from a policy file (e.g. walk for other skills).
  std::filesystem::path init_policy;
  /// Called after each iteration is logged (benchmarks read the timing through it).
  std::function<void(const IterationStats&, const IterationTiming&)> on_iteration;
  /// Data-parallel run when set: this process is one rank. Rank 0 resolves the config and
  /// alone reads and writes out_dir (config, log, checkpoints, report); every rank runs
  /// env.num_envs environments, so the batch is world_size times larger.
  std::shared_ptr<Communicator> comm;
  /// Parameter checksum interval across ranks (iterations).
  int check_every = 10;
};

/// The training configs train_policy stores in a policy's metadata ("extra").
struct PolicyConfigs {
  task::SkillConfig skill;            ///< extra.skill.
  std::optional<sim::EnvConfig> env;  ///< extra.env, when stored.
};

/// Reads a policy's stored configs; throws sims::Error naming `source` when it has none.
PolicyConfigs ReadPolicyConfigs(const Policy& policy, const std::string& source);

/// The AMP demonstrations of a run: the skill's clips in windows of env.amp_history steps,
/// style-labelled when the discriminator is conditional, drawn per emotion as the skill's
/// episodes are. Null when AMP is off or the skill has no motion library.
std::shared_ptr<const DemoSource> MakeTrainingDemos(const TrainConfig& config,
                                                    const task::SkillSetup& setup);

/// Runs (or resumes) training; returns the final iteration count.
int64_t RunTraining(TrainConfig config, const TrainOptions& options);

}  // namespace sims::learning
