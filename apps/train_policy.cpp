// train_policy: PPO + AMP training of one skill, resumable (--resume continues from the last
// checkpoint in --out with the run's saved config). Under a launcher (mpirun, srun, or RANK /
// WORLD_SIZE / MASTER_ADDR / MASTER_PORT) each process is one data-parallel rank.
#include <cstdlib>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/error.h"
#include "sims/core/parallel.h"
#include "sims/core/paths.h"
#include "sims/learning/distributed.h"
#include "sims/learning/train_run.h"

int main(int argc, char** argv) {
  CLI::App app{"Train a skill policy with PPO + (conditional) AMP"};
  std::string skill, config_path;
  sims::learning::TrainOptions opt;
  std::string out = "runs/train";
  int iterations = 0;
  uint64_t seed = 0;
  sims::AppFlags flags;
  app.add_option("--skill", skill, "skill name (walk, sit, lie, reach, getup, unified)");
  app.add_option("--config", config_path, "configs/skills/<skill>.json (default from --skill)");
  app.add_option("--out", out, "output directory (config, log.csv, report.html, checkpoints)");
  auto* it_opt =
      app.add_option("--iterations", iterations, "total iterations")->check(CLI::PositiveNumber);
  auto* seed_opt = app.add_option("--seed", seed, "seed for environments and learner");
  app.add_flag("--resume", opt.resume, "continue from --out/checkpoint.pt");
  std::string init_from, init_policy;
  app.add_option("--init-policy", init_policy,
                 "initialise actor/critic from a policy.pt (e.g. walk)");
  app.add_option("--init-from", init_from, "warm start from another run's checkpoint.pt");
  double dist_timeout = 120;
  app.add_option("--dist-timeout", dist_timeout,
                 "data-parallel: seconds a rank waits for its peers before the run ends with an "
                 "error")
      ->check(CLI::PositiveNumber);
  app.add_option("--check-every", opt.check_every,
                 "data-parallel: compare a parameter checksum across ranks every K iterations")
      ->check(CLI::PositiveNumber);
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    // A resumed run reads its own saved config from --out.
    if (config_path.empty() && skill.empty() && !opt.resume)
      throw sims::Error("--skill or --config: expected at least one of them");
    if (config_path.empty() && !skill.empty())
      config_path = sims::ConfigPath("skills/" + skill + ".json").string();
    opt.out_dir = out;
    opt.init_from = init_from;
    opt.init_policy = init_policy;
    if (!skill.empty()) opt.skill = skill;
    if (*it_opt) opt.iterations = iterations;
    if (*seed_opt) opt.seed = seed;
    if (auto dist = sims::learning::DistributedConfigFromEnvironment(std::getenv)) {
      // Ranks share the machine: one thread each unless --threads or OMP_NUM_THREADS says more.
      if (flags.threads == 0) {
        const char* omp = std::getenv("OMP_NUM_THREADS");
        sims::SetThreadCount(omp && std::atoi(omp) > 0 ? std::atoi(omp) : 1);
      }
      dist->timeout_seconds = dist_timeout;
      dist->check_every = opt.check_every;
      opt.comm = sims::learning::ConnectProcessGroup(*dist);
    }
    auto config = opt.resume ? sims::learning::TrainConfig{}
                             : sims::LoadConfig<sims::learning::TrainConfig>(config_path);
    sims::learning::RunTraining(config, opt);
    return 0;
  });
}
