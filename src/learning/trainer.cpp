#include "sims/learning/trainer.h"

#include <malloc.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <mutex>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>
#include <tuple>

#include <torch/torch.h>

#include "learning/amp.h"
#include "learning/networks.h"
#include "learning/ppo.h"
#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/parallel.h"
#include "sims/learning/distributed.h"

namespace sims::learning {

namespace {

// A network config without its exploration noise: the fixed action σ is a training setting, so
// a resumed or warm-started run may change it; the layer sizes must match the weights.
nlohmann::json NetworkShape(nlohmann::json network) {
  network.erase("action_log_std");
  return network;
}

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Debian's libtorch starts with one intra-op thread; follow the project's Parallelism setting.
// glibc serves the update's MiB-sized temporaries with fresh mmap()s and trims the heap after
// each free, so every minibatch paid page faults on all its activations (perf: ~14 % of a sit
// training run in the kernel); keeping freed memory in the process removes that.
void BindTorchThreads() {
  static const bool once = [] {
    mallopt(M_MMAP_THRESHOLD, 256 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    AddThreadCountListener([](int n) { torch::set_num_threads(n); });
    return true;
  }();
  (void)once;
}

torch::Tensor FromBuffer(const float* data, std::vector<int64_t> shape) {
  return torch::from_blob(const_cast<float*>(data), shape, torch::kFloat32).clone();
}

torch::Tensor Permutation(Rng& rng, int64_t n) {
  std::vector<int64_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  for (int64_t i = n - 1; i > 0; --i) std::swap(idx[i], idx[rng.UniformInt(i + 1)]);
  return torch::tensor(idx, torch::kInt64);
}

// Multiply-adds of the linear layers of a module, for the FLOP estimate of the update.
double LinearMacs(torch::nn::Module& m) {
  double macs = 0;
  for (const auto& p : m.named_parameters())
    if (p.key().size() >= 6 && p.key().compare(p.key().size() - 6, 6, "weight") == 0)
      macs += static_cast<double>(p.value().numel());
  return macs;
}

}  // namespace

struct Trainer::Impl {
  std::shared_ptr<VecEnv> env;
  std::shared_ptr<const DemoSource> demo;
  LearnerConfig cfg;
  std::vector<sim::ObsSegment> segments;
  int64_t n = 0, obs_dim = 0, act_dim = 0, amp_dim = 0, style_dim = 0;
  bool use_amp = false;

  ActorCritic ac{nullptr};
  Discriminator disc{nullptr};
  RunningMeanStd obs_norm{nullptr}, value_norm{nullptr}, amp_norm{nullptr};
  std::unique_ptr<torch::optim::Adam> optim;
  std::unique_ptr<ReplayBuffer> replay;
  torch::Tensor demo_pool, demo_pool_styles, style_table;
  // `rng` orders minibatches and is the same on every rank; exploration noise comes from one
  // stream per environment (by global env id) and discriminator sampling from a per-rank one,
  // so a run's update does not depend on how its environments are split over ranks.
  Rng rng, amp_rng;
  std::vector<Rng> noise_rng;
  std::shared_ptr<Communicator> comm;
  int rank = 0, world = 1, check_every = 10;
  int64_t first_env = 0;
  int64_t iteration = 0, samples = 0;
  double learning_rate = 0;  // the optimiser's current rate (the adaptive schedule moves it)
  std::vector<double> ep_return, ep_len;
  std::vector<uint8_t> ep_success;

  std::vector<torch::Tensor> AllParameters() const {
    auto p = ac->parameters();
    if (use_amp) {
      auto d = disc->parameters();
      p.insert(p.end(), d.begin(), d.end());
    }
    return p;
  }

  /// What a rollout gathered besides the buffers.
  struct Rollout {
    double return_sum = 0, length_sum = 0, success_sum = 0, fall_sum = 0, force_sum = 0;
    // Episodes and successes by start kind (reference-state vs default starts).
    double reference_episodes = 0, reference_success = 0, default_success = 0;
    int64_t episodes = 0;
    double seconds = 0, env_seconds = 0;
  };
  /// One iteration's training batch, flattened to [T·N, ·].
  struct Batch {
    torch::Tensor obs, obs_norm, actions, log_probs, advantages, returns;
    torch::Tensor reward, style_reward;   // [T, N]
    torch::Tensor amp, amp_norm, styles;  // AMP only
    // Each sample's successor in its episode (t + 1, same env) and whether it has one.
    torch::Tensor next_index, next_valid;
  };
  /// Loss sums over minibatches (each weighted by this rank's share).
  struct UpdateTotals {
    double actor = 0, critic = 0, bounds = 0, smooth = 0, disc = 0, grad_penalty = 0,
           demo_accuracy = 0, agent_accuracy = 0, clip_fraction = 0, kl = 0;
    double minibatch_kl = 0;  // this rank's share of the last minibatch's KL
    int64_t steps = 0, disc_steps = 0, disc_samples = 0, minibatch = 0;
  };
  /// Seconds of the update phases (for the time split).
  struct Timings {
    double disc = 0, ppo = 0;
  };
  /// Steps the environments for one horizon with the current policy, filling the buffers.
  Rollout CollectRollout();
  /// Style rewards, GAE advantages and normalised targets of the collected buffers.
  Batch PrepareBatch(Timings* timing);
  /// Mini-epochs of PPO (+ discriminator) steps over the batch.
  UpdateTotals Update(const Batch& b, Timings* timing);
  /// The adaptive schedule's step after a minibatch whose KL (this rank's share) is given.
  void AdaptLearningRate(double minibatch_kl);
  /// Accumulates the PPO loss gradients of samples `idx`.
  void PpoLoss(const Batch& b, const torch::Tensor& idx, double share, UpdateTotals* u);
  /// Accumulates the discriminator loss gradients for policy windows `agent_idx`.
  void DiscriminatorLoss(const Batch& b, const torch::Tensor& agent_idx, double share,
                         UpdateTotals* u);

  /// Networks, normalisers, optimiser, minibatch stream and counters: what all ranks share.
  /// Without `with_optimizer` the optimiser's moments are left out (compact checkpoints).
  void WriteLearnerState(torch::serialize::OutputArchive& archive, bool with_optimizer) const;
  /// Reads WriteLearnerState() output; `source` names it in errors.
  void ReadLearnerState(torch::serialize::InputArchive& archive, const std::string& source);

  // The demo pool is refreshed in blocks of amp.demo_refresh windows, block j (after iteration
  // j) cycling through the pool and drawn from its own stream Rng(seed, j): the pool at any
  // iteration is then a function of the iteration alone, and a resumed run rebuilds it from
  // the last pool's worth of blocks instead of storing it.
  void RefreshDemoBlock(int64_t j) {
    const int64_t k = cfg.amp.demo_refresh, size = demo_pool.size(0);
    Rng block_rng = Rng::ForEnv(cfg.seed ^ 0x6A09E667F3BCC909ull, static_cast<int>(j));
    std::vector<float> windows(static_cast<size_t>(k * amp_dim));
    std::vector<int> styles(static_cast<size_t>(k));
    demo->Sample(static_cast<int>(k), block_rng, windows.data(), styles.data());
    float* pool = demo_pool.data_ptr<float>();
    int64_t* pool_styles = demo_pool_styles.data_ptr<int64_t>();
    for (int64_t i = 0; i < k; ++i) {
      const int64_t row = ((j - 1) * k + i) % size;
      std::memcpy(pool + row * amp_dim, windows.data() + i * amp_dim, sizeof(float) * amp_dim);
      pool_styles[row] = styles[i];
    }
  }
  void RebuildDemoPool() {
    if (!use_amp || cfg.amp.demo_refresh <= 0) return;
    const int64_t blocks = (demo_pool.size(0) + cfg.amp.demo_refresh - 1) / cfg.amp.demo_refresh;
    for (int64_t j = std::max<int64_t>(1, iteration - blocks + 1); j <= iteration; ++j)
      RefreshDemoBlock(j);
  }

