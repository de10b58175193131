// bench_env: batched environment step vs raw mj_step on the same model, 1..N threads.
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/bench/env_bench.h"
#include "sims/core/app.h"
#include "sims/core/log.h"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark the batched env against a raw mj_step loop (prints JSON)"};
  sims::bench::EnvBenchOptions o;
  bool json = false;
  app.add_flag("--json", json, "print only the JSON result");
  app.add_option("--envs", o.num_envs, "environments")->check(CLI::PositiveNumber);
  app.add_option("--steps", o.control_steps, "control steps per measurement")
      ->check(CLI::PositiveNumber);
  app.add_option("--repeats", o.repeats, "best-of repeats")->check(CLI::PositiveNumber);
  app.add_option("--max-threads", o.max_threads, "largest thread count (0 = hardware)");
  sims::AppFlags flags;
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  if (json) flags.default_log_level = "warn";
  return sims::RunApp(flags, [&] {
    const auto result = sims::bench::RunEnvBenchmark(o);
    if (!json) spdlog::info("env/raw ratio at 1 thread: {:.3f}", result["ratio"].get<double>());
    std::cout << result.dump(json ? -1 : 2) << std::endl;
    return 0;
  });
}
