#include "sims/bench/train_bench.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>

#include <torch/torch.h>

#include "sims/bench/env_bench.h"
#include "sims/core/error.h"
#include "sims/core/parallel.h"
#include "sims/io/subprocess.h"
#include "sims/learning/sim_vec_env.h"
#include "sims/learning/text_styles.h"
#include "sims/learning/train_run.h"
#include "sims/learning/trainer.h"

namespace sims::bench {

using learning::ApplyStyleModel;
using learning::DemoSource;
using learning::FreeLoopbackPort;
using learning::IterationStats;
using learning::IterationTiming;
using learning::MakeTrainingDemos;
using learning::RunTraining;
using learning::SimVecEnv;
using learning::TrainConfig;
using learning::Trainer;
using learning::TrainOptions;

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
  auto setup =
      task::CreateSkill(config.skill, config.env.num_envs, config.env.seed, nullptr, &config.env);
  ApplyStyleModel(config.skill, &setup);
  auto env = std::make_shared<sim::BatchedEnv>(setup.context.humanoid, config.env, setup.skill);
  const std::shared_ptr<const DemoSource> demo = MakeTrainingDemos(config, setup);
  if (!demo) config.learner.amp.enabled = false;
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
  options.comm = o.comm;
  const int world = o.comm ? o.comm->world_size() : 1;
  int64_t bytes_before = 0, calls_before = 0;
  double collective_before = 0;
  struct Sums {
    double interval = 0, env = 0, inference = 0, disc = 0, ppo = 0, logging = 0, gflop = 0;
    double update = 0;
    int64_t samples = 0;
    int count = 0;
  } sum;
  int seen = 0;
  options.on_iteration = [&](const IterationStats& s, const IterationTiming& t) {
    if (++seen <= warmup) {
      if (o.comm) {
        bytes_before = o.comm->bytes_reduced();
        calls_before = o.comm->reduce_calls();
        collective_before = o.comm->collective_seconds();
      }
      return;
    }
    sum.interval += t.interval_seconds;
    sum.logging += t.logging_seconds;
    sum.env += s.env_seconds;
    sum.inference += s.inference_seconds;
    sum.disc += s.disc_seconds;
    sum.ppo += s.ppo_seconds;
    sum.gflop += s.update_gflop;
    sum.update += s.update_seconds;
    sum.samples += static_cast<int64_t>(config.learner.ppo.horizon) * config.env.num_envs * world;
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
  nlohmann::json result = {{"config", o.config.string()},
                           {"skill", config.skill.skill},
                           {"threads", ThreadCount()},
                           {"ranks", world},
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
                           {"samples_per_s", sum.samples / sum.interval}};
  if (o.comm) {
    const double per_it = 1.0 / measured;
    result["allreduce_bytes_per_iteration"] = (o.comm->bytes_reduced() - bytes_before) * per_it;
    result["allreduce_calls_per_iteration"] = (o.comm->reduce_calls() - calls_before) * per_it;
    const int64_t grad_bytes = o.comm->max_reduce_bytes();
    result["gradient_bytes"] = grad_bytes;
    // All-reduce times between these ranks now: medians of 41 calls at a small size, a
    // quarter of the gradients and the flattened gradients (what a training step sends).
    auto time_allreduce = [&](int64_t floats) {
      std::vector<float> buf(std::max<int64_t>(floats, 1), 1.0f);
      std::vector<double> t;
      for (int r = 0; r < 46; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        o.comm->AllReduceSum(buf.data(), static_cast<int64_t>(buf.size()));
        if (r >= 5)
          t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      }
      std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
      return t[t.size() / 2];
    };
    nlohmann::json sizes = nlohmann::json::array();
    for (int64_t bytes : {int64_t{4096}, grad_bytes / 4, grad_bytes})
      sizes.push_back({{"bytes", bytes}, {"seconds", time_allreduce(bytes / 4)}});
    result["allreduce_timings"] = sizes;
    result["collective_seconds_per_iteration"] =
        (o.comm->collective_seconds() - collective_before) * per_it;
  }
  const double per_it = 1.0 / measured;
  const double other = sum.interval - sum.env - sum.inference - sum.disc - sum.ppo - sum.logging;
  auto share = [&](double x) { return x / sum.interval; };
  result.update({{"time_share",
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
                   {"other", other * per_it}}}});
  if (!o.references) return result;

