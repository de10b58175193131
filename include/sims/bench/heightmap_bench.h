// Heightmap benchmark (apps/bench_heightmap): raw Embree down-ray rate on the built-in house, the
// egocentric sampler's cost per env per control step, and the raw physics cost per env per
// control step (4 × mj_step of the humanoid in the house model), measured in one run.
#pragma once

#include <nlohmann/json.hpp>

namespace sims::bench {

/// Benchmark settings.
struct HeightmapBenchOptions {
  int rays = 1'000'000;       ///< Down-rays for the raw Embree rate.
  int num_envs = 256;         ///< Environments sampled per heightmap batch.
  int sampler_repeats = 200;  ///< Batches timed for the sampler.
  int physics_envs = 8;       ///< Humanoids stepped for the physics reference.
  int control_steps = 150;    ///< Control steps (4 physics steps each) per physics run.
  int repeats = 3;            ///< Best-of repeats per measurement.
};

/// Runs the benchmark single-threaded (and the ray rate also at the process thread count);
/// returns rays_per_s, rays_per_s_threads, grid_build_s, sampler_us_per_env,
/// sampler_unihsi_us_per_env, physics_us_per_env, physics_empty_floor_us_per_env,
/// ratio (= sampler / physics) and settings.
nlohmann::json RunHeightmapBenchmark(const HeightmapBenchOptions& options);

}  // namespace sims::bench
