// demo_env: the humanoid on flat ground in the batched environment, holding its standing
// pose under random perturbations with a fixed seed; writes DIR/result.json + DIR/config.json.
#include <CLI/CLI.hpp>

#include "sims/bench/demo.h"
#include "sims/core/app.h"
#include "sims/core/config.h"
#include "sims/core/paths.h"

int main(int argc, char** argv) {
  CLI::App app{"Run the batched humanoid environment on flat ground and write a result file"};
  std::string config_path = sims::ConfigPath("env.json").string(), out = "out/demo_env";
  int steps = 300;
  double noise = 0.1;
  uint64_t seed = 0;
  sims::AppFlags flags;
  app.add_option("--config", config_path, "environment config (JSON)");
  app.add_option("--out", out, "output directory");
  app.add_option("--steps", steps, "control steps (30 Hz)")->check(CLI::PositiveNumber);
  app.add_option("--noise", noise, "std of the random action perturbation")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--seed", seed, "random seed");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    auto config = sims::LoadConfig<sims::sim::EnvConfig>(config_path);
    config.seed = seed;
    sims::bench::RunStandingDemo(config, steps, noise, out);
    return 0;
  });
}
