#include "sims/sim/env.h"

#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/humanoid/model_builder.h"

namespace sims::sim {
namespace {

std::shared_ptr<const humanoid::Humanoid> MakeHumanoid() {
  static auto h = std::make_shared<const humanoid::Humanoid>(humanoid::BuildModel());
  return h;
}

EnvConfig SmallConfig(int n, int threads) {
  EnvConfig c;
  c.num_envs = n;
  c.threads = threads;
  c.seed = 7;
  c.spawn_radius = 2.0;
  return c;
}

std::vector<float> RandomActions(Rng& rng, int n, double scale) {
  std::vector<float> a(static_cast<size_t>(n) * humanoid::kNumDofs);
  for (auto& x : a) x = static_cast<float>(scale * rng.Normal());
  return a;
}

// A task whose goal is one number, observed as is.
class GoalTask : public TaskHook {
 public:
  double goal = 1.0;
  int obs_dim() const override { return 1; }
  void SampleInitialState(int, Rng&, InitialState*) override {}
  void OnReset(const EnvView&, Rng&) override {}
  TaskStepResult Step(const EnvView&) override { return {}; }
  void Observe(const EnvView&, float* out) const override { out[0] = static_cast<float>(goal); }
};

TEST(EnvTest, RefreshTaskObservationShowsANewGoalAtOnce) {
  auto task = std::make_unique<GoalTask>();
  GoalTask* goal = task.get();
  BatchedEnv env(MakeHumanoid(), SmallConfig(2, 1), std::move(task));
  env.Reset();
  const int last = env.obs_dim() - 1;
  EXPECT_EQ(env.observations()[last], 1.0f);
  const std::vector<float> before(env.observations(), env.observations() + 2 * env.obs_dim());
  goal->goal = 5.0;
  env.RefreshTaskObservation(1);
  EXPECT_EQ(env.observations()[env.obs_dim() + last], 5.0f);
  EXPECT_EQ(env.observations()[last], 1.0f) << "other envs keep their rows";
  for (int k = 0; k < last; ++k)
    EXPECT_EQ(env.observations()[env.obs_dim() + k], before[env.obs_dim() + k]) << k;
}

TEST(EnvTest, Dimensions) {
  BatchedEnv env(MakeHumanoid(), SmallConfig(3, 1));
  EXPECT_EQ(env.obs_dim(), 223);
  EXPECT_EQ(env.amp_obs_dim(), 1250);
  EXPECT_EQ(env.action_dim(), 28);
  EXPECT_NEAR(env.control_dt(), 1.0 / 30.0, 1e-9);
}

TEST(EnvTest, ConfigValidationNamesField) {
  EnvConfig c;
  c.num_envs = 0;
  try {
    BatchedEnv env(MakeHumanoid(), c);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("num_envs"), std::string::npos);
  }
}

// action_smoothing blends each step's PD targets with those held before (after a reset: the
// initial pose's), α·held + (1 − α)·new, per env; a snapshot carries the held targets, so a
// smoothed run resumes bit-exactly; out-of-range values are refused by name.
TEST(EnvTest, ActionSmoothingBlendsWithTheHeldTargets) {
  EnvConfig c = SmallConfig(2, 1);
  c.action_smoothing = 0.5;
  BatchedEnv env(MakeHumanoid(), c);
  env.Reset();
  env.set_action_smoothing(1, 0.0);
  const humanoid::Humanoid& h = *MakeHumanoid();
  auto held = [&](int i, int j) { return env.View(i).data->ctrl[h.actuator_id(j)]; };
  std::vector<double> before(humanoid::kNumDofs);
  for (int j = 0; j < humanoid::kNumDofs; ++j) before[j] = held(0, j);
  Rng rng(3);
  const std::vector<float> a = RandomActions(rng, 2, 0.5);
  std::vector<double> target(2 * humanoid::kNumDofs);
  h.ActionToTargets(a.data(), target.data());
  h.ActionToTargets(a.data() + humanoid::kNumDofs, target.data() + humanoid::kNumDofs);
  env.Step(a.data());
  for (int j = 0; j < humanoid::kNumDofs; ++j) {
    EXPECT_NEAR(held(0, j), 0.5 * before[j] + 0.5 * target[j], 1e-12) << j;
    EXPECT_EQ(held(1, j), target[humanoid::kNumDofs + j]) << "env 1 is not smoothed";
  }

  EnvConfig resumed_config = c;
  BatchedEnv resumed(MakeHumanoid(), resumed_config);
  resumed.LoadState(env.SaveState());
  resumed.set_action_smoothing(1, 0.0);
  const std::vector<float> next = RandomActions(rng, 2, 0.5);
  env.Step(next.data());
  resumed.Step(next.data());
  EXPECT_EQ(0, std::memcmp(env.observations(), resumed.observations(),
                           sizeof(float) * 2 * env.obs_dim()));

  EXPECT_THROW(env.set_action_smoothing(0, 0.95), Error);
  c.action_smoothing = -0.1;
  const std::string e = sims::testing::ErrorOf([&] { BatchedEnv bad(MakeHumanoid(), c); });
  EXPECT_NE(e.find("action_smoothing"), std::string::npos) << e;
  EXPECT_NE(e.find("[0, 0.9]"), std::string::npos) << e;
}

// A task that pays a fixed reward every step.
class FixedRewardTask : public GoalTask {
 public:
  TaskStepResult Step(const EnvView&) override {
    TaskStepResult r;
    r.reward = 0.6f;
    return r;
  }
};

// action_rate_weight pays a share of the reward for steady PD targets: (1 − w)·r_task +
// w·exp(−k·mean_j Δ_j²), Δ the new target minus the held one (after a reset: the initial
// pose); repeating an action pays the full share; out-of-range values are refused by name.
TEST(EnvTest, ActionRateSharePaysForSteadyTargets) {
  EnvConfig c = SmallConfig(1, 1);
  c.action_rate_weight = 0.25;
  c.action_rate_scale = 10.0;
  BatchedEnv env(MakeHumanoid(), c, std::make_unique<FixedRewardTask>());
  env.Reset();
  const humanoid::Humanoid& h = *MakeHumanoid();
  double mean_sq = 0;
  Rng rng(5);
  const std::vector<float> a = RandomActions(rng, 1, 0.3);
  std::vector<double> target(humanoid::kNumDofs);
  h.ActionToTargets(a.data(), target.data());
  for (int j = 0; j < humanoid::kNumDofs; ++j) {
    const double held = env.View(0).data->ctrl[h.actuator_id(j)];
    mean_sq += (target[j] - held) * (target[j] - held) / humanoid::kNumDofs;
  }
  ASSERT_GT(mean_sq, 1e-3);
  env.Step(a.data());
  ASSERT_FALSE(env.dones()[0]);
  EXPECT_NEAR(env.rewards()[0], 0.75 * 0.6 + 0.25 * std::exp(-10.0 * mean_sq), 1e-6);
  env.Step(a.data());
  EXPECT_NEAR(env.rewards()[0], 0.75 * 0.6 + 0.25, 1e-6) << "the same targets again: no jump";

  c.action_rate_weight = 1.5;
  std::string e = sims::testing::ErrorOf([&] { BatchedEnv bad(MakeHumanoid(), c); });
  EXPECT_NE(e.find("action_rate_weight"), std::string::npos) << e;
  c.action_rate_weight = 0.1;
  c.action_rate_scale = 0;
  e = sims::testing::ErrorOf([&] { BatchedEnv bad(MakeHumanoid(), c); });
  EXPECT_NE(e.find("action_rate_scale"), std::string::npos) << e;
}

// Rotating the whole world about z (positions, orientations, velocities) must leave the
// local observations unchanged.
TEST(EnvTest, ObservationsAreHeadingInvariant) {
  EnvConfig c = SmallConfig(2, 1);
  c.random_heading = false;
  c.spawn_radius = 0;
  BatchedEnv env(MakeHumanoid(), c);
  Rng rng(3);
  humanoid::HumanoidPose p;
  p.root_pos = {0.3, -0.2, 2.0};
  p.root_rot = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
               Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX());
  p.root_lin_vel = {0.5, 0.1, -0.1};
  p.root_ang_vel = {0.2, -0.3, 0.7};
  for (int i = 0; i < humanoid::kNumDofs; ++i)
    p.dof_pos[i] = rng.Uniform(-0.1, 0.1), p.dof_vel[i] = rng.Normal();
  p.dof_pos[6] = -0.6;  // arms abducted and the body in the air: no contacts, whose pyramidal
  p.dof_pos[10] = 0.6;  // friction cones would break exact rotation invariance of the physics
  env.SetState(0, p);
  ASSERT_EQ(env.data(0)->ncon, 0);
  const Eigen::AngleAxisd rz(1.9, Eigen::Vector3d::UnitZ());
  humanoid::HumanoidPose q = p;
  q.root_pos = rz * p.root_pos;
  q.root_rot = rz * p.root_rot;
  q.root_lin_vel = rz * p.root_lin_vel;
  q.root_ang_vel = rz * p.root_ang_vel;
  env.SetState(1, q);
  const float* o = env.observations();
  for (int k = 0; k < env.obs_dim(); ++k) EXPECT_NEAR(o[k], o[env.obs_dim() + k], 1e-5) << k;
  const float* a = env.amp_observations();
  for (int k = 0; k < env.amp_obs_dim(); ++k)
    EXPECT_NEAR(a[k], a[env.amp_obs_dim() + k], 1e-5) << k;
  // One step with identical actions keeps both worlds in lock-step up to round-off.
  std::vector<float> act(2 * humanoid::kNumDofs, 0.1f);
  env.Step(act.data());
  ASSERT_EQ(env.data(0)->ncon, 0);
  for (int k = 0; k < humanoid::kAmpObsStepDim; ++k)
    EXPECT_NEAR(a[k], a[env.amp_obs_dim() + k], 1e-4) << k;
}

