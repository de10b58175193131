// Learner benchmark (ARCHITECTURE §6): libtorch sgemm GFLOP/s on this machine against the
// GFLOP/s achieved by the PPO + AMP update of a training config, measured in one run.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace sims::learning {

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
};

/// Runs real train_policy iterations (RunTraining into a temporary directory: CSV rows,
/// progress, checkpoints every checkpoint_every) and returns the end-to-end samples_per_s,
/// the time per iteration split into env / inference / discriminator / ppo_update / logging /
/// other, the env rate against raw mj_step on copies of the skill's reset states and the
/// update's FLOP/s against sgemm, all measured in this run.
nlohmann::json RunTrainBenchmark(const TrainBenchOptions& options);

/// Best-of GFLOP/s of an n×n×n float matmul in libtorch.
double MeasureSgemmGflops(int n = 1024, int repeats = 5);

}  // namespace sims::learning