  // References measured in this run: raw mj_step on the skill's own scene, and sgemm.
  auto setup =
      task::CreateSkill(config.skill, config.env.num_envs, config.env.seed, nullptr, &config.env);
  sim::BatchedEnv ref_env(setup.context.humanoid, config.env, setup.skill);
  const double raw = RawStepsPerSecondFrom(ref_env, ThreadCount(), 30);
  const double sgemm = MeasureSgemmGflops();
  const double substeps = config.env.substeps;
  const double ceiling = raw / substeps;
  const double samples = static_cast<double>(sum.samples);
  result.update({{"env_samples_per_s", samples / sum.env},
                 {"raw_mj_step_per_s", raw},
                 {"raw_ceiling_samples_per_s", ceiling},
                 {"env_vs_raw", samples / sum.env / ceiling},
                 {"end_to_end_vs_ceiling", samples / sum.interval / ceiling},
                 {"update_gflops", sum.gflop / sum.update},
                 {"sgemm_gflops", sgemm},
                 {"update_vs_sgemm", sum.gflop / sum.update / sgemm}});
  return result;
}

namespace {

// Starts `count` workers at once (as ranks of one run, or independently), waits for all and
// returns their JSON results.
std::vector<nlohmann::json> RunWorkers(const RankBenchOptions& o, int count, bool as_ranks,
                                       const std::filesystem::path& dir) {
  const int port = as_ranks ? FreeLoopbackPort() : 0;
  std::vector<std::unique_ptr<io::Subprocess>> procs;
  std::vector<std::filesystem::path> outs, logs;
  for (int i = 0; i < count; ++i) {
    const std::string tag =
        (as_ranks ? "rank" : "solo") + std::to_string(count) + "_" + std::to_string(i);
    outs.push_back(dir / (tag + ".json"));
    logs.push_back(dir / (tag + ".log"));
    auto argv = o.worker;
    argv.insert(argv.end(), {"--worker-out", outs.back().string()});
    io::SubprocessOptions so;
    so.stdout_file = logs.back();
    so.stderr_to_stdout = true;
    // One thread per process; a launcher's variables from the caller's shell never leak in.
    so.env = {"OMP_NUM_THREADS=1", "RANK=" + std::to_string(as_ranks ? i : 0),
              "WORLD_SIZE=" + std::to_string(as_ranks ? count : 1), "MASTER_ADDR=127.0.0.1",
              "MASTER_PORT=" + std::to_string(as_ranks ? port : 29500)};
    procs.push_back(std::make_unique<io::Subprocess>(argv, so));
  }
  std::vector<nlohmann::json> results;
  for (int i = 0; i < count; ++i) {
    const int code = procs[i]->Wait();
    if (code != 0) {
      std::ifstream in(logs[i]);
      std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (text.size() > 2000) text = text.substr(text.size() - 2000);
      throw Error("bench_train worker " + std::to_string(i) + " exited with code " +
                  std::to_string(code) + ":\n" + text);
    }
    results.push_back(ReadJsonFile(outs[i]));
  }
  return results;
}

}  // namespace

