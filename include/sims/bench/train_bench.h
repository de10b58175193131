// Learner and training benchmarks (docs/training_speed.md): libtorch sgemm GFLOP/s on this machine
// against the GFLOP/s achieved by the PPO + AMP update of a training config, measured in one run.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/learning/distributed.h"

namespace sims::bench {

/// Runs `iterations` training iterations (after one warm-up) of the config and the sgemm
/// reference; returns sgemm_gflops, update_gflops, ratio, env_samples_per_s,
/// train_samples_per_s, threads.
nlohmann::json RunLearnerBenchmark(const std::filesystem::path& config, int iterations);

/// What bench_train measures.
struct TrainBenchOptions {
  std::filesystem::path config;  ///< Training config (configs/skills/<skill>.json).
  int iterations = 0;            ///< Measured iterations (0 = the config's checkpoint_every).
  int warmup = 2;                ///< Iterations run first and not measured.
  int num_envs = 0;              ///< Override env.num_envs (0 = the config's).
  /// Run as one rank of a data-parallel run (samples count every rank's environments); the
  /// result then also holds all-reduce traffic per iteration and measured all-reduce times.
  std::shared_ptr<learning::Communicator> comm;
  bool references = true;  ///< Also measure raw mj_step and sgemm (the scaling runs skip them).
};

/// Runs real train_policy iterations (RunTraining into a temporary directory: CSV rows,
/// progress, checkpoints every checkpoint_every) and returns the end-to-end samples_per_s,
/// the time per iteration split into env / inference / discriminator / ppo_update / logging /
/// other, the env rate against raw mj_step on copies of the skill's reset states and the
/// update's FLOP/s against sgemm, all measured in this run.
nlohmann::json RunTrainBenchmark(const TrainBenchOptions& options);

/// What bench_train --ranks measures.
struct RankBenchOptions {
  TrainBenchOptions train;          ///< Each process's run (one thread per process).
  int ranks = 2;                    ///< Processes of the data-parallel run.
  int repeats = 2;                  ///< Rounds of the three runs (means are reported).
  std::vector<std::string> worker;  ///< argv that runs one worker; "--worker-out FILE" is added.
  std::vector<int> project = {8, 32, 64};  ///< Core counts of the projection table.
};

/// Runs the config as 1 process, as `ranks` independent processes side by side, and as one
/// `ranks`-rank data-parallel run (workers on 127.0.0.1, one thread each); returns samples/s of
/// each, efficiency = data-parallel samples/s over the independent processes' total (what the
/// cores allow, so only synchronisation is charged), the all-reduce traffic and timings, and a
/// projection to larger rank counts from those measured inputs.
nlohmann::json RunRankScalingBenchmark(const RankBenchOptions& options);

/// Best-of GFLOP/s of an n×n×n float matmul in libtorch.
double MeasureSgemmGflops(int n = 1024, int repeats = 5);

}  // namespace sims::bench
