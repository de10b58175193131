#include "sims/learning/trainer.h"

#include <gtest/gtest.h>
#include <torch/torch.h>

#include "common/test_util.h"
#include "point_mass_env.h"

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

double PolicyObsCount(const std::filesystem::path& policy) {
  torch::serialize::InputArchive archive, norm;
  archive.load_from(policy.string());
  archive.read("obs_norm", norm);
  torch::Tensor count;
  norm.read("count", count, /*is_buffer=*/true);
  return count.item<double>();
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
  EXPECT_GT(PolicyObsCount(dir / "source.pt"), 2000.0);  // 3 iterations × 800 samples
  EXPECT_DOUBLE_EQ(PolicyObsCount(dir / "warm.pt"), 50.0);
}

}  // namespace
}  // namespace sims::learning