TEST(EnvTest, AmpHistoryShiftsOneStep) {
  BatchedEnv env(MakeHumanoid(), SmallConfig(1, 1));
  Rng rng(1);
  auto act = RandomActions(rng, 1, 0.2);
  env.Step(act.data());
  std::vector<float> prev(env.amp_observations(),
                          env.amp_observations() + humanoid::kAmpObsStepDim);
  env.Step(act.data());
  const float* now = env.amp_observations();
  for (int k = 0; k < humanoid::kAmpObsStepDim; ++k)
    EXPECT_FLOAT_EQ(now[humanoid::kAmpObsStepDim + k], prev[k]);
}

TEST(EnvTest, StandingPdHoldsAndFallResets) {
  EnvConfig c = SmallConfig(2, 1);
  BatchedEnv env(MakeHumanoid(), c);
  // Env 1 starts lying on the floor: its torso and head touch the ground.
  humanoid::HumanoidPose lying;
  lying.root_pos = {0, 0, 0.12};
  lying.root_rot = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY());
  env.SetState(1, lying);
  std::vector<float> zero(2 * humanoid::kNumDofs);
  // Zero actions are PD targets at the neutral pose except elbows/knees (mid-range); hold the
  // default pose exactly instead.
  const double targets[humanoid::kNumDofs] = {0};
  env.humanoid().TargetsToAction(targets, zero.data());
  env.humanoid().TargetsToAction(targets, zero.data() + humanoid::kNumDofs);
  int fall_step = -1;
  for (int t = 0; t < 30; ++t) {
    env.Step(zero.data());
    if (env.dones()[1] && fall_step < 0) fall_step = t;
    EXPECT_EQ(env.dones()[0], 0) << "standing env must not reset at step " << t;
  }
  EXPECT_GE(fall_step, 1);
  EXPECT_EQ(env.stats().falls, 1);
  EXPECT_GT(env.pose(0).root_pos.z(), 0.8);
}

