// bench_train: end-to-end training throughput (env samples learned from per wall-clock second)
// of real train_policy iterations, with its time breakdown and in-run references (prints JSON).
// --ranks N measures data-parallel scaling with N worker processes of this same binary.
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/bench/train_bench.h"
#include "sims/core/app.h"
#include "sims/core/config.h"
#include "sims/core/parallel.h"
#include "sims/core/paths.h"

int main(int argc, char** argv) {
  CLI::App app{"Benchmark training throughput as a user's train_policy run sees it"};
  sims::bench::TrainBenchOptions o;
  std::string config = sims::ConfigPath("skills/sit.json").string();
  std::string worker_out;
  bool json = false;
  int ranks = 0, repeats = 2;
  sims::AppFlags flags;
  app.add_option("--config", config, "training config (default: sit)");
  app.add_option("--iterations", o.iterations, "measured iterations (default: checkpoint_every)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--warmup", o.warmup, "unmeasured iterations first")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--num-envs", o.num_envs, "override env.num_envs")->check(CLI::NonNegativeNumber);
  app.add_option("--ranks", ranks,
                 "data-parallel scaling: 1 process, N side by side, and an N-rank run on "
                 "127.0.0.1, one thread each")
      ->check(CLI::Range(2, 1024));
  app.add_option("--repeats", repeats, "--ranks: rounds of the three runs (means reported)")
      ->check(CLI::PositiveNumber);
  app.add_option("--worker-out", worker_out, "(internal) run one worker, write its JSON here")
      ->group("");
  sims::AddAppFlags(&app, &flags);
  app.add_flag("--json", json, "print only the JSON result");
  CLI11_PARSE(app, argc, argv);
  if (json || !worker_out.empty()) flags.default_log_level = "warn";
  return sims::RunApp(flags, [&] {
    o.config = config;
    if (!worker_out.empty()) {
      if (const char* omp = std::getenv("OMP_NUM_THREADS"); omp && std::atoi(omp) > 0)
        sims::SetThreadCount(std::atoi(omp));
      if (auto dist = sims::learning::DistributedConfigFromEnvironment(std::getenv))
        o.comm = sims::learning::ConnectProcessGroup(*dist);
      o.references = false;
      sims::WriteJsonFile(worker_out, sims::bench::RunTrainBenchmark(o));
      return 0;
    }
    if (ranks > 0) {
      sims::bench::RankBenchOptions r;
      r.train = o;
      r.ranks = ranks;
      r.repeats = repeats;
      r.worker = {std::filesystem::read_symlink("/proc/self/exe").string(),
                  "--config",
                  config,
                  "--warmup",
                  std::to_string(o.warmup),
                  "--iterations",
                  std::to_string(o.iterations > 0 ? o.iterations : 10)};
      if (o.num_envs > 0)
        r.worker.insert(r.worker.end(), {"--num-envs", std::to_string(o.num_envs)});
      const auto result = sims::bench::RunRankScalingBenchmark(r);
      std::cout << result.dump(json ? -1 : 2) << std::endl;
      return 0;
    }
    const auto r = sims::bench::RunTrainBenchmark(o);
    std::cout << r.dump(json ? -1 : 2) << std::endl;
    return 0;
  });
}
