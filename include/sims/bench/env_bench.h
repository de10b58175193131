// Environment benchmark: the batched env step against a raw mj_step loop on the same model,
// measured in one run, used by apps/bench_env.
#pragma once

#include <nlohmann/json.hpp>

namespace sims::sim {
class BatchedEnv;
}  // namespace sims::sim

namespace sims::bench {

/// Benchmark settings.
struct EnvBenchOptions {
  int num_envs = 16;          ///< Environments (and raw mjData instances).
  int control_steps = 200;    ///< Control steps per measurement.
  int repeats = 3;            ///< Best-of repeats per measurement.
  int max_threads = 0;        ///< Largest thread count for the scaling figure (0 = hardware).
  double action_noise = 0.1;  ///< Perturbation around the standing pose.
};

/// Raw physics reference for any scene: copies of `env`'s current mjData states, their
/// controls held, stepped with plain mj_step `substeps` times per control step in an OpenMP
/// loop with `threads` threads. Returns the best-of-`repeats` mj_step calls per second.
double RawStepsPerSecondFrom(sim::BatchedEnv& env, int threads, int control_steps, int repeats = 3);

/// Runs the benchmark; returns raw_steps_per_s, env_physics_steps_per_s, ratio, threads,
/// scaling and per-thread-count details.
nlohmann::json RunEnvBenchmark(const EnvBenchOptions& options);

}  // namespace sims::bench