// ASE recovery episodes: with probability 1 a fall does not end the episode; the env goes
// on lying there with falls ignored for recovery_steps, then falls (and recovers) again. The
// draws come from the env's own stream, so the same seed gives the same episodes.
TEST(EnvTest, RecoveryEpisodesKeepAFallenEnvGoing) {
  humanoid::HumanoidPose lying;
  lying.root_pos = {0, 0, 0.12};
  lying.root_rot = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY());
  const double targets[humanoid::kNumDofs] = {0};
  auto run = [&](double p, std::vector<int>* done_steps, std::vector<int>* recover_steps) {
    EnvConfig c = SmallConfig(1, 1);
    c.recovery_episode_prob = p;
    c.recovery_steps = 10;
    BatchedEnv env(MakeHumanoid(), c);
    env.SetState(0, lying);
    std::vector<float> act(humanoid::kNumDofs);
    env.humanoid().TargetsToAction(targets, act.data());
    int64_t recoveries = 0;
    for (int t = 0; t < 40; ++t) {
      env.Step(act.data());
      if (env.dones()[0]) {
        done_steps->push_back(t);
        env.SetState(0, lying);
      }
      if (env.stats().recoveries > recoveries) recover_steps->push_back(t);
      recoveries = env.stats().recoveries;
    }
    return env.stats();
  };
  std::vector<int> done_off, rec_off, done_on, rec_on;
  const EnvStats off = run(0.0, &done_off, &rec_off);
  EXPECT_GT(off.falls, 0);
  EXPECT_EQ(off.recoveries, 0);
  const EnvStats on = run(1.0, &done_on, &rec_on);
  EXPECT_EQ(on.falls, 0);
  EXPECT_TRUE(done_on.empty());
  ASSERT_GE(rec_on.size(), 2u);
  EXPECT_EQ(rec_on[0], done_off[0]) << "the first fall is where it would have ended";
  for (size_t k = 1; k < rec_on.size(); ++k) EXPECT_EQ(rec_on[k] - rec_on[k - 1], 10);
  EnvConfig bad = SmallConfig(1, 1);
  bad.recovery_episode_prob = 1.5;
  EXPECT_THROW(BatchedEnv(MakeHumanoid(), bad), Error);
}