  // Sum over ranks, in place (contiguous float32 or float64 tensors).
  void AllReduce(torch::Tensor& t) {
    if (!comm) return;
    if (t.scalar_type() == torch::kFloat64)
      comm->AllReduceSum(t.data_ptr<double>(), t.numel());
    else
      comm->AllReduceSum(t.data_ptr<float>(), t.numel());
  }

  // Folds a batch into a normaliser; with ranks, the batch is the union of all ranks' batches
  // (moments all-reduced in float64), so every rank keeps identical statistics.
  void UpdateNorm(RunningMeanStd& norm, const torch::Tensor& x) {
    if (!comm) return norm->Update(x);
    torch::NoGradGuard guard;
    const auto local = ColumnMoments(x.reshape({-1, norm->size()}));
    const int64_t d = norm->size();
    auto moments =
        torch::cat({torch::full({1}, local.count, torch::kFloat64), local.sum, local.sum_sq})
            .contiguous();
    AllReduce(moments);
    norm->MergeMoments({moments[0].item<double>(), moments.slice(0, 1, 1 + d),
                        moments.slice(0, 1 + d, 1 + 2 * d)});
  }

  // Gradients are all-reduced as two flat buckets per minibatch: the actor-critic's starts as
  // soon as its backward pass ends and runs while the discriminator computes; each rank's
  // loss is already weighted by its share of the global minibatch, so the sums are the
  // gradients of the global loss.
  torch::Tensor ac_grads, disc_grads;
  static torch::Tensor FlattenGrads(const std::vector<torch::Tensor>& params) {
    std::vector<torch::Tensor> flat;
    flat.reserve(params.size());
    for (const auto& p : params)
      flat.push_back(p.grad().defined() ? p.grad().reshape({-1}) : torch::zeros({p.numel()}));
    return torch::cat(flat);
  }
  static void ScatterGrads(const std::vector<torch::Tensor>& params, const torch::Tensor& all) {
    int64_t off = 0;
    for (auto p : params) {
      const auto g = all.slice(0, off, off + p.numel()).view(p.sizes());
      if (p.grad().defined())
        p.mutable_grad().copy_(g);
      else
        p.mutable_grad() = g.clone();
      off += p.numel();
    }
  }
  void StartReduce(const std::vector<torch::Tensor>& params, torch::Tensor* bucket) {
    if (!comm) return;
    torch::NoGradGuard guard;
    *bucket = FlattenGrads(params);
    comm->StartAllReduceSum(bucket->data_ptr<float>(), bucket->numel());
  }
  void FinishReduce(const std::vector<torch::Tensor>& ac_params,
                    const std::vector<torch::Tensor>& disc_params) {
    if (!comm) return;
    torch::NoGradGuard guard;
    comm->WaitAll();
    ScatterGrads(ac_params, ac_grads);
    if (!disc_params.empty()) ScatterGrads(disc_params, disc_grads);
  }

  // Mean and unbiased standard deviation of a tensor (over all ranks), summed in a fixed
  // order so that they do not depend on the thread count.
  std::pair<double, double> GlobalMeanStd(const torch::Tensor& x) {
    const auto local = ColumnMoments(x.reshape({-1}));
    double m[] = {local.count, local.sum.item<double>(), local.sum_sq.item<double>()};
    if (comm) comm->AllReduceSum(m, 3);
    const double n = m[0], sum = m[1], sq = m[2];
    const double mean = sum / std::max(n, 1.0);
    const double var = n > 1 ? std::max(sq - n * mean * mean, 0.0) / (n - 1) : 0.0;
    return {mean, std::sqrt(var)};
  }

  // Ranks that disagree on parameters would silently train different models: compare a
  // position-weighted checksum with rank 0's and stop every rank together on a mismatch.
  void CheckParametersAgree() {
    torch::NoGradGuard guard;
    double sum = 0;
    int64_t i = 0;
    for (const auto& p : AllParameters()) {
      const auto c = p.detach().to(torch::kFloat64).reshape({-1});
      const auto w = torch::arange(i, i + c.numel(), torch::kFloat64).remainder(7.0) + 1.0;
      sum += (c * w).sum().item<double>();
      i += c.numel();
    }
    double root = sum;
    comm->Broadcast(&root, 1, 0);
    double mismatch = root == sum ? 0.0 : 1.0;
    comm->AllReduceSum(&mismatch, 1);
    if (mismatch > 0)
      throw Error("distributed training: parameters differ between ranks at iteration " +
                  std::to_string(iteration) + " (rank " + std::to_string(rank) + " checksum " +
                  std::to_string(sum) + ", rank 0 " + std::to_string(root) +
                  "); ranks must run the same binary, config and checkpoint");
  }

  torch::Tensor StyleOf(const torch::Tensor& ids) const {
    if (style_dim == 0) return torch::Tensor();
    return style_table.index_select(0, ids.clamp_min(0));
  }

  // Values in return units (de-normalised when the critic is normalised).
  torch::Tensor ValuesOf(const torch::Tensor& normalised, const torch::Tensor& obs) {
    const auto v = ac->Value(normalised, obs);
    return cfg.ppo.normalize_value ? value_norm->Denormalize(v.unsqueeze(-1)).squeeze(-1) : v;
  }

