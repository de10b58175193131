// bench_train: end-to-end training throughput (env samples learned from per wall-clock second)
// of real train_policy iterations, with its time breakdown and in-run references (prints JSON).
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/paths.h"
#include "sims/learning/bench.h"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark training throughput as a user's train_policy run sees it"};
  sims::learning::TrainBenchOptions o;
  std::string config = sims::ConfigPath("skills/sit.json").string();
  bool json = false;
  sims::AppFlags flags;
  app.add_option("--config", config, "training config (default: sit)");
  app.add_option("--iterations", o.iterations, "measured iterations (default: checkpoint_every)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--warmup", o.warmup, "unmeasured iterations first")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--num-envs", o.num_envs, "override env.num_envs")->check(CLI::NonNegativeNumber);
  sims::AddAppFlags(&app, &flags);
  app.add_flag("--json", json, "print only the JSON result");
  CLI11_PARSE(app, argc, argv);
  if (json) flags.default_log_level = "warn";
  return sims::RunApp(flags, [&] {
    o.config = config;
    const auto r = sims::learning::RunTrainBenchmark(o);
    std::cout << r.dump(json ? -1 : 2) << std::endl;
    return 0;
  });
}
