#include "sims/learning/bench.h"

#include <unistd.h>
#include <chrono>

#include <torch/torch.h>

#include "sims/core/error.h"
#include "sims/core/parallel.h"
#include "sims/learning/motion_demo.h"
#include "sims/learning/sim_vec_env.h"
#include "sims/learning/text_styles.h"
#include "sims/learning/train_run.h"
#include "sims/learning/trainer.h"
#include "sims/sim/bench.h"

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
        setup.context.motions, config.learner.amp.conditional ? setup.context.styles : nullptr,
        config.env.amp_history);
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

nlohmann::json RunTrainBenchmark(const TrainBenchOptions& o) {
  auto config = LoadConfig<TrainConfig>(o.config);
  if (o.num_envs > 0) config.env.num_envs = o.num_envs;
  const int measured = o.iterations > 0 ? o.iterations : config.checkpoint_every;
  const int warmup = std::max(o.warmup, 0);
  const auto dir =
      std::filesystem::temp_directory_path() / ("sims_bench_train_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  TrainOptions options;
  options.out_dir = dir;
  options.iterations = warmup + measured;
  struct Sums {
    double interval = 0, env = 0, inference = 0, disc = 0, ppo = 0, logging = 0, gflop = 0;
    double update = 0;
    int64_t samples = 0;
    int count = 0;
  } sum;
  int seen = 0;
  options.on_iteration = [&](const IterationStats& s, const IterationTiming& t) {
    if (++seen <= warmup) return;
    sum.interval += t.interval_seconds;
    sum.logging += t.logging_seconds;
    sum.env += s.env_seconds;
    sum.inference += s.inference_seconds;
    sum.disc += s.disc_seconds;
    sum.ppo += s.ppo_seconds;
    sum.gflop += s.update_gflop;
    sum.update += s.update_seconds;
    sum.samples += static_cast<int64_t>(config.learner.ppo.horizon) * config.env.num_envs;
    ++sum.count;
  };
  try {
    RunTraining(config, options);
  } catch (...) {
    std::filesystem::remove_all(dir);
    throw;
  }
  std::filesystem::remove_all(dir);
  SIMS_CHECK(sum.count == measured);

  // References measured in this run: raw mj_step on the skill's own scene, and sgemm.
  auto setup = task::CreateSkill(config.skill, config.env.num_envs, config.env.seed);
  sim::BatchedEnv ref_env(setup.context.humanoid, config.env, setup.skill);
  const double raw = sim::RawStepsPerSecondFrom(ref_env, ThreadCount(), 30);
  const double sgemm = MeasureSgemmGflops();
  const double substeps = config.env.substeps;
  const double ceiling = raw / substeps;
  const double samples = static_cast<double>(sum.samples);
  const double per_it = 1.0 / measured;
  const double other = sum.interval - sum.env - sum.inference - sum.disc - sum.ppo - sum.logging;
  auto share = [&](double x) { return x / sum.interval; };
  return {{"config", o.config.string()},
          {"skill", config.skill.skill},
          {"threads", ThreadCount()},
          {"num_envs", config.env.num_envs},
          {"horizon", config.learner.ppo.horizon},
          {"mini_epochs", config.learner.ppo.mini_epochs},
          {"minibatch_size", config.learner.ppo.minibatch_size},
          {"amp", config.learner.amp.enabled},
          {"amp_history", config.env.amp_history},
          {"amp_batch_size", config.learner.amp.batch_size},
          {"iterations", measured},
          {"samples", sum.samples},
          {"wall_seconds", sum.interval},
          {"samples_per_s", samples / sum.interval},
          {"time_share",
           {{"env", share(sum.env)},
            {"inference", share(sum.inference)},
            {"discriminator", share(sum.disc)},
            {"ppo_update", share(sum.ppo)},
            {"logging", share(sum.logging)},
            {"other", share(other)}}},
          {"seconds_per_iteration",
           {{"total", sum.interval * per_it},
            {"env", sum.env * per_it},
            {"inference", sum.inference * per_it},
            {"discriminator", sum.disc * per_it},
            {"ppo_update", sum.ppo * per_it},
            {"logging", sum.logging * per_it},
            {"other", other * per_it}}},
          {"env_samples_per_s", samples / sum.env},
          {"raw_mj_step_per_s", raw},
          {"raw_ceiling_samples_per_s", ceiling},
          {"env_vs_raw", samples / sum.env / ceiling},
          {"end_to_end_vs_ceiling", samples / sum.interval / ceiling},
          {"update_gflops", sum.gflop / sum.update},
          {"sgemm_gflops", sgemm},
          {"update_vs_sgemm", sum.gflop / sum.update / sgemm}};
}

}  // namespace sims::learning
