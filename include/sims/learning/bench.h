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

/// Best-of GFLOP/s of an n×n×n float matmul in libtorch.
double MeasureSgemmGflops(int n = 1024, int repeats = 5);

}  // namespace sims::learning