  // Rollout buffers, allocated once: the batch shape never changes within a run.
  torch::Tensor obs_buf, last_obs, act_buf, logp_buf, val_buf, rew_buf, done_buf, boot_buf, amp_buf,
      style_buf;
  void AllocateRollout(int64_t T) {
    obs_buf = torch::empty({T, n, obs_dim});
    last_obs = torch::empty({n, obs_dim});
    act_buf = torch::empty({T, n, act_dim});
    logp_buf = torch::empty({T, n});
    val_buf = torch::empty({T + 1, n});
    rew_buf = torch::empty({T, n});
    done_buf = torch::empty({T, n});
    boot_buf = torch::zeros({T, n});
    if (use_amp) {
      amp_buf = torch::empty({T, n, amp_dim});
      style_buf = torch::zeros({T, n}, torch::kInt64);
    }
  }
};

Trainer::Trainer(std::shared_ptr<VecEnv> env, std::shared_ptr<const DemoSource> demo,
                 const LearnerConfig& config, std::shared_ptr<Communicator> comm, int check_every)
    : impl_(std::make_unique<Impl>()) {
  BindTorchThreads();
  auto& m = *impl_;
  ValidateConfig(config, "learner config");
  m.env = std::move(env);
  m.demo = std::move(demo);
  m.cfg = config;
  m.segments = m.env->obs_segments();
  m.n = m.env->num_envs();
  m.obs_dim = m.env->obs_dim();
  m.act_dim = m.env->action_dim();
  m.amp_dim = m.env->amp_obs_dim();
  SIMS_CHECK_MSG(ObsWidth(m.segments) == m.obs_dim, "observation segments must cover obs_dim");
  m.use_amp = config.amp.enabled;
  if (m.use_amp) {
    if (!m.demo)
      ThrowInputError("learner config", "amp.enabled", "demonstration data (a motion library)",
                      "none");
    if (m.amp_dim == 0 || m.demo->amp_obs_dim() != m.amp_dim)
      ThrowInputError("learner config", "amp", "environment and demo AMP widths to match",
                      std::to_string(m.amp_dim) + " vs " + std::to_string(m.demo->amp_obs_dim()));
    if (config.amp.conditional) {
      const auto& z = m.demo->style_embeddings();
      if (z.empty())
        ThrowInputError("learner config", "amp.conditional", "style embeddings in the demo data",
                        "none");
      m.style_dim = z[0].size();
      m.style_table = torch::empty({static_cast<int64_t>(z.size()), m.style_dim});
      for (size_t i = 0; i < z.size(); ++i)
        for (int64_t k = 0; k < m.style_dim; ++k) m.style_table[i][k] = z[i][k];
    }
  }
  if (comm) {
    m.comm = std::move(comm);
    m.rank = m.comm->rank();
    m.world = m.comm->world_size();
    m.check_every = std::max(check_every, 1);
    m.first_env = m.rank * m.n;
    // Equal sums and sums of squares over ranks hold only when every rank has the same value.
    double shape[] = {static_cast<double>(m.n),
                      static_cast<double>(m.obs_dim),
                      static_cast<double>(m.act_dim),
                      static_cast<double>(m.amp_dim),
                      0,
                      0,
                      0,
                      0};
    for (int k = 0; k < 4; ++k) shape[4 + k] = shape[k] * shape[k];
    double reduced[8];
    std::copy(shape, shape + 8, reduced);
    m.comm->AllReduceSum(reduced, 8);
    for (int k = 0; k < 4; ++k)
      if (reduced[k] != m.world * shape[k] || reduced[4 + k] != m.world * shape[4 + k])
        throw Error(
            "distributed training, rank " + std::to_string(m.rank) +
            ": ranks disagree on num_envs / observation / action / AMP widths (this rank: " +
            std::to_string(m.n) + " envs, obs " + std::to_string(m.obs_dim) +
            "); every rank needs the same config");
  }
  // Network initialisation draws from torch's one global generator: trainers built at the
  // same time on several threads (ranks in one process, tests) would interleave its draws.
  static std::mutex init_mutex;
  std::unique_lock<std::mutex> init_lock(init_mutex);
  torch::manual_seed(config.seed);
  m.rng = Rng(config.seed);
  m.amp_rng = Rng::ForEnv(config.seed ^ 0xA3B195354A39B70Dull, m.rank);
  for (int64_t i = 0; i < m.n; ++i)
    m.noise_rng.push_back(
        Rng::ForEnv(config.seed ^ 0x2545F4914F6CDD1Dull, static_cast<int>(m.first_env + i)));
  m.ac = ActorCritic(m.segments, m.act_dim, config.network);
  if (const auto mean = m.env->initial_action_mean(); !mean.empty())
    m.ac->SetInitialActionMean(mean);
  m.obs_norm = RunningMeanStd(m.obs_dim, config.ppo.obs_clip);
  m.value_norm = RunningMeanStd(1, 1e9);
  std::vector<torch::Tensor> params = m.ac->parameters();
  if (!m.use_amp) init_lock.unlock();
  if (m.use_amp) {
    m.disc = Discriminator(m.amp_dim, m.style_dim, config.network);
    init_lock.unlock();
    m.amp_norm = RunningMeanStd(m.amp_dim, config.ppo.obs_clip);
    auto d = m.disc->parameters();
    params.insert(params.end(), d.begin(), d.end());
    m.replay = std::make_unique<ReplayBuffer>(config.amp.replay_size, m.amp_dim);
    // A fixed demo pool from its own seeded stream: regenerated identically on resume.
    Rng demo_rng(config.seed ^ 0x9E3779B97F4A7C15ull);
    m.demo_pool = torch::empty({config.amp.demo_pool_size, m.amp_dim});
    std::vector<int> styles(config.amp.demo_pool_size);
    m.demo->Sample(config.amp.demo_pool_size, demo_rng, m.demo_pool.data_ptr<float>(),
                   styles.data());
    m.demo_pool_styles =
        torch::tensor(std::vector<int64_t>(styles.begin(), styles.end()), torch::kInt64);
    m.amp_norm->Update(m.demo_pool);
  }
  m.learning_rate = config.ppo.learning_rate;
  m.optim = std::make_unique<torch::optim::Adam>(
      params, torch::optim::AdamOptions(config.ppo.learning_rate).eps(1e-8));
  m.AllocateRollout(config.ppo.horizon);
  Synchronize();
  m.env->Reset();
  m.UpdateNorm(m.obs_norm, FromBuffer(m.env->observations(), {m.n, m.obs_dim}));
  m.ep_return.assign(m.n, 0.0);
  m.ep_len.assign(m.n, 0.0);
  m.ep_success.assign(m.n, 0);
}

Trainer::~Trainer() = default;

int64_t Trainer::iteration() const { return impl_->iteration; }
double Trainer::learning_rate() const { return impl_->learning_rate; }
const LearnerConfig& Trainer::config() const { return impl_->cfg; }

// ---- one iteration: rollout → batch (style rewards, advantages) → minibatch updates -----------

Trainer::Impl::Rollout Trainer::Impl::CollectRollout() {
  const int64_t T = cfg.ppo.horizon, N = n, D = obs_dim, A = act_dim, W = amp_dim;
  Rollout out;
  float* obs_p = obs_buf.data_ptr<float>();
  float* act_p = act_buf.data_ptr<float>();
  float* logp_p = logp_buf.data_ptr<float>();
  float* val_p = val_buf.data_ptr<float>();
  float* rew_p = rew_buf.data_ptr<float>();
  float* done_p = done_buf.data_ptr<float>();
  float* boot_p = boot_buf.data_ptr<float>();
  std::fill(boot_p, boot_p + T * N, 0.0f);  // V(terminal) for time-outs, 0 for terminations
  const float sigma = static_cast<float>(std::exp(ac->log_std()));
  // Buffers are written through raw pointers and the networks run in inference mode: per step
  // the learner adds a handful of tensor ops to the environment step, no autograd records.
  const auto t_collect = Clock::now();
  torch::InferenceMode guard;
  std::memcpy(obs_p, env->observations(), sizeof(float) * N * D);
  for (int64_t t = 0; t < T; ++t) {
    float* o_t = obs_p + t * N * D;
    const auto obs = torch::from_blob(o_t, {N, D});
    const auto norm = obs_norm->Normalize(obs);
    const auto mu = ac->Mean(norm, obs).contiguous();
    const auto v = ValuesOf(norm, obs).contiguous();
    std::memcpy(val_p + t * N, v.data_ptr<float>(), sizeof(float) * N);
    const float* mu_p = mu.data_ptr<float>();
    float* a_t = act_p + t * N * A;
    for (int64_t i = 0; i < N; ++i)
      for (int64_t j = i * A; j < (i + 1) * A; ++j)
        a_t[j] = mu_p[j] + sigma * static_cast<float>(noise_rng[i].Normal());
    const auto logp = GaussianLogProb(torch::from_blob(a_t, {N, A}), mu, ac->log_std());
    std::memcpy(logp_p + t * N, logp.contiguous().data_ptr<float>(), sizeof(float) * N);
    if (use_amp && style_dim > 0 && env->style_ids()) {
      const int* ids = env->style_ids();
      int64_t* s_t = style_buf.data_ptr<int64_t>() + t * N;
      for (int64_t i = 0; i < N; ++i) s_t[i] = ids[i];
    }
    const auto t_env = Clock::now();
    env->Step(a_t);
    out.env_seconds += Since(t_env);
    const float* r = env->rewards();
    const uint8_t* done = env->dones();
    const uint8_t* term = env->terminated();
    const uint8_t* succ = env->completions();
    const sim::EndReason* why = env->end_reasons();
    const uint8_t* reference = env->reference_starts();
    std::memcpy(rew_p + t * N, r, sizeof(float) * N);
    std::vector<int64_t> timeouts;
    for (int64_t i = 0; i < N; ++i) {
      done_p[t * N + i] = done[i] ? 1.0f : 0.0f;
      if (done[i] && !term[i]) timeouts.push_back(i);
    }
    if (!timeouts.empty()) {
      const auto idx = torch::tensor(timeouts, torch::kInt64);
      const auto term_obs =
          torch::from_blob(const_cast<float*>(env->terminal_observations()), {N, D})
              .index_select(0, idx);
      const auto tv = ValuesOf(obs_norm->Normalize(term_obs), term_obs).contiguous();
      for (size_t k = 0; k < timeouts.size(); ++k)
        boot_p[t * N + timeouts[k]] = tv.data_ptr<float>()[k];
    }
    if (use_amp)
      std::memcpy(amp_buf.data_ptr<float>() + t * N * W, env->amp_observations(),
                  sizeof(float) * N * W);
    // Episode bookkeeping uses the task reward; the style part is added after the rollout.
    for (int64_t i = 0; i < N; ++i) {
      ep_return[i] += r[i];
      ep_len[i] += 1;
      ep_success[i] |= succ[i];
      if (done[i]) {
        out.return_sum += ep_return[i];
        out.length_sum += ep_len[i];
        out.success_sum += ep_success[i];
        if (why) {
          out.fall_sum += why[i] == sim::EndReason::kFall || why[i] == sim::EndReason::kUnstable;
          out.force_sum += why[i] == sim::EndReason::kTaskTerminate;
        } else {
          out.fall_sum += term[i];
        }
        if (reference && reference[i]) {
          out.reference_episodes += 1;
          out.reference_success += ep_success[i];
        } else {
          out.default_success += ep_success[i];
        }
        ++out.episodes;
        ep_return[i] = ep_len[i] = 0;
        ep_success[i] = 0;
      }
    }
    float* next = t + 1 < T ? o_t + N * D : last_obs.data_ptr<float>();
    std::memcpy(next, env->observations(), sizeof(float) * N * D);
  }
  const auto v = ValuesOf(obs_norm->Normalize(last_obs), last_obs).contiguous();
  std::memcpy(val_p + T * N, v.data_ptr<float>(), sizeof(float) * N);
  out.seconds = Since(t_collect);
  return out;
}

Trainer::Impl::Batch Trainer::Impl::PrepareBatch(Timings* timing) {
  const auto& ppo = cfg.ppo;
  const auto& ampc = cfg.amp;
  const int64_t T = ppo.horizon, N = n;
  Batch b;
  auto t_phase = Clock::now();
  b.style_reward = torch::zeros({T, N});
  torch::NoGradGuard guard;
  if (use_amp) {
    b.amp = amp_buf.reshape({T * N, amp_dim});
    b.styles = style_buf.reshape({T * N});
    // amp_norm changes only after the update, so the policy windows are normalised once.
    b.amp_norm = amp_norm->Normalize(b.amp);
    const auto logits = disc->forward(b.amp_norm, StyleOf(b.styles));
    b.style_reward = StyleReward(logits, ampc).reshape({T, N});
    timing->disc += Since(t_phase);
    t_phase = Clock::now();
  }
  b.reward = use_amp ? ampc.task_weight * rew_buf + ampc.style_weight * b.style_reward : rew_buf;
  auto next_val = val_buf.slice(0, 1, T + 1).clone();
  next_val = torch::where(done_buf > 0.5, boot_buf, next_val);
  const auto values = val_buf.slice(0, 0, T);
  const auto adv = ComputeGae(b.reward, values, next_val, done_buf, ppo.gamma, ppo.lambda);
  const auto returns = adv + values;
  if (ppo.normalize_value) UpdateNorm(value_norm, returns.reshape({-1, 1}));
  b.obs = obs_buf.reshape({T * N, obs_dim});
  // obs_norm changes only after the update: normalise the whole batch once.
  b.obs_norm = obs_norm->Normalize(b.obs);
  b.actions = act_buf.reshape({T * N, act_dim});
  // Sample t·N + i follows on at (t + 1)·N + i unless the episode ended at t (the next row is
  // then a reset) or t is the horizon's last step.
  b.next_index = torch::arange(T * N, torch::kLong) + N;
  b.next_valid = torch::zeros({T, N});
  if (T > 1)
    b.next_valid.slice(0, 0, T - 1).copy_((done_buf.slice(0, 0, T - 1) < 0.5).to(torch::kFloat));
  b.next_valid = b.next_valid.reshape({T * N});
  b.next_index = torch::where(b.next_valid > 0.5, b.next_index, torch::arange(T * N, torch::kLong));
  b.log_probs = logp_buf.reshape({T * N});
  const auto ret_f = returns.reshape({T * N});
  b.advantages = adv.reshape({T * N});
  if (ppo.normalize_advantage) {
    const auto [mean, std] = GlobalMeanStd(b.advantages);
    b.advantages = (b.advantages - mean) / (std + 1e-8);
  }
  b.returns = ppo.normalize_value ? value_norm->Normalize(ret_f.unsqueeze(-1)).squeeze(-1) : ret_f;
  timing->ppo += Since(t_phase);
  return b;
}

void Trainer::Impl::PpoLoss(const Batch& b, const torch::Tensor& idx, double share,
                            UpdateTotals* u) {
  const auto& ppo = cfg.ppo;
  const auto o = b.obs.index_select(0, idx);
  const auto norm_o = b.obs_norm.index_select(0, idx);
  const auto mu = ac->Mean(norm_o, o);
  const auto v = ac->Value(norm_o, o);
  const auto logp = GaussianLogProb(b.actions.index_select(0, idx), mu, ac->log_std());
  const auto old_logp = b.log_probs.index_select(0, idx);
  const auto actor =
      ClippedSurrogateLoss(logp, old_logp, b.advantages.index_select(0, idx), ppo.clip);
  const auto critic = (v - b.returns.index_select(0, idx)).pow(2).mean();
  const auto bounds = BoundsLoss(mu);
  // Temporal smoothness of the mean: measured always (the log's chatter figure), trained with
  // smooth_coef > 0 (then the successor's mean carries gradients too, as in CAPS).
  torch::Tensor smooth;
  {
    const auto next = b.next_index.index_select(0, idx);
    const auto valid = b.next_valid.index_select(0, idx);
    std::optional<torch::NoGradGuard> off;
    if (ppo.smooth_coef <= 0) off.emplace();
    const auto mu_next = ac->Mean(b.obs_norm.index_select(0, next), b.obs.index_select(0, next));
    const auto per_sample = ((ppo.smooth_coef > 0 ? mu : mu.detach()) - mu_next).pow(2).mean(-1);
    smooth = (per_sample * valid).sum() / valid.sum().clamp_min(1.0);
  }
  // During the actor warm-up only the critic learns: a fresh value function (and value
  // normaliser) gives a warm-started actor meaningless advantages at first.
  const double actor_weight = iteration < ppo.actor_warmup_iterations ? 0.0 : 1.0;
  auto loss = actor_weight * (actor + ppo.bounds_coef * bounds) + ppo.critic_coef * critic;
  if (ppo.smooth_coef > 0) loss = loss + actor_weight * ppo.smooth_coef * smooth;
  (world == 1 ? loss : loss * share).backward();
  u->actor += actor.item<double>() * share;
  u->critic += critic.item<double>() * share;
  u->bounds += bounds.item<double>() * share;
  u->smooth += smooth.item<double>() * share;
  u->clip_fraction += ClipFraction(logp.detach(), old_logp, ppo.clip) * share;
  // KL(old ‖ new) by the low-variance estimator E[(r − 1) − log r].
  const auto log_r = (logp.detach() - old_logp);
  u->minibatch_kl = ((log_r.exp() - 1) - log_r).mean().item<double>() * share;
  u->kl += u->minibatch_kl;
}

void Trainer::Impl::DiscriminatorLoss(const Batch& b, const torch::Tensor& agent_idx, double share,
                                      UpdateTotals* u) {
  const auto& ampc = cfg.amp;
  const int64_t na = agent_idx.size(0);
  auto neg = b.amp_norm.index_select(0, agent_idx);
  auto neg_style = b.styles.index_select(0, agent_idx);
  if (replay->size() > 0) {
    auto [rep, rep_style] = replay->Sample(na, amp_rng);
    neg = torch::cat({neg, amp_norm->Normalize(rep)});
    neg_style = torch::cat({neg_style, rep_style});
  }
  std::vector<int64_t> demo_idx(na);
  for (auto& i : demo_idx) i = amp_rng.UniformInt(demo_pool.size(0));
  const auto di = torch::tensor(demo_idx, torch::kInt64);
  const auto pos = amp_norm->Normalize(demo_pool.index_select(0, di));
  const auto pos_style = demo_pool_styles.index_select(0, di);
  // SIMS conditional negatives: real motion paired with another clip's embedding.
  if (style_dim > 0 && ampc.mismatch_fraction > 0 && style_table.size(0) > 1)
    AppendMismatchedNegatives(pos, pos_style, ampc.mismatch_fraction, style_table.size(0), amp_rng,
                              &neg, &neg_style);
  const auto dl =
      learning::DiscriminatorLoss(disc, pos, StyleOf(pos_style), neg, StyleOf(neg_style), ampc);
  (ampc.disc_coef * (world == 1 ? dl.total : dl.total * share)).backward();
  u->disc += dl.classification * share;
  u->grad_penalty += dl.grad_penalty * share;
  u->demo_accuracy += dl.demo_accuracy * share;
  u->agent_accuracy += dl.agent_accuracy * share;
  u->disc_samples += pos.size(0) + neg.size(0);
}

Trainer::Impl::UpdateTotals Trainer::Impl::Update(const Batch& b, Timings* timing) {
  const auto& ppo = cfg.ppo;
  const int64_t N = n;
  // The PPO and discriminator losses share no parameters: two backward passes give the same
  // gradients as one on their sum, and let the benchmark time each network's share.
  // With ranks, the batch is the union of all ranks' samples (global flat index
  // t × N_total + global env id); every rank draws the same permutation of it, and in each
  // minibatch trains on the samples it holds, its losses weighted by its share.
  UpdateTotals u;
  const int64_t total = ppo.horizon * N * world;
  u.minibatch = std::min<int64_t>(static_cast<int64_t>(ppo.minibatch_size) * world, total);
  const int64_t mb = u.minibatch;
  const int64_t n_mb = std::max<int64_t>(total / mb, 1);
  const int64_t na_all = std::min<int64_t>(static_cast<int64_t>(cfg.amp.batch_size) * world, mb);
  const int64_t n_total = N * world, first = first_env;
  auto local_of = [&](const torch::Tensor& global) {
    if (world == 1) return global;
    const auto env_id = global.remainder(n_total);
    const auto mask = (env_id >= first).logical_and(env_id < first + N);
    return (global.div(n_total, "floor") * N + env_id - first).masked_select(mask);
  };
  const auto ac_params = ac->parameters();
  // Each network's gradient is clipped on its own: one norm over all three let the critic's
  // (5× weighted) or the discriminator's gradient shrink the actor's step.
  std::vector<torch::Tensor> actor_params, critic_params;
  for (const auto& p : ac->named_parameters())
    (p.key().rfind("actor", 0) == 0 ? actor_params : critic_params).push_back(p.value());
  const auto disc_params = use_amp ? disc->parameters() : std::vector<torch::Tensor>{};
  const std::vector<torch::Tensor> no_params;
  for (int epoch = 0; epoch < ppo.mini_epochs; ++epoch) {
    const bool train_disc = use_amp && (cfg.amp.disc_epochs == 0 || epoch < cfg.amp.disc_epochs);
    // Zeroed gradients would still move it (Adam steps on its momentum); undefined ones are
    // skipped, and zero_grad and the PPO backward leave them undefined for the whole epoch.
    if (use_amp && !train_disc)
      for (const auto& p : disc_params) p.mutable_grad() = torch::Tensor();
    const auto perm = Permutation(rng, total);
    for (int64_t k = 0; k < n_mb; ++k) {
      auto t_phase = Clock::now();
      const auto chunk = perm.slice(0, k * mb, (k + 1) * mb);
      const auto idx = local_of(chunk);
      optim->zero_grad();
      u.minibatch_kl = 0;
      if (idx.size(0) > 0)
        PpoLoss(b, idx, static_cast<double>(idx.size(0)) / static_cast<double>(mb), &u);
      StartReduce(ac_params, &ac_grads);
      timing->ppo += Since(t_phase);
      if (train_disc) {
        t_phase = Clock::now();
        const auto agent_idx = local_of(chunk.slice(0, 0, na_all));
        if (agent_idx.size(0) > 0)
          DiscriminatorLoss(b, agent_idx,
                            static_cast<double>(agent_idx.size(0)) / static_cast<double>(na_all),
                            &u);
        ++u.disc_steps;
        timing->disc += Since(t_phase);
      }
      t_phase = Clock::now();
      if (train_disc) StartReduce(disc_params, &disc_grads);
      FinishReduce(ac_params, train_disc ? disc_params : no_params);
      if (ppo.grad_norm > 0) {
        ClipGradNorm(actor_params, ppo.grad_norm);
        ClipGradNorm(critic_params, ppo.grad_norm);
      }
      if (train_disc && cfg.amp.grad_norm > 0) ClipGradNorm(disc_params, cfg.amp.grad_norm);
      optim->step();
      // (While the actor is frozen its KL says nothing: the rate stays.)
      if (ppo.lr_schedule == "adaptive" && iteration >= ppo.actor_warmup_iterations)
        AdaptLearningRate(u.minibatch_kl);
      timing->ppo += Since(t_phase);
      ++u.steps;
    }
  }
  return u;
}

void Trainer::Impl::AdaptLearningRate(double minibatch_kl) {
  // Every rank applies the same change: the KL is summed over the ranks' shares.
  if (comm) comm->AllReduceSum(&minibatch_kl, 1);
  const double threshold = cfg.ppo.kl_threshold;
  if (minibatch_kl > 2.0 * threshold)
    learning_rate = std::max(learning_rate / 1.5, 1e-6);
  else if (minibatch_kl < 0.5 * threshold)
    learning_rate = std::min(learning_rate * 1.5, 1e-2);
  for (auto& group : optim->param_groups())
    static_cast<torch::optim::AdamOptions&>(group.options()).lr(learning_rate);
}

IterationStats Trainer::RunIteration() {
  auto& m = *impl_;
  const int64_t T = m.cfg.ppo.horizon, N = m.n;
  IterationStats st;
  const auto t_iter = Clock::now();
  Impl::Rollout roll = m.CollectRollout();
  m.samples += T * N * m.world;
  Impl::Timings timing;
  const Impl::Batch batch = m.PrepareBatch(&timing);
  const auto t_update = Clock::now();
  Impl::UpdateTotals u = m.Update(batch, &timing);
  st.update_seconds = Since(t_update);

  // ---- buffers and normalisers for the next iteration ---------------------------------------
  if (m.use_amp) {
    m.replay->Add(batch.amp, batch.styles, m.cfg.amp.replay_keep_prob, m.amp_rng);
    m.UpdateNorm(m.amp_norm, batch.amp);
  }
  m.UpdateNorm(m.obs_norm, batch.obs);
  ++m.iteration;
  if (m.use_amp && m.cfg.amp.demo_refresh > 0) m.RefreshDemoBlock(m.iteration);

  // ---- statistics -------------------------------------------------------------------------
  // Sums over all ranks, so every rank (and rank 0's log) reports the whole run's figures.
  const double level = m.env->curriculum_level();
  const bool has_level = !std::isnan(level);
  double sums[] = {roll.return_sum,
                   roll.length_sum,
                   roll.success_sum,
                   roll.fall_sum,
                   static_cast<double>(roll.episodes),
                   m.rew_buf.sum().item<double>(),
                   batch.style_reward.sum().item<double>(),
                   batch.reward.sum().item<double>(),
                   u.actor,
                   u.critic,
                   u.bounds,
                   u.disc,
                   u.grad_penalty,
                   u.demo_accuracy,
                   u.agent_accuracy,
                   u.clip_fraction,
                   roll.force_sum,
                   roll.reference_episodes,
                   roll.reference_success,
                   roll.default_success,
                   u.kl,
                   has_level ? level : 0.0,
                   has_level ? 1.0 : 0.0,
                   u.smooth};
  if (m.comm) m.comm->AllReduceSum(sums, static_cast<int64_t>(std::size(sums)));
  const double episodes = sums[4];
  const double batch_size = static_cast<double>(T * N * m.world);
  if (m.comm && m.iteration % m.check_every == 0) m.CheckParametersAgree();
  const double s = std::max<int64_t>(u.steps, 1);
  st.iteration = m.iteration;
  st.samples = m.samples;
  st.task_reward = sums[5] / batch_size;
  st.style_reward = sums[6] / batch_size;
  st.total_reward = sums[7] / batch_size;
  st.episodes = static_cast<int64_t>(episodes);
  st.episode_return = episodes > 0 ? sums[0] / episodes : std::nan("");
  st.episode_length = episodes > 0 ? sums[1] / episodes : std::nan("");
  st.success_rate = episodes > 0 ? sums[2] / episodes : std::nan("");
  st.fall_rate = episodes > 0 ? sums[3] / episodes : std::nan("");
  st.actor_loss = sums[8] / s;
  st.critic_loss = sums[9] / s;
  st.bounds_loss = sums[10] / s;
  st.smooth_loss = sums[23] / s;
  const double ds = std::max<int64_t>(u.disc_steps, 1);
  st.disc_loss = sums[11] / ds;
  st.grad_penalty = sums[12] / ds;
  st.disc_acc_demo = sums[13] / ds;
  st.disc_acc_agent = sums[14] / ds;
  st.clip_fraction = sums[15] / s;
  st.kl = sums[20] / s;
  st.learning_rate = m.learning_rate;
  st.curriculum_level = sums[22] > 0 ? sums[21] / sums[22] : std::nan("");
  st.force_end_rate = episodes > 0 ? sums[16] / episodes : std::nan("");
  st.reference_start_share = episodes > 0 ? sums[17] / episodes : std::nan("");
  st.success_rate_reference = sums[17] > 0 ? sums[18] / sums[17] : std::nan("");
  st.success_rate_default = episodes > sums[17] ? sums[19] / (episodes - sums[17]) : std::nan("");
  st.env_samples_per_s = static_cast<double>(T * N) / roll.seconds;
  const int64_t mb_rank = u.minibatch / m.world;  // this rank's FLOPs and samples
  st.train_samples_per_s =
      static_cast<double>(u.steps * mb_rank) / std::max(st.update_seconds, 1e-9);
  // Forward + backward ≈ 3 × 2 × MACs per sample for each network (the discriminator also
  // pays a double-backward for the gradient penalty on its demo half, ≈ 2× more).
  const double ac_flop = 6.0 * LinearMacs(*m.ac) * static_cast<double>(u.steps * mb_rank);
  const double disc_flop =
      m.use_amp ? 6.0 * LinearMacs(*m.disc) * static_cast<double>(u.disc_samples) * 1.5 : 0.0;
  st.update_gflop = (ac_flop + disc_flop) * 1e-9;
  st.env_seconds = roll.env_seconds;
  st.inference_seconds = roll.seconds - roll.env_seconds;
  st.disc_seconds = timing.disc;
  st.ppo_seconds = timing.ppo;
  st.iteration_seconds = Since(t_iter);
  return st;
}

namespace {
void WriteTensor(torch::serialize::OutputArchive& a, const std::string& key,
                 const torch::Tensor& t) {
  a.write(key, t, /*is_buffer=*/true);
}
torch::Tensor ReadTensor(torch::serialize::InputArchive& a, const std::string& key) {
  torch::Tensor t;
  a.read(key, t, /*is_buffer=*/true);
  return t;
}
void SaveArchiveAtomically(torch::serialize::OutputArchive& archive,
                           const std::filesystem::path& path) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  auto tmp = path;
  tmp += ".tmp";
  archive.save_to(tmp.string());
  std::filesystem::rename(tmp, path);
}
// A module's parameters and buffers stored as one sub-archive under `key`.
template <class Module>
void WriteModule(torch::serialize::OutputArchive& a, const std::string& key, const Module& m) {
  torch::serialize::OutputArchive sub;
  m->save(sub);
  a.write(key, sub);
}
template <class Module>
void ReadModule(torch::serialize::InputArchive& a, const std::string& key, Module& m) {
  torch::serialize::InputArchive sub;
  a.read(key, sub);
  m->load(sub);
}
torch::Tensor StringTensor(const std::string& s) {
  auto t = torch::empty({static_cast<int64_t>(s.size())}, torch::kUInt8);
  std::memcpy(t.data_ptr<uint8_t>(), s.data(), s.size());
  return t;
}
std::string TensorString(const torch::Tensor& t) {
  const auto c = t.contiguous();
  return std::string(reinterpret_cast<const char*>(c.data_ptr<uint8_t>()), c.numel());
}
// Opens a policy file written by ExportPolicy and hands its archive and metadata to `use`;
// any failure becomes one error naming the file.
void ReadPolicyFile(
    const std::filesystem::path& path,
    const std::function<void(torch::serialize::InputArchive&, const std::string&)>& use) {
  if (!std::filesystem::exists(path))
    ThrowInputError(path.string(), "", "a policy file", "missing");
  try {
    torch::serialize::InputArchive archive;
    archive.load_from(path.string());
    use(archive, TensorString(ReadTensor(archive, "metadata")));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    ThrowInputError(path.string(), "", "a policy file written by ExportPolicy", e.what());
  }
}
// The observation layout a policy file's metadata records (ExportPolicy).
std::vector<sim::ObsSegment> SegmentsOf(const nlohmann::json& meta) {
  std::vector<sim::ObsSegment> out;
  for (const auto& j : meta.at("segments")) {
    sim::ObsSegment seg;
    seg.name = j.at("name").get<std::string>();
    seg.kind = static_cast<sim::ObsSegment::Kind>(j.at("kind").get<int>());
    seg.offset = j.at("offset").get<int>();
    seg.size = j.at("size").get<int>();
    seg.rows = j.at("rows").get<int>();
    seg.cols = j.at("cols").get<int>();
    out.push_back(seg);
  }
  return out;
}
// The weights a policy file carries: actor-critic and observation normaliser.
void LoadPolicyWeights(torch::serialize::InputArchive& archive, ActorCritic& ac,
                       RunningMeanStd& obs_norm) {
  ReadModule(archive, "actor_critic", ac);
  ReadModule(archive, "obs_norm", obs_norm);
  obs_norm->PerFeatureCount();
}
}  // namespace

namespace {
torch::Tensor RngTensor(const Rng& rng) {
  const auto s = rng.state();
  return torch::tensor({static_cast<int64_t>(s[0]), static_cast<int64_t>(s[1]),
                        static_cast<int64_t>(s[2]), static_cast<int64_t>(s[3])},
                       torch::kInt64);
}
void SetRng(Rng& rng, const torch::Tensor& t) {
  rng.set_state(
      {static_cast<uint64_t>(t[0].item<int64_t>()), static_cast<uint64_t>(t[1].item<int64_t>()),
       static_cast<uint64_t>(t[2].item<int64_t>()), static_cast<uint64_t>(t[3].item<int64_t>())});
}
}  // namespace

// What every rank shares: networks, normalisers, optimiser, minibatch order and counters.
void Trainer::Impl::WriteLearnerState(torch::serialize::OutputArchive& archive,
                                      bool with_optimizer) const {
  const auto& m = *this;
  WriteModule(archive, "actor_critic", m.ac);
  WriteModule(archive, "obs_norm", m.obs_norm);
  WriteModule(archive, "value_norm", m.value_norm);
  if (m.use_amp) {
    WriteModule(archive, "disc", m.disc);
    WriteModule(archive, "amp_norm", m.amp_norm);
  }
  if (with_optimizer) {
    torch::serialize::OutputArchive opt;
    m.optim->save(opt);
    archive.write("optimizer", opt);
  }
  WriteTensor(archive, "rng", RngTensor(m.rng));
  WriteTensor(archive, "counters", torch::tensor({m.iteration, m.samples}, torch::kInt64));
  WriteTensor(archive, "learning_rate", torch::tensor({m.learning_rate}, torch::kFloat64));
  WriteTensor(archive, "config", StringTensor(ConfigToJson(m.cfg).dump()));
}

void Trainer::Impl::ReadLearnerState(torch::serialize::InputArchive& archive,
                                     const std::string& source) {
  auto& m = *this;
  const auto saved_cfg = nlohmann::json::parse(TensorString(ReadTensor(archive, "config")));
  if (NetworkShape(saved_cfg["network"]) != NetworkShape(ConfigToJson(m.cfg.network)))
    ThrowInputError(source, "network", "the same network sizes as the current config",
                    saved_cfg["network"].dump());
  ReadModule(archive, "actor_critic", m.ac);
  ReadModule(archive, "obs_norm", m.obs_norm);
  ReadModule(archive, "value_norm", m.value_norm);
  m.obs_norm->PerFeatureCount();
  if (m.use_amp) {
    ReadModule(archive, "disc", m.disc);
    ReadModule(archive, "amp_norm", m.amp_norm);
    m.amp_norm->PerFeatureCount();
  }
  torch::serialize::InputArchive opt;
  if (archive.try_read("optimizer", opt)) {
    m.optim->load(opt);
  } else {
    // A compact checkpoint: Adam's moments start again from zero (its first steps are
    // bias-corrected, so the step size stays the learning rate kept below).
    m.optim->state().clear();
    spdlog::info("{}: no optimiser moments (a compact checkpoint); Adam restarts", source);
  }
  SetRng(m.rng, ReadTensor(archive, "rng"));
  const auto counters = ReadTensor(archive, "counters");
  m.iteration = counters[0].item<int64_t>();
  m.samples = counters[1].item<int64_t>();
  // The adaptive schedule's rate (checkpoints from before it keep the configured one).
  torch::Tensor lr;
  m.learning_rate = archive.try_read("learning_rate", lr, /*is_buffer=*/true)
                        ? lr[0].item<double>()
                        : m.cfg.ppo.learning_rate;
  for (auto& group : m.optim->param_groups())
    static_cast<torch::optim::AdamOptions&>(group.options()).lr(m.learning_rate);
  RebuildDemoPool();
}

void Trainer::SaveCheckpoint(const std::filesystem::path& path, bool full) const {
  const auto& m = *impl_;
  torch::serialize::OutputArchive archive;
  m.WriteLearnerState(archive, /*with_optimizer=*/full);
  // This rank's own state: replay buffer, sampling streams, episodes, environments. With
  // ranks, rank 0 writes the checkpoint; the others restart their environments on resume.
  if (m.use_amp && full) {
    WriteTensor(archive, "replay_data", m.replay->data());
    WriteTensor(archive, "replay_styles", m.replay->styles());
    WriteTensor(archive, "replay_size", torch::tensor({m.replay->size()}, torch::kInt64));
  }
  WriteTensor(archive, "amp_rng", RngTensor(m.amp_rng));
  std::vector<torch::Tensor> noise;
  for (const auto& r : m.noise_rng) noise.push_back(RngTensor(r));
  WriteTensor(archive, "noise_rng", torch::stack(noise));
  WriteTensor(archive, "world_size", torch::tensor({static_cast<int64_t>(m.world)}, torch::kInt64));
  WriteTensor(archive, "ep_return", torch::tensor(m.ep_return, torch::kFloat64));
  WriteTensor(archive, "ep_len", torch::tensor(m.ep_len, torch::kFloat64));
  WriteTensor(
      archive, "ep_success",
      torch::tensor(std::vector<int64_t>(m.ep_success.begin(), m.ep_success.end()), torch::kInt64));
  WriteTensor(archive, "env_state", StringTensor(m.env->SaveState()));
  SaveArchiveAtomically(archive, path);
}

void Trainer::LoadCheckpoint(const std::filesystem::path& path) {
  auto& m = *impl_;
  if (!std::filesystem::exists(path))
    ThrowInputError(path.string(), "", "a checkpoint file", "missing");
  try {
    torch::serialize::InputArchive archive;
    archive.load_from(path.string());
    m.ReadLearnerState(archive, path.string());
    torch::Tensor data;
    if (m.use_amp && archive.try_read("replay_data", data, /*is_buffer=*/true)) {
      if (data.sizes() != m.replay->data().sizes())
        ThrowInputError(path.string(), "replay_data", "a replay buffer of the configured size",
                        "another size");
      m.replay->data().copy_(data);
      m.replay->styles().copy_(ReadTensor(archive, "replay_styles"));
      m.replay->set_size(ReadTensor(archive, "replay_size")[0].item<int64_t>());
    } else if (m.use_amp) {
      spdlog::info(
          "{}: a compact checkpoint; the AMP replay buffer refills from the next "
          "rollouts",
          path.string());
    }
    // Checkpoints from before per-environment noise streams keep the fresh ones.
    torch::Tensor t;
    if (archive.try_read("amp_rng", t, /*is_buffer=*/true)) SetRng(m.amp_rng, t);
    if (archive.try_read("noise_rng", t, /*is_buffer=*/true) && t.size(0) == m.n)
      for (int64_t i = 0; i < m.n; ++i) SetRng(m.noise_rng[i], t[i]);
    const auto er = ReadTensor(archive, "ep_return"), el = ReadTensor(archive, "ep_len"),
               es = ReadTensor(archive, "ep_success");
    if (er.numel() != m.n)
      ThrowInputError(path.string(), "ep_return", std::to_string(m.n) + " environments",
                      std::to_string(er.numel()));
    for (int64_t i = 0; i < m.n; ++i) {
      m.ep_return[i] = er[i].item<double>();
      m.ep_len[i] = el[i].item<double>();
      m.ep_success[i] = static_cast<uint8_t>(es[i].item<int64_t>());
    }
    m.env->LoadState(TensorString(ReadTensor(archive, "env_state")));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    ThrowInputError(path.string(), "", "a checkpoint written by this trainer configuration",
                    e.what());
  }
}

void Trainer::Synchronize() {
  auto& m = *impl_;
  if (!m.comm) return;
  std::string bytes;
  if (m.rank == 0) {
    torch::serialize::OutputArchive archive;
    m.WriteLearnerState(archive, /*with_optimizer=*/true);
    std::ostringstream out;
    archive.save_to(out);
    bytes = out.str();
  }
  m.comm->Broadcast(&bytes, 0);
  if (m.rank != 0) {
    torch::serialize::InputArchive archive;
    std::istringstream in(bytes);
    archive.load_from(in);
    m.ReadLearnerState(archive, "rank 0's learner state");
  }
}

void Trainer::InitFromPolicy(const std::filesystem::path& path) {
  auto& m = *impl_;
  ReadPolicyFile(path, [&](torch::serialize::InputArchive& archive, const std::string& metadata) {
    const auto meta = nlohmann::json::parse(metadata);
    if (NetworkShape(meta.at("network")) != NetworkShape(ConfigToJson(m.cfg.network)))
      ThrowInputError(path.string(), "network", "the same network sizes as this run",
                      meta.at("network").dump());
    const std::vector<sim::ObsSegment> segs = SegmentsOf(meta);
    const int64_t offset = ObsWidth(segs);
    if (offset != meta.at("obs_dim").get<int64_t>())
      ThrowInputError(path.string(), "segments", "segments covering obs_dim",
                      std::to_string(offset));
    auto same = [](const sim::ObsSegment& a, const sim::ObsSegment& b) {
      return a.name == b.name && a.kind == b.kind && a.offset == b.offset && a.size == b.size;
    };
    if (segs.size() == m.segments.size() &&
        std::equal(segs.begin(), segs.end(), m.segments.begin(), same)) {
      LoadPolicyWeights(archive, m.ac, m.obs_norm);
      return;
    }
    // Another task's layout (walk → an object skill): shared inputs keep their weights and
    // statistics, new ones start silent.
    ActorCritic src(segs, m.act_dim, m.cfg.network);
    RunningMeanStd src_norm(offset, m.cfg.ppo.obs_clip);
    LoadPolicyWeights(archive, src, src_norm);
    const LayoutImport imported =
        ImportAcrossLayouts(src, src_norm, segs, m.ac, m.obs_norm, m.segments, m.cfg.network,
                            m.cfg.ppo.warm_start_quiet_var);
    std::string names;
    for (const auto& n : imported.new_segments) names += (names.empty() ? "" : ", ") + n;
    spdlog::info(
        "{}: warm start across layouts; new inputs start silent: {}; {} task inputs that were "
        "near-constant there (variance < {}) too",
        path.string(), names.empty() ? "none" : names, imported.silenced,
        m.cfg.ppo.warm_start_quiet_var);
  });
  // The task inputs' statistics count as warm_start_obs_count samples so the new task's take
  // over within a few iterations; the proprioceptive ("self") inputs keep the source's count:
  // renormalising them to the new task's poses would change what the imported policy does
  // before it has learnt anything (a walk policy then falls within 1.5 s).
  for (const auto& seg : m.segments)
    if (seg.name != "self" && seg.kind != sim::ObsSegment::Kind::kStyle)
      m.obs_norm->CapCount(seg.offset, seg.size, m.cfg.ppo.warm_start_obs_count);
  const int64_t restarted = m.obs_norm->Soften(std::numeric_limits<double>::infinity(), 1e-6);
  spdlog::info(
      "{}: task inputs of the observation normaliser count as {} samples (the self observation "
      "keeps its count); {} inputs constant there restart",
      path.string(), m.cfg.ppo.warm_start_obs_count, restarted);
}

void Trainer::ExportPolicy(const std::filesystem::path& path, const std::string& extra_json) const {
  const auto& m = *impl_;
  torch::serialize::OutputArchive archive;
  WriteModule(archive, "actor_critic", m.ac);
  WriteModule(archive, "obs_norm", m.obs_norm);
  nlohmann::json segs = nlohmann::json::array();
  for (const auto& s : m.segments)
    segs.push_back({{"name", s.name},
                    {"kind", static_cast<int>(s.kind)},
                    {"offset", s.offset},
                    {"size", s.size},
                    {"rows", s.rows},
                    {"cols", s.cols}});
  nlohmann::json meta = {{"format", "sims-policy-1"},
                         {"obs_dim", m.obs_dim},
                         {"action_dim", m.act_dim},
                         {"segments", segs},
                         {"network", ConfigToJson(m.cfg.network)},
                         {"obs_clip", m.cfg.ppo.obs_clip},
                         {"iteration", m.iteration}};
  if (!extra_json.empty()) meta["extra"] = nlohmann::json::parse(extra_json);
  WriteTensor(archive, "metadata", StringTensor(meta.dump()));
  SaveArchiveAtomically(archive, path);
}

std::vector<float> Trainer::FlatParameters() const {
  std::vector<float> out;
  for (const auto& p : impl_->AllParameters()) {
    const auto c = p.detach().contiguous();
    out.insert(out.end(), c.data_ptr<float>(), c.data_ptr<float>() + c.numel());
  }
  return out;
}

void Trainer::ActMean(const float* obs, int n, float* actions) const {
  torch::InferenceMode guard;
  const auto o = FromBuffer(obs, {n, impl_->obs_dim});
  const auto mu = impl_->ac->Mean(impl_->obs_norm->Normalize(o), o).contiguous();
  std::memcpy(actions, mu.data_ptr<float>(), sizeof(float) * n * impl_->act_dim);
}

// ---- Policy --------------------------------------------------------------------------------

struct Policy::Impl {
  ActorCritic ac{nullptr};
  RunningMeanStd obs_norm{nullptr};
  int obs_dim = 0, action_dim = 0;
  std::string metadata;
  std::once_flag row_exact_once;
  int row_exact_rows = 1;
};

Policy::Policy(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  BindTorchThreads();
  ReadPolicyFile(path, [&](torch::serialize::InputArchive& archive, const std::string& metadata) {
    impl_->metadata = metadata;
    const auto meta = nlohmann::json::parse(impl_->metadata);
    const std::vector<sim::ObsSegment> segments = SegmentsOf(meta);
    const auto net = ConfigFromJson<NetworkConfig>(meta.at("network"), path.string());
    impl_->obs_dim = meta.at("obs_dim").get<int>();
    impl_->action_dim = meta.at("action_dim").get<int>();
    impl_->ac = ActorCritic(segments, impl_->action_dim, net);
    impl_->obs_norm = RunningMeanStd(impl_->obs_dim, meta.at("obs_clip").get<double>());
    LoadPolicyWeights(archive, impl_->ac, impl_->obs_norm);
  });
}

Policy::~Policy() = default;
Policy::Policy(Policy&&) noexcept = default;
Policy& Policy::operator=(Policy&&) noexcept = default;
int Policy::obs_dim() const { return impl_->obs_dim; }
int Policy::action_dim() const { return impl_->action_dim; }
const std::string& Policy::metadata_json() const { return impl_->metadata; }

void Policy::Act(const float* obs, int n, float* actions) const {
  torch::InferenceMode guard;
  const auto o = FromBuffer(obs, {n, impl_->obs_dim});
  const auto mu = impl_->ac->Mean(impl_->obs_norm->Normalize(o), o).contiguous();
  std::memcpy(actions, mu.data_ptr<float>(), sizeof(float) * n * impl_->action_dim);
}

int Policy::RowExactRows() const {
  std::call_once(impl_->row_exact_once, [this] {
    constexpr int kMaxRows = 64;
    const int d = impl_->obs_dim, a = impl_->action_dim;
    std::mt19937 gen(12345);
    std::normal_distribution<float> normal;
    std::vector<float> obs(static_cast<size_t>(kMaxRows) * d);
    for (auto& v : obs) v = normal(gen);
    std::vector<float> alone(static_cast<size_t>(kMaxRows) * a), together(alone.size());
    for (int i = 0; i < kMaxRows; ++i)
      Act(obs.data() + static_cast<size_t>(i) * d, 1, alone.data() + static_cast<size_t>(i) * a);
    // Chunks of c rows end in a shorter one, so every batch size up to c has to agree.
    int rows = 1;
    for (int c = 2; c <= kMaxRows; ++c) {
      Act(obs.data(), c, together.data());
      if (std::memcmp(together.data(), alone.data(), sizeof(float) * c * a) != 0) break;
      rows = c;
    }
    impl_->row_exact_rows = rows;
  });
  return impl_->row_exact_rows;
}

void Policy::ActRowExact(const float* obs, int n, float* actions) const {
  const int chunk = RowExactRows();
  for (int r = 0; r < n; r += chunk)
    Act(obs + static_cast<size_t>(r) * impl_->obs_dim, std::min(chunk, n - r),
        actions + static_cast<size_t>(r) * impl_->action_dim);
}

}  // namespace sims::learning
