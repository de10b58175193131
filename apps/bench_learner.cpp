// bench_learner: sgemm GFLOP/s vs the PPO + AMP update's achieved GFLOP/s (prints JSON).
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/log.h"
#include "sims/core/parallel.h"
#include "sims/core/paths.h"
#include "sims/learning/bench.h"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark the learner against sgemm on this machine"};
  std::string config = sims::ConfigPath("skills/walk.json").string();
  int iterations = 3, threads = 0;
  bool json = false;
  app.add_option("--config", config, "training config");
  app.add_option("--iterations", iterations, "measured iterations")->check(CLI::PositiveNumber);
  app.add_option("--threads", threads, "threads (0 = all hardware threads)");
  app.add_flag("--json", json, "print only the JSON result");
  CLI11_PARSE(app, argc, argv);
  try {
    sims::InitLogging(json ? "warn" : "");
    sims::SetThreadCount(threads);
    const auto r = sims::learning::RunLearnerBenchmark(config, iterations);
    std::cout << r.dump(json ? -1 : 2) << std::endl;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
