// bench_heightmap: Embree down-ray rate, egocentric heightmap sampling and raw physics per env
// per control step on the built-in house (prints JSON; target ratio < 0.1).
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/bench/heightmap_bench.h"
#include "sims/core/app.h"
#include "sims/core/log.h"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark heightmap sampling against the physics step (prints JSON)"};
  sims::bench::HeightmapBenchOptions o;
  bool json = false;
  app.add_flag("--json", json, "print only the JSON result");
  app.add_option("--rays", o.rays, "down-rays for the raw Embree rate")->check(CLI::PositiveNumber);
  app.add_option("--envs", o.num_envs, "environments per heightmap batch")
      ->check(CLI::PositiveNumber);
  app.add_option("--physics-envs", o.physics_envs, "humanoids in the physics reference")
      ->check(CLI::PositiveNumber);
  app.add_option("--steps", o.control_steps, "control steps per physics run")
      ->check(CLI::PositiveNumber);
  app.add_option("--repeats", o.repeats, "best-of repeats")->check(CLI::PositiveNumber);
  sims::AppFlags flags;
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  if (json) flags.default_log_level = "warn";
  return sims::RunApp(flags, [&] {
    const auto result = sims::bench::RunHeightmapBenchmark(o);
    if (!json)
      spdlog::info("sampler/physics ratio: {:.4f} (target < 0.1)", result["ratio"].get<double>());
    std::cout << result.dump(json ? -1 : 2) << std::endl;
    return 0;
  });
}