TEST(EnvTest, TimeoutTruncatesWithoutTermination) {
  EnvConfig c = SmallConfig(1, 1);
  c.episode_length = 5;
  BatchedEnv env(MakeHumanoid(), c);
  std::vector<float> act(humanoid::kNumDofs);
  const double targets[humanoid::kNumDofs] = {0};
  env.humanoid().TargetsToAction(targets, act.data());
  int dones = 0;
  for (int t = 0; t < 4; ++t) {
    env.Step(act.data());
    dones += env.dones()[0];
    EXPECT_EQ(env.terminated()[0], 0);
  }
  EXPECT_EQ(dones, 1);
  EXPECT_EQ(env.stats().timeouts, 1);
  EXPECT_EQ(env.progress(0), 0);
}

TEST(EnvTest, NanInjectionResetsOnlyThatEnv) {
  EnvConfig c = SmallConfig(3, 1);
  BatchedEnv env(MakeHumanoid(), c), reference(MakeHumanoid(), c);
  Rng rng(11);
  for (int t = 0; t < 5; ++t) {
    auto act = RandomActions(rng, 3, 0.3);
    env.Step(act.data());
    reference.Step(act.data());
  }
  env.data(1)->qvel[8] = std::nan("");
  auto act = RandomActions(rng, 3, 0.3);
  {
    testing::ScopedAllowMujocoWarnings allow;
    env.Step(act.data());
  }
  reference.Step(act.data());
  EXPECT_EQ(env.dones()[1], 1);
  EXPECT_EQ(env.terminated()[1], 1);
  EXPECT_EQ(env.stats().instabilities, 1);
  EXPECT_EQ(env.progress(1), 0);
  for (int k = 0; k < env.obs_dim(); ++k)
    ASSERT_TRUE(std::isfinite(env.observations()[env.obs_dim() + k]));
  for (int k = 0; k < env.amp_obs_dim(); ++k)
    ASSERT_TRUE(std::isfinite(env.amp_observations()[env.amp_obs_dim() + k]));
  for (int i : {0, 2}) {
    EXPECT_EQ(env.dones()[i], 0);
    EXPECT_EQ(
        0, std::memcmp(env.observations() + i * env.obs_dim(),
                       reference.observations() + i * env.obs_dim(), sizeof(float) * env.obs_dim()))
        << "env " << i << " was disturbed";
  }
}

