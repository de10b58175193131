#include "sims/learning/trainer.h"

#include <cmath>
#include <filesystem>
#include <iostream>

#include <gtest/gtest.h>
#include <torch/torch.h>

#include "common/test_util.h"
#include "point_mass_env.h"
#include "sims/core/paths.h"

namespace sims::learning {
namespace {

LearnerConfig ToyConfig(bool amp) {
  LearnerConfig c;
  c.network.actor_hidden = {64, 64};
  c.network.critic_hidden = {64, 64};
  c.network.disc_hidden = {32};
  c.network.action_log_std = -1.0;  // the toy task needs more exploration than σ = 0.055
  c.ppo.horizon = 25;
  c.ppo.minibatch_size = 400;
  c.ppo.mini_epochs = 5;
  c.ppo.learning_rate = 3e-3;
  c.ppo.critic_coef = 1.0;
  c.amp.enabled = amp;
  c.amp.conditional = amp;
  c.amp.replay_size = 2000;
  c.amp.demo_pool_size = 1000;
  c.amp.batch_size = 128;
  c.amp.task_weight = 0.9;
  c.amp.style_weight = 0.1;
  c.seed = 3;
  return c;
}

Trainer MakeTrainer(bool amp, uint64_t env_seed = 5) {
  return Trainer(std::make_shared<testing::PointMassEnv>(32, env_seed),
                 amp ? std::make_shared<testing::ToyDemo>() : nullptr, ToyConfig(amp));
}

Trainer MakeTrainer(const LearnerConfig& c, uint64_t env_seed = 5) {
  return Trainer(std::make_shared<testing::PointMassEnv>(32, env_seed),
                 c.amp.enabled ? std::make_shared<testing::ToyDemo>() : nullptr, c);
}

// PPO on a small MuJoCo task improves the return by a clear margin (fixed seeds).
TEST(TrainerTest, PpoLearnsPointMassReaching) {
  Trainer t = MakeTrainer(false);
  double first = 0, last = 0;
  const int iters = 60;
  for (int i = 0; i < iters; ++i) {
    const auto s = t.RunIteration();
    if (i < 5) first += s.task_reward / 5;
    if (i >= iters - 5) last += s.task_reward / 5;
  }
  EXPECT_GT(last, first + 0.2) << "first " << first << " last " << last;
  EXPECT_GT(last, 0.55);
}

// The temporal smoothness loss (CAPS) is measured whether or not it trains; with a weight it
// makes the action mean change less between consecutive states while the task is still learnt
// (fixed seeds, the same rollouts' start).
TEST(TrainerTest, SmoothnessLossCalmsTheActionMean) {
  auto run = [](double coef, double* first_reward, double* last_reward) {
    LearnerConfig c = ToyConfig(false);
    c.ppo.smooth_coef = coef;
    Trainer t = MakeTrainer(c);
    double last_smooth = 0;
    *first_reward = *last_reward = 0;
    const int iters = 60;
    for (int i = 0; i < iters; ++i) {
      const auto s = t.RunIteration();
      EXPECT_GE(s.smooth_loss, 0.0);
      if (i < 5) *first_reward += s.task_reward / 5;
      if (i >= iters - 10) {
        last_smooth += s.smooth_loss / 10;
        *last_reward += s.task_reward / 10;
      }
    }
    return last_smooth;
  };
  double first0 = 0, last0 = 0, first1 = 0, last1 = 0;
  const double free = run(0.0, &first0, &last0);
  const double smoothed = run(50.0, &first1, &last1);
  std::cout << "smooth loss: coef 0 " << free << ", coef 50 " << smoothed << "; task reward "
            << first0 << " -> " << last0 << " and " << first1 << " -> " << last1 << "\n";
  EXPECT_GT(free, 0.0);
  EXPECT_LT(smoothed, 0.5 * free);
  EXPECT_GT(last1, first1 + 0.1) << "the smoothed policy still learns the task";
  LearnerConfig bad = ToyConfig(false);
  bad.ppo.smooth_coef = -1;
  const std::string e = sims::testing::ErrorOf([&] { bad.ppo.Validate(); });
  EXPECT_NE(e.find("smooth_coef"), std::string::npos) << e;
}

TEST(TrainerTest, CheckpointRestoresIdenticalActions) {
  const auto dir = sims::testing::TempDir("trainer");
  Trainer a = MakeTrainer(true);
  a.RunIteration();
  a.SaveCheckpoint(dir / "ckpt.pt");
  a.ExportPolicy(dir / "policy.pt");
  Trainer b = MakeTrainer(true, /*env_seed=*/99);
  b.LoadCheckpoint(dir / "ckpt.pt");
  EXPECT_EQ(a.FlatParameters(), b.FlatParameters());
  const std::vector<float> obs = {0.3f, -0.2f, 0.1f, 0.0f, -1.0f, 0.5f, 0.2f, 0.1f};
  std::vector<float> act_a(4), act_b(4), act_p(4);
  a.ActMean(obs.data(), 2, act_a.data());
  b.ActMean(obs.data(), 2, act_b.data());
  Policy p(dir / "policy.pt");
  p.Act(obs.data(), 2, act_p.data());
  EXPECT_EQ(act_a, act_b);
  EXPECT_EQ(act_a, act_p);
  EXPECT_THROW(Policy(dir / "missing.pt"), Error);
  std::filesystem::resize_file(dir / "policy.pt", 100);
  EXPECT_THROW(Policy(dir / "policy.pt"), Error);
}

// A batch gives every row exactly the action the row gets alone (the batched story FSM relies
// on it), on the bundled walk policy, whose layer sizes the BLAS blocks.
TEST(PolicyTest, RowExactBatchesGiveEachRowItsLoneAction) {
  const Policy p(AssetPath("policies/walk/policy.pt"));
  EXPECT_GE(p.RowExactRows(), 1);
  EXPECT_LE(p.RowExactRows(), 64);
  const int n = 37, d = p.obs_dim(), a = p.action_dim();
  std::vector<float> obs(static_cast<size_t>(n) * d), batch(static_cast<size_t>(n) * a), one(a);
  for (size_t i = 0; i < obs.size(); ++i) obs[i] = std::sin(0.37f * i);
  p.ActRowExact(obs.data(), n, batch.data());
  for (int r = 0; r < n; ++r) {
    p.Act(obs.data() + static_cast<size_t>(r) * d, 1, one.data());
    EXPECT_EQ(std::vector<float>(batch.begin() + r * a, batch.begin() + (r + 1) * a), one)
        << "row " << r;
  }
}

// A compact checkpoint (no replay buffer, no optimiser moments) is what a campaign commits
// between sessions: it is smaller, restores the networks, counters and learning rate exactly,
// and training goes on from it.
TEST(TrainerTest, CompactCheckpointResumesWithoutTheReplay) {
  const auto dir = sims::testing::TempDir("trainer_compact");
  LearnerConfig c = ToyConfig(true);
  c.amp.replay_size = 20000;  // large enough that the buffer dominates the file
  Trainer a = MakeTrainer(c);
  a.RunIteration();
  a.SaveCheckpoint(dir / "full.pt");
  a.SaveCheckpoint(dir / "compact.pt", /*full=*/false);
  EXPECT_LT(std::filesystem::file_size(dir / "compact.pt"),
            std::filesystem::file_size(dir / "full.pt") / 2);
  Trainer b = MakeTrainer(c, /*env_seed=*/99);
  b.LoadCheckpoint(dir / "compact.pt");
  EXPECT_EQ(b.iteration(), 1);
  EXPECT_EQ(a.FlatParameters(), b.FlatParameters());
  const IterationStats s = b.RunIteration();
  EXPECT_EQ(s.iteration, 2);
  EXPECT_TRUE(std::isfinite(s.disc_loss));

  // Without AMP (no replay) the optimiser's two moments per weight are most of a full file.
  LearnerConfig adaptive = ToyConfig(false);
  adaptive.ppo.lr_schedule = "adaptive";
  const auto make = [&](uint64_t env_seed) {
    return Trainer(std::make_shared<testing::PointMassEnv>(32, env_seed), nullptr, adaptive);
  };
  Trainer p = make(5);
  p.RunIteration();
  ASSERT_NE(p.learning_rate(), adaptive.ppo.learning_rate) << "the schedule moved it";
  p.SaveCheckpoint(dir / "ppo_full.pt");
  p.SaveCheckpoint(dir / "ppo_compact.pt", /*full=*/false);
  EXPECT_LT(std::filesystem::file_size(dir / "ppo_compact.pt"),
            0.6 * std::filesystem::file_size(dir / "ppo_full.pt"));
  Trainer q = make(99);
  q.LoadCheckpoint(dir / "ppo_compact.pt");
  EXPECT_EQ(p.FlatParameters(), q.FlatParameters());
  EXPECT_EQ(q.learning_rate(), p.learning_rate()) << "the learning rate is kept";
  EXPECT_EQ(q.RunIteration().iteration, 2);
}

// A campaign may change the fixed exploration noise between chunks: a checkpoint loads under
// another action σ (the new one is used), but not under other layer sizes.
TEST(TrainerTest, ResumeMayChangeTheActionNoiseButNotTheLayers) {
  const auto dir = sims::testing::TempDir("trainer_sigma");
  Trainer a = MakeTrainer(true);
  a.RunIteration();
  a.SaveCheckpoint(dir / "ckpt.pt");
  LearnerConfig noisier = ToyConfig(true);
  noisier.network.action_log_std = -0.5;
  Trainer b = MakeTrainer(noisier);
  b.LoadCheckpoint(dir / "ckpt.pt");
  EXPECT_EQ(a.FlatParameters(), b.FlatParameters());
  LearnerConfig wider = ToyConfig(true);
  wider.network.actor_hidden = {64, 32};
  Trainer c = MakeTrainer(wider);
  EXPECT_THROW(c.LoadCheckpoint(dir / "ckpt.pt"), Error);
}

// The actor warm-up: for the first K iterations only the critic learns (a warm-started actor
// is not pushed around by a fresh critic's advantages); afterwards the actor learns too.
TEST(TrainerTest, ActorWarmupFreezesTheActorOnly) {
  LearnerConfig c = ToyConfig(false);
  c.ppo.actor_warmup_iterations = 2;
  Trainer t = MakeTrainer(c);
  // FlatParameters lists the actor's MLP first (the point-mass observation has no encoder
  // parameters): 4 → 64 → 64 → 2 weights and biases.
  const size_t actor_n = (4 + 1) * 64 + (64 + 1) * 64 + (64 + 1) * 2;
  auto split = [&](const std::vector<float>& p) {
    return std::make_pair(std::vector<float>(p.begin(), p.begin() + actor_n),
                          std::vector<float>(p.begin() + actor_n, p.end()));
  };
  const auto [actor0, critic0] = split(t.FlatParameters());
  t.RunIteration();
  t.RunIteration();
  const auto [actor2, critic2] = split(t.FlatParameters());
  EXPECT_EQ(actor2, actor0);  // the actor has not moved
  EXPECT_NE(critic2, critic0);
  t.RunIteration();
  EXPECT_NE(split(t.FlatParameters()).first, actor0);  // from iteration 3 on it learns
}

// With disc_epochs = 1 the discriminator trains in the first mini-epoch only: after an
// iteration its weights are those of a run with one mini-epoch (Adam's momentum must not move
// them in the later ones), while the policy still takes all its PPO epochs.
TEST(TrainerTest, DiscriminatorTrainsInItsEpochsOnly) {
  const size_t disc_n =
      MakeTrainer(true).FlatParameters().size() - MakeTrainer(false).FlatParameters().size();
  ASSERT_GT(disc_n, 0u);
  auto split = [&](const Trainer& t) {
    const auto p = t.FlatParameters();
    return std::make_pair(std::vector<float>(p.begin(), p.end() - disc_n),
                          std::vector<float>(p.end() - disc_n, p.end()));
  };
  LearnerConfig one_epoch = ToyConfig(true);
  one_epoch.ppo.mini_epochs = 1;
  LearnerConfig first_epoch = ToyConfig(true);
  first_epoch.amp.disc_epochs = 1;
  ASSERT_GT(first_epoch.ppo.mini_epochs, 1);
  Trainer a = MakeTrainer(one_epoch), b = MakeTrainer(first_epoch), all = MakeTrainer(true);
  const auto st_a = a.RunIteration();
  const auto st_b = b.RunIteration();
  all.RunIteration();
  EXPECT_EQ(split(b).second, split(a).second);
  EXPECT_NE(split(all).second, split(a).second);
  EXPECT_NE(split(b).first, split(a).first);  // the PPO epochs went on
  // The logged discriminator figures average its own steps only.
  EXPECT_DOUBLE_EQ(st_b.disc_loss, st_a.disc_loss);
  EXPECT_DOUBLE_EQ(st_b.disc_acc_demo, st_a.disc_acc_demo);
}

// The adaptive schedule: a KL target far below what an update moves shrinks the rate by 1.5
// per minibatch step, one far above grows it; the rate is part of the checkpoint.
TEST(TrainerTest, AdaptiveLearningRateFollowsTheKl) {
  const auto dir = sims::testing::TempDir("trainer_adaptive");
  LearnerConfig c = ToyConfig(false);
  c.ppo.lr_schedule = "adaptive";
  c.ppo.kl_threshold = 1e-12;
  Trainer shrink = MakeTrainer(c);
  const IterationStats s = shrink.RunIteration();
  EXPECT_GT(s.kl, 2e-12);
  // 5 epochs × 2 minibatches, each a ÷1.5 step (the very first may see the rollout's own
  // policy, KL ≈ 0, and grow instead).
  EXPECT_LT(s.learning_rate, c.ppo.learning_rate / std::pow(1.5, 7));
  EXPECT_GT(s.learning_rate, c.ppo.learning_rate / std::pow(1.5, 10) * 0.999);
  shrink.SaveCheckpoint(dir / "ckpt.pt");
  Trainer resumed = MakeTrainer(c);
  resumed.LoadCheckpoint(dir / "ckpt.pt");
  EXPECT_LT(resumed.RunIteration().learning_rate, s.learning_rate / std::pow(1.5, 7));
  c.ppo.kl_threshold = 1e3;
  Trainer grow = MakeTrainer(c);
  EXPECT_NEAR(grow.RunIteration().learning_rate,
              std::min(c.ppo.learning_rate * std::pow(1.5, 10), 1e-2), 1e-12);
  c.ppo.lr_schedule = "constant";
  EXPECT_EQ(MakeTrainer(c).RunIteration().learning_rate, c.ppo.learning_rate);
}

// N iterations straight equal N/2, checkpoint, fresh process state, resume, N/2 more.
TEST(TrainerTest, ResumeIsEquivalentToStraightRun) {
  const auto dir = sims::testing::TempDir("resume");
  Trainer straight = MakeTrainer(true);
  for (int i = 0; i < 4; ++i) straight.RunIteration();
  Trainer first = MakeTrainer(true);
  for (int i = 0; i < 2; ++i) first.RunIteration();
  first.SaveCheckpoint(dir / "ckpt.pt");
  Trainer resumed = MakeTrainer(true, /*env_seed=*/1234);
  resumed.LoadCheckpoint(dir / "ckpt.pt");
  EXPECT_EQ(resumed.iteration(), 2);
  for (int i = 0; i < 2; ++i) resumed.RunIteration();
  EXPECT_EQ(straight.FlatParameters(), resumed.FlatParameters());
}

// With a refreshed demo pool the pool depends on the iteration alone: a resumed run rebuilds
// it and continues exactly as a straight one, and the refresh does change training.
TEST(TrainerTest, DemoRefreshResumesExactlyAndChangesThePool) {
  const auto dir = sims::testing::TempDir("demo_refresh");
  LearnerConfig c = ToyConfig(true);
  c.amp.demo_refresh = 300;  // the 1000-window pool wraps within four iterations
  Trainer straight = MakeTrainer(c);
  for (int i = 0; i < 4; ++i) straight.RunIteration();
  Trainer first = MakeTrainer(c);
  for (int i = 0; i < 2; ++i) first.RunIteration();
  first.SaveCheckpoint(dir / "ckpt.pt");
  Trainer resumed = MakeTrainer(c, /*env_seed=*/1234);
  resumed.LoadCheckpoint(dir / "ckpt.pt");
  for (int i = 0; i < 2; ++i) resumed.RunIteration();
  EXPECT_EQ(straight.FlatParameters(), resumed.FlatParameters());
  Trainer fixed = MakeTrainer(true);
  for (int i = 0; i < 4; ++i) fixed.RunIteration();
  EXPECT_NE(straight.FlatParameters(), fixed.FlatParameters());
}

// Actor, critic and discriminator gradients are clipped separately: scaling the critic's loss
// a thousandfold leaves the actor's update untouched (one joint clip would shrink it).
TEST(TrainerTest, ClipsEachNetworkOnItsOwn) {
  LearnerConfig a = ToyConfig(false), b = ToyConfig(false);
  a.ppo.grad_norm = b.ppo.grad_norm = 0.5;
  b.ppo.critic_coef = 1000.0;
  Trainer ta = MakeTrainer(a), tb = MakeTrainer(b);
  ta.RunIteration();
  tb.RunIteration();
  testing::PointMassEnv probe(8, 77);
  probe.Reset();
  std::vector<float> mean_a(8 * probe.action_dim()), mean_b(mean_a.size());
  ta.ActMean(probe.observations(), 8, mean_a.data());
  tb.ActMean(probe.observations(), 8, mean_b.data());
  EXPECT_EQ(mean_a, mean_b);
  EXPECT_NE(ta.FlatParameters(), tb.FlatParameters()) << "the critics differ";
}

// The per-feature sample counts of a policy's observation normaliser.
torch::Tensor PolicyObsCounts(const std::filesystem::path& policy) {
  torch::serialize::InputArchive archive, norm;
  archive.load_from(policy.string());
  archive.read("obs_norm", norm);
  torch::Tensor count;
  norm.read("count", count, /*is_buffer=*/true);
  return count;
}

// --init-policy keeps the source's weights but caps its normaliser count, so the new task's
// observation statistics take over instead of being outweighed by millions of old samples.
TEST(TrainerTest, InitFromPolicyCapsTheNormaliserCount) {
  const auto dir = sims::testing::TempDir("init_policy");
  Trainer source = MakeTrainer(false);
  for (int i = 0; i < 3; ++i) source.RunIteration();
  source.ExportPolicy(dir / "source.pt");
  LearnerConfig c = ToyConfig(false);
  c.ppo.warm_start_obs_count = 50;
  Trainer warm = MakeTrainer(c, /*env_seed=*/8);
  warm.InitFromPolicy(dir / "source.pt");
  warm.ExportPolicy(dir / "warm.pt");
  EXPECT_GT(PolicyObsCounts(dir / "source.pt").min().item<double>(), 2000.0);  // 3 × 800
  // The point mass observes one task segment ("state"): its count is capped.
  EXPECT_DOUBLE_EQ(PolicyObsCounts(dir / "warm.pt").max().item<double>(), 50.0);
}

}  // namespace
}  // namespace sims::learning
