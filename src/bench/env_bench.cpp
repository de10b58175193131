#include "sims/bench/env_bench.h"

#include <algorithm>
#include <chrono>

#include <omp.h>

#include "sims/core/parallel.h"
#include "sims/sim/env.h"

namespace sims::bench {

using humanoid::BuildModel;
using humanoid::Humanoid;
using humanoid::kNumDofs;
using humanoid::MakeData;
using humanoid::MjDataPtr;
using sim::BatchedEnv;
using sim::EnvConfig;

namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a) {
  return std::chrono::duration<double>(Clock::now() - a).count();
}

// Same action stream for raw and env runs: the standing pose plus noise.
std::vector<float> MakeActions(const Humanoid& h, int n, int steps, double noise) {
  std::vector<float> hold(kNumDofs);
  const double zero[kNumDofs] = {0};
  h.TargetsToAction(zero, hold.data());
  Rng rng(12345);
  std::vector<float> a(static_cast<size_t>(steps) * n * kNumDofs);
  for (size_t k = 0; k < a.size(); ++k)
    a[k] = hold[k % kNumDofs] + static_cast<float>(noise * rng.Normal());
  return a;
}

// Raw reference: the same number of mjData instances, each stepped `substeps` times per
// control step with ctrl = PD target, no observations, no resets.
double RawStepsPerSecond(const Humanoid& h, const EnvBenchOptions& o, int threads,
                         const std::vector<float>& actions) {
  const mjModel* m = h.model();
  std::vector<MjDataPtr> datas;
  for (int i = 0; i < o.num_envs; ++i) {
    datas.push_back(MakeData(m));
    mj_forward(m, datas.back().get());
  }
  const int substeps = 4;
  double best = 0;
  for (int r = 0; r < o.repeats; ++r) {
    for (auto& d : datas) mj_resetData(m, d.get());
    const auto t0 = Clock::now();
    for (int t = 0; t < o.control_steps; ++t) {
#pragma omp parallel for schedule(static) num_threads(threads)
      for (int i = 0; i < o.num_envs; ++i) {
        mjData* d = datas[i].get();
        const float* a = actions.data() + (static_cast<size_t>(t) * o.num_envs + i) * kNumDofs;
        double targets[kNumDofs];
        h.ActionToTargets(a, targets);
        for (int j = 0; j < kNumDofs; ++j) d->ctrl[h.actuator_id(j)] = targets[j];
        for (int k = 0; k < substeps; ++k) mj_step(m, d);
      }
    }
    best =
        std::max(best, static_cast<double>(o.control_steps) * o.num_envs * substeps / Seconds(t0));
  }
  return best;
}

double EnvPhysicsStepsPerSecond(const std::shared_ptr<const Humanoid>& h, const EnvBenchOptions& o,
                                int threads, const std::vector<float>& actions) {
  EnvConfig c;
  c.num_envs = o.num_envs;
  c.threads = threads;
  c.seed = 1;
  double best = 0;
  for (int r = 0; r < o.repeats; ++r) {
    BatchedEnv env(h, c);
    const auto t0 = Clock::now();
    for (int t = 0; t < o.control_steps; ++t)
      env.Step(actions.data() + static_cast<size_t>(t) * o.num_envs * kNumDofs);
    best = std::max(best,
                    static_cast<double>(o.control_steps) * o.num_envs * c.substeps / Seconds(t0));
  }
  return best;
}

}  // namespace

double RawStepsPerSecondFrom(BatchedEnv& env, int threads, int control_steps, int repeats) {
  const mjModel* m = env.humanoid().model();
  const int n = env.num_envs(), substeps = env.config().substeps;
  std::vector<MjDataPtr> start, work;
  for (int i = 0; i < n; ++i) {
    start.push_back(MakeData(m));
    work.push_back(MakeData(m));
    mj_copyData(start.back().get(), m, env.data(i));
  }
  double best = 0;
  for (int r = 0; r < repeats; ++r) {
    for (int i = 0; i < n; ++i) mj_copyData(work[i].get(), m, start[i].get());
    const auto t0 = Clock::now();
    for (int t = 0; t < control_steps; ++t) {
#pragma omp parallel for schedule(static) num_threads(threads)
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < substeps; ++k) mj_step(m, work[i].get());
    }
    best = std::max(best, static_cast<double>(control_steps) * n * substeps / Seconds(t0));
  }
  return best;
}

nlohmann::json RunEnvBenchmark(const EnvBenchOptions& o) {
  auto h = std::make_shared<const Humanoid>(BuildModel());
  const auto actions = MakeActions(*h, o.num_envs, o.control_steps, o.action_noise);
  const int max_threads = o.max_threads > 0 ? o.max_threads : HardwareThreads();
  nlohmann::json per_threads = nlohmann::json::array();
  double raw1 = 0, env1 = 0, envn = 0, rawn = 0;
  for (int threads = 1; threads <= max_threads; threads *= 2) {
    const double raw = RawStepsPerSecond(*h, o, threads, actions);
    const double env = EnvPhysicsStepsPerSecond(h, o, threads, actions);
    per_threads.push_back({{"threads", threads},
                           {"raw_steps_per_s", raw},
                           {"env_physics_steps_per_s", env},
                           {"ratio", env / raw}});
    if (threads == 1) raw1 = raw, env1 = env;
    envn = env;
    rawn = raw;
    if (threads * 2 > max_threads && threads != max_threads) {
      threads = max_threads / 2;  // make sure max_threads itself is measured
    }
  }
  return {
      {"raw_steps_per_s", raw1}, {"env_physics_steps_per_s", env1},  {"ratio", env1 / raw1},
      {"threads", max_threads},  {"scaling", envn / env1},           {"raw_scaling", rawn / raw1},
      {"num_envs", o.num_envs},  {"control_steps", o.control_steps}, {"per_threads", per_threads}};
}

}  // namespace sims::bench