std::vector<float> Rollout(int threads, int steps) {
  EnvConfig c = SmallConfig(6, threads);
  c.episode_length = 60;  // include resets in the window
  BatchedEnv env(MakeHumanoid(), c);
  Rng rng(99);
  std::vector<float> trace;
  for (int t = 0; t < steps; ++t) {
    auto act = RandomActions(rng, c.num_envs, 0.5);
    env.Step(act.data());
  }
  trace.assign(env.observations(), env.observations() + c.num_envs * env.obs_dim());
  trace.insert(trace.end(), env.amp_observations(),
               env.amp_observations() + c.num_envs * env.amp_obs_dim());
  return trace;
}

TEST(EnvTest, DeterministicAcrossThreadCounts) {
  const auto one = Rollout(1, 200);
  const auto two = Rollout(2, 200);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(0, std::memcmp(one.data(), two.data(), sizeof(float) * one.size()));
}

}  // namespace
}  // namespace sims::sim

namespace sims::sim {
namespace {

TEST(EnvStateTest, SaveLoadContinuesBitExactly) {
  EnvConfig c = SmallConfig(4, 2);
  c.episode_length = 40;
  BatchedEnv a(MakeHumanoid(), c);
  Rng rng(5);
  for (int t = 0; t < 30; ++t) a.Step(RandomActions(rng, 4, 0.4).data());
  const std::string snapshot = a.SaveState();
  EnvConfig other = c;
  other.seed = 1234;  // a different start must be fully overwritten by the snapshot
  BatchedEnv b(MakeHumanoid(), other);
  b.LoadState(snapshot);
  EXPECT_EQ(0, std::memcmp(a.observations(), b.observations(), sizeof(float) * 4 * a.obs_dim()));
  for (int t = 0; t < 30; ++t) {
    const auto act = RandomActions(rng, 4, 0.4);
    a.Step(act.data());
    b.Step(act.data());
  }
  EXPECT_EQ(0, std::memcmp(a.observations(), b.observations(), sizeof(float) * 4 * a.obs_dim()));
  EXPECT_EQ(0, std::memcmp(a.amp_observations(), b.amp_observations(),
                           sizeof(float) * 4 * a.amp_obs_dim()));
  EXPECT_EQ(a.stats().episodes, b.stats().episodes);
  EnvConfig fewer = c;
  fewer.num_envs = 3;
  BatchedEnv wrong(MakeHumanoid(), fewer);
  EXPECT_THROW(wrong.LoadState(snapshot), Error);
  EXPECT_THROW(b.LoadState(snapshot.substr(0, snapshot.size() / 2)), Error);
}

// Checkpoints written before the stats were count-prefixed ("SIM2": EnvStats as one raw struct,
// 6 counters, or 7 once `recoveries` was added) must still resume: the committed policies' training
// checkpoints are of that kind.
TEST(EnvStateTest, OlderSnapshotsWithRawStatsStillLoad) {
  EnvConfig c = SmallConfig(3, 2);
  BatchedEnv a(MakeHumanoid(), c);
  Rng rng(11);
  for (int t = 0; t < 12; ++t) a.Step(RandomActions(rng, 3, 0.4).data());
  ASSERT_EQ(a.stats().recoveries, 0);
  const std::string sim3 = a.SaveState();
  const size_t stats_at = sizeof(uint32_t) + 5 * sizeof(int);  // the count, then 7 counters
  int count = 0;
  std::memcpy(&count, sim3.data() + stats_at, sizeof(count));
  ASSERT_EQ(count, 7);
  const uint32_t sim2_magic = 0x53494D32;
  std::string sim2_seven = sim3;
  std::memcpy(sim2_seven.data(), &sim2_magic, sizeof(sim2_magic));
  sim2_seven.erase(stats_at, sizeof(int));
  std::string sim2_six = sim2_seven;
  sim2_six.erase(stats_at + 6 * sizeof(int64_t), sizeof(int64_t));
  for (const std::string* old : {&sim2_six, &sim2_seven}) {
    EnvConfig other = c;
    other.seed = 99;
    BatchedEnv b(MakeHumanoid(), other);
    b.LoadState(*old);
    EXPECT_EQ(b.SaveState(), sim3);  // resaved as SIM3, nothing lost
    EXPECT_EQ(b.stats().episodes, a.stats().episodes);
  }
  // A SIM3 snapshot claiming 8 counters is refused, and leaves the env as it was.
  BatchedEnv b(MakeHumanoid(), c);
  const std::string before = b.SaveState();
  std::string eight = sim3;
  count = 8;
  std::memcpy(eight.data() + stats_at, &count, sizeof(count));
  EXPECT_THROW(b.LoadState(eight), Error);
  EXPECT_EQ(b.SaveState(), before);
}

// Fuzzer findings (tools/fuzz.sh env_state): a snapshot rejected part way through left the
// first envs overwritten, and a task-state count past the end of the data asked for that many
// doubles (std::length_error / bad_alloc instead of an input error).
TEST(EnvStateTest, RejectedSnapshotLeavesTheEnvAsItWas) {
  EnvConfig c = SmallConfig(3, 2);
  BatchedEnv a(MakeHumanoid(), c);
  Rng rng(9);
  for (int t = 0; t < 10; ++t) a.Step(RandomActions(rng, 3, 0.4).data());
  const std::string snapshot = a.SaveState();
  EnvConfig other = c;
  other.seed = 77;
  BatchedEnv b(MakeHumanoid(), other);
  const std::string before = b.SaveState();
  // The last env is cut short: the first two were already applied when the error comes.
  EXPECT_THROW(b.LoadState(snapshot.substr(0, snapshot.size() - 4)), Error);
  EXPECT_EQ(b.SaveState(), before);
  // Without a task each env ends with its task-state count (0); claim 2^60 values.
  std::string huge = snapshot;
  const uint64_t count = uint64_t{1} << 60;
  std::memcpy(huge.data() + huge.size() - sizeof(count), &count, sizeof(count));
  EXPECT_THROW(b.LoadState(huge), Error);
  EXPECT_EQ(b.SaveState(), before);
  // Env 0's step count past the episode length (INT_MAX overflowed at the next step): the
  // header (magic, num_envs, nq, nv, nu, amp_history), the stats (count-prefixed), the RNG,
  // then the count.
  std::string late = snapshot;
  const size_t at = sizeof(uint32_t) + 6 * sizeof(int) + sizeof(EnvStats) + 4 * sizeof(uint64_t);
  int progress = 0;
  std::memcpy(&progress, late.data() + at, sizeof(progress));
  EXPECT_EQ(progress, a.progress(0));
  progress = std::numeric_limits<int>::max();
  std::memcpy(late.data() + at, &progress, sizeof(progress));
  EXPECT_THROW(b.LoadState(late), Error);
  EXPECT_EQ(b.SaveState(), before);
  b.LoadState(snapshot);
  EXPECT_EQ(b.SaveState(), snapshot);
}

}  // namespace
}  // namespace sims::sim

