#include "sims/bench/demo.h"

#include <chrono>

#include "sims/core/log.h"
#include "sims/core/progress.h"

namespace sims::bench {

using humanoid::BuildModel;
using humanoid::Humanoid;
using humanoid::kNumDofs;
using sim::BatchedEnv;
using sim::EnvConfig;
using sim::EnvStats;

nlohmann::json RunStandingDemo(const EnvConfig& config, int steps, double noise,
                               const std::filesystem::path& out_dir) {
  auto humanoid = std::make_shared<const Humanoid>(BuildModel());
  BatchedEnv env(humanoid, config);
  const int n = env.num_envs();
  std::vector<float> hold(kNumDofs), actions(static_cast<size_t>(n) * kNumDofs);
  const double zero_targets[kNumDofs] = {0};
  humanoid->TargetsToAction(zero_targets, hold.data());
  Rng rng(config.seed + 1000003);  // action noise stream, separate from the env streams
  double height_sum = 0;
  ProgressReporter progress("demo_env", steps, "steps");
  const auto t0 = std::chrono::steady_clock::now();
  for (int t = 0; t < steps; ++t) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < kNumDofs; ++j)
        actions[static_cast<size_t>(i) * kNumDofs + j] =
            hold[j] + static_cast<float>(noise * rng.Normal());
    env.Step(actions.data());
    for (int i = 0; i < n; ++i) height_sum += env.pose(i).root_pos.z();
    progress.Update(t + 1);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  progress.Finish();
  const EnvStats& s = env.stats();
  nlohmann::json result = {
      {"num_envs", n},
      {"control_steps", steps},
      {"simulated_seconds", steps * env.control_dt()},
      {"mean_root_height_m", height_sum / (static_cast<double>(steps) * n)},
      {"episodes_ended", s.episodes},
      {"falls", s.falls},
      {"timeouts", s.timeouts},
      {"instabilities", s.instabilities},
      {"env_steps_per_s", static_cast<double>(s.steps) / seconds},
      {"seed", config.seed},
  };
  std::filesystem::create_directories(out_dir);
  WriteJsonFile(out_dir / "config.json",
                {{"env", ConfigToJson(config)}, {"steps", steps}, {"noise", noise}});
  WriteJsonFile(out_dir / "result.json", result);
  spdlog::info("wrote {}: {} falls, mean root height {:.3f} m", (out_dir / "result.json").string(),
               s.falls, result["mean_root_height_m"].get<double>());
  return result;
}

}  // namespace sims::bench
