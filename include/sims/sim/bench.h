// Environment benchmark: the batched env step against a raw mj_step loop on the same model,
// measured in one run (ARCHITECTURE §6), used by apps/bench_env.
#pragma once

#include <nlohmann/json.hpp>

namespace sims::sim {

/// Benchmark settings.
struct EnvBenchOptions {
  int num_envs = 16;          ///< Environments (and raw mjData instances).
  int control_steps = 200;    ///< Control steps per measurement.
  int repeats = 3;            ///< Best-of repeats per measurement.
  int max_threads = 0;        ///< Largest thread count for the scaling figure (0 = hardware).
  double action_noise = 0.1;  ///< Perturbation around the standing pose.
};

/// Runs the benchmark; returns raw_steps_per_s, env_physics_steps_per_s, ratio, threads,
/// scaling and per-thread-count details.
nlohmann::json RunEnvBenchmark(const EnvBenchOptions& options);

}  // namespace sims::sim
