// bench_learner: sgemm GFLOP/s vs the PPO + AMP update's achieved GFLOP/s (prints JSON).
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/bench/train_bench.h"
#include "sims/core/app.h"
#include "sims/core/paths.h"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark the learner against sgemm on this machine"};
  std::string config = sims::ConfigPath("skills/walk.json").string();
  int iterations = 3;
  bool json = false;
  sims::AppFlags flags;
  app.add_option("--config", config, "training config");
  app.add_option("--iterations", iterations, "measured iterations")->check(CLI::PositiveNumber);
  sims::AddAppFlags(&app, &flags);
  app.add_flag("--json", json, "print only the JSON result");
  CLI11_PARSE(app, argc, argv);
  if (json) flags.default_log_level = "warn";
  return sims::RunApp(flags, [&] {
    const auto r = sims::bench::RunLearnerBenchmark(config, iterations);
    std::cout << r.dump(json ? -1 : 2) << std::endl;
    return 0;
  });
}