namespace sims::sim {
namespace {

TEST(ObsAblationTest, ZeroesOnlyTheWithheldSegments) {
  // Task layout: a vector (3), a 2×2 heightmap, a style z (2); two rows.
  std::vector<ObsSegment> segs(3);
  segs[0] = {"goal", ObsSegment::Kind::kVector, 0, 3, 0, 0};
  segs[1] = {"heightmap", ObsSegment::Kind::kHeightmap, 3, 4, 2, 2};
  segs[2] = {"z", ObsSegment::Kind::kStyle, 7, 2, 0, 0};
  const int dim = humanoid::kSelfObsDim + 9;
  std::vector<float> obs(2 * dim);
  for (size_t k = 0; k < obs.size(); ++k) obs[k] = 1.f + static_cast<float>(k);
  const auto run = [&](bool no_text, bool no_heightmap) {
    std::vector<float> o = obs;
    ObsAblation a;
    a.no_text = no_text;
    a.no_heightmap = no_heightmap;
    a.Apply(segs, 2, dim, o.data());
    return o;
  };
  EXPECT_EQ(run(false, false), obs);
  for (const bool text : {false, true})
    for (const bool hm : {false, true}) {
      const auto o = run(text, hm);
      for (int i = 0; i < 2; ++i)
        for (int k = 0; k < dim; ++k) {
          const int t = k - humanoid::kSelfObsDim;  // index in the task observation
          const bool zeroed = (hm && t >= 3 && t < 7) || (text && t >= 7);
          EXPECT_EQ(o[i * dim + k], zeroed ? 0.f : obs[i * dim + k]) << i << " " << k;
        }
    }
}

}  // namespace
}  // namespace sims::sim
