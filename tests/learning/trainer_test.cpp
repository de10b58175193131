#include "sims/learning/trainer.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sims::learning
