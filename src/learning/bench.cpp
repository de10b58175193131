#include "sims/learning/bench.h"

#include <chrono>

#include <torch/torch.h>

#include "sims/core/parallel.h"
#include "sims/learning/motion_demo.h"
#include "sims/learning/sim_vec_env.h"
#include "sims/learning/text_styles.h"
#include "sims/learning/train_run.h"
#include "sims/learning/trainer.h"

namespace sims::learning {

double MeasureSgemmGflops(int n, int repeats) {
  torch::set_num_threads(ThreadCount());
  const auto a = torch::randn({n, n}), b = torch::randn({n, n});
  auto c = torch::mm(a, b);  // warm-up
  double best = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    c = torch::mm(a, b);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::max(best, 2.0 * n * n * n / s * 1e-9);
  }
  return best;
}

nlohmann::json RunLearnerBenchmark(const std::filesystem::path& config_path, int iterations) {
  auto config = LoadConfig<TrainConfig>(config_path);
  auto setup = task::CreateSkill(config.skill, config.env.num_envs, config.env.seed);
  ApplyStyleModel(config.skill, &setup);
  auto env = std::make_shared<sim::BatchedEnv>(setup.context.humanoid, config.env, setup.skill);
  std::shared_ptr<const DemoSource> demo;
  if (config.learner.amp.enabled && setup.context.motions)
    demo = std::make_shared<MotionDemoSource>(
        setup.context.motions, config.learner.amp.conditional ? setup.context.styles : nullptr);
  else
    config.learner.amp.enabled = false;
  Trainer trainer(std::make_shared<SimVecEnv>(env), demo, config.learner);
  trainer.RunIteration();  // warm-up: allocator, normaliser start-up
  double gflop = 0, update_s = 0, env_rate = 0, train_rate = 0;
  for (int i = 0; i < iterations; ++i) {
    const auto s = trainer.RunIteration();
    gflop += s.update_gflop;
    update_s += s.update_seconds;
    env_rate += s.env_samples_per_s / iterations;
    train_rate += s.train_samples_per_s / iterations;
  }
  const double sgemm = MeasureSgemmGflops();
  const double update = gflop / update_s;
  return {{"sgemm_gflops", sgemm},
          {"update_gflops", update},
          {"ratio", update / sgemm},
          {"env_samples_per_s", env_rate},
          {"train_samples_per_s", train_rate},
          {"amp", config.learner.amp.enabled},
          {"num_envs", config.env.num_envs},
          {"minibatch_size", config.learner.ppo.minibatch_size},
          {"threads", ThreadCount()},
          {"config", config_path.string()}};
}

}  // namespace sims::learning