nlohmann::json RunRankScalingBenchmark(const RankBenchOptions& o) {
  if (o.ranks < 2) ThrowInputError("--ranks", "ranks", "at least 2", std::to_string(o.ranks));
  if (o.worker.empty()) ThrowInputError("bench options", "worker", "a worker command", "none");
  const auto dir =
      std::filesystem::temp_directory_path() / ("sims_bench_ranks_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // Rounds alternate the three runs so that a slow phase of a shared machine hits all of
  // them alike; the figures are means over rounds.
  nlohmann::json single, ranked, rounds = nlohmann::json::array();
  std::vector<nlohmann::json> indep, ranks;
  double s1 = 0, s_indep = 0, s_ranked = 0;
  const int repeats = std::max(o.repeats, 1);
  try {
    for (int round = 0; round < repeats; ++round) {
      single = RunWorkers(o, 1, false, dir)[0];
      indep = RunWorkers(o, o.ranks, false, dir);
      ranks = RunWorkers(o, o.ranks, true, dir);
      ranked = ranks[0];
      double a = single["samples_per_s"].get<double>(), b = 0;
      for (const auto& r : indep) b += r["samples_per_s"].get<double>();
      const double c = ranked["samples_per_s"].get<double>();
      rounds.push_back({{"single_samples_per_s", a},
                        {"independent_samples_per_s", b},
                        {"ranked_samples_per_s", c},
                        {"efficiency", c / b}});
      s1 += a / repeats;
      s_indep += b / repeats;
      s_ranked += c / repeats;
    }
  } catch (...) {
    std::filesystem::remove_all(dir);
    throw;
  }
  std::filesystem::remove_all(dir);
  const double indep_speedup = s_indep / s1, ranked_speedup = s_ranked / s1;

  // Projection: each rank computes as the single process did; per iteration it adds its
  // all-reduces, modelled as Gloo's ring: T(P, B) = 2(P−1)·α + 2(P−1)/P · B/β. On 2 ranks
  // T = 2α + B/β, so a least-squares line through the measured (bytes, seconds) gives α and β.
  const double batch_rank =
      static_cast<double>(single["horizon"].get<int>()) * single["num_envs"].get<int>();
  const double t_iter = batch_rank / s1;
  const double calls = ranked["allreduce_calls_per_iteration"].get<double>();
  const double bytes_it = ranked["allreduce_bytes_per_iteration"].get<double>();
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (const auto& m : ranked["allreduce_timings"]) {
    const double x = m["bytes"].get<double>(), y = m["seconds"].get<double>();
    sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
  }
  const double slope = std::max((n * sxy - sx * sy) / std::max(n * sxx - sx * sx, 1e-30), 0.0);
  const double intercept = std::max((sy - slope * sx) / n, 0.0);
  const double alpha = intercept / 2.0;
  const double inv_beta = slope;  // seconds per byte; 0 when bandwidth did not show
  nlohmann::json table = nlohmann::json::array();
  for (int p : o.project) {
    const double steps = 2.0 * (p - 1);
    const double t_comm = calls * steps * alpha + steps / p * bytes_it * inv_beta;
    const double t = t_iter + t_comm;
    table.push_back({{"ranks", p},
                     {"samples_per_s", p * batch_rank / t},
                     {"efficiency", t_iter / t},
                     {"allreduce_seconds_per_iteration", t_comm}});
  }
  return {{"config", o.train.config.string()},
          {"ranks", o.ranks},
          {"threads_per_rank", 1},
          {"num_envs_per_rank", single["num_envs"]},
          {"iterations", single["iterations"]},
          {"single_samples_per_s", s1},
          {"independent_samples_per_s", s_indep},
          {"independent_speedup", indep_speedup},
          {"ranked_samples_per_s", s_ranked},
          {"ranked_speedup", ranked_speedup},
          {"efficiency", s_ranked / s_indep},
          {"rounds", rounds},
          {"allreduce",
           {{"calls_per_iteration", calls},
            {"bytes_per_iteration", bytes_it},
            {"gradient_bytes", ranked["gradient_bytes"]},
            {"timings", ranked["allreduce_timings"]},
            {"latency_alpha_seconds", alpha},
            {"bandwidth_bytes_per_s", inv_beta > 0 ? 1.0 / inv_beta : 0.0}}},
          {"seconds_per_iteration_single", t_iter},
          {"projection_model",
           "t(P) = t_iter + calls*2(P-1)*alpha + 2(P-1)/P*bytes/beta; 1 thread per rank, "
           "excludes the machine's own core sharing (independent_speedup)"},
          {"projection", table},
          {"workers", {{"single", single}, {"independent", indep}, {"ranked", ranks}}}};
}

}  // namespace sims::bench
