// A tiny MuJoCo task for learner tests: a point mass driven by two motors must reach a random
// goal in the plane. Observation [goal − p, v]; reward exp(−2‖goal − p‖²); 50-step episodes.
// Its AMP observation is [p, v] at t and t−1, and ToyDemo supplies "clips" of smooth motion.
#pragma once

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "sims/core/rng.h"
#include "sims/humanoid/model_builder.h"
#include "sims/learning/vec_env.h"

namespace sims::learning::testing {

inline const char* kPointMassXml = R"(
<mujoco model="point_mass">
  <option timestep="0.02"/>
  <worldbody>
    <body name="mass">
      <joint name="x" type="slide" axis="1 0 0" damping="0.5"/>
      <joint name="y" type="slide" axis="0 1 0" damping="0.5"/>
      <geom type="sphere" size="0.05" mass="1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
  <actuator>
    <motor joint="x" gear="2" ctrlrange="-1 1" ctrllimited="true"/>
    <motor joint="y" gear="2" ctrlrange="-1 1" ctrllimited="true"/>
  </actuator>
</mujoco>)";

class PointMassEnv : public VecEnv {
 public:
  PointMassEnv(int n, uint64_t seed) : n_(n) {
    model_ = humanoid::LoadModelFromXml(kPointMassXml, "point mass");
    for (int i = 0; i < n; ++i) {
      data_.push_back(humanoid::MakeData(model_.get()));
      rng_.push_back(Rng::ForEnv(seed, i));
    }
    goal_.assign(2 * n, 0);
    t_.assign(n, 0);
    obs_.assign(4 * n, 0);
    term_obs_.assign(4 * n, 0);
    rew_.assign(n, 0);
    done_.assign(n, 0);
    terminated_.assign(n, 0);
    succ_.assign(n, 0);
    amp_.assign(8 * n, 0);
    prev_.assign(4 * n, 0);
    styles_.assign(n, 0);
  }
  int num_envs() const override { return n_; }
  int obs_dim() const override { return 4; }
  int action_dim() const override { return 2; }
  int amp_obs_dim() const override { return 8; }
  std::vector<sim::ObsSegment> obs_segments() const override {
    sim::ObsSegment s;
    s.name = "state";
    s.size = 4;
    return {s};
  }
  void Reset() override {
    for (int i = 0; i < n_; ++i) ResetEnv(i);
  }
  void Step(const float* a) override {
    for (int i = 0; i < n_; ++i) {
      mjData* d = data_[i].get();
      d->ctrl[0] = a[2 * i];
      d->ctrl[1] = a[2 * i + 1];
      for (int k = 0; k < 2; ++k) mj_step(model_.get(), d);
      ++t_[i];
      const double dx = goal_[2 * i] - d->qpos[0], dy = goal_[2 * i + 1] - d->qpos[1];
      rew_[i] = static_cast<float>(std::exp(-2.0 * (dx * dx + dy * dy)));
      succ_[i] = dx * dx + dy * dy < 0.01;
      done_[i] = t_[i] >= 50;
      terminated_[i] = 0;
      Observe(i);
      if (done_[i]) {
        std::memcpy(&term_obs_[4 * i], &obs_[4 * i], 4 * sizeof(float));
        ResetEnv(i);
      }
    }
  }
  const float* observations() const override { return obs_.data(); }
  const float* terminal_observations() const override { return term_obs_.data(); }
  const float* rewards() const override { return rew_.data(); }
  const uint8_t* dones() const override { return done_.data(); }
  const uint8_t* terminated() const override { return terminated_.data(); }
  const uint8_t* successes() const override { return succ_.data(); }
  const float* amp_observations() const override { return amp_.data(); }
  const int* style_ids() const override { return styles_.data(); }
  std::string SaveState() const override {
    std::string s;
    auto put = [&](const void* p, size_t b) { s.append(static_cast<const char*>(p), b); };
    for (int i = 0; i < n_; ++i) {
      const mjData* d = data_[i].get();
      put(d->qpos, 2 * sizeof(double));
      put(d->qvel, 2 * sizeof(double));
      put(d->qacc_warmstart, 2 * sizeof(double));
      const auto r = rng_[i].state();
      put(r.data(), sizeof(r));
    }
    put(goal_.data(), goal_.size() * sizeof(double));
    put(t_.data(), t_.size() * sizeof(int));
    put(obs_.data(), obs_.size() * sizeof(float));
    put(prev_.data(), prev_.size() * sizeof(float));
    put(styles_.data(), styles_.size() * sizeof(int));
    return s;
  }
  void LoadState(const std::string& s) override {
    size_t pos = 0;
    auto get = [&](void* p, size_t b) {
      std::memcpy(p, s.data() + pos, b);
      pos += b;
    };
    for (int i = 0; i < n_; ++i) {
      mjData* d = data_[i].get();
      get(d->qpos, 2 * sizeof(double));
      get(d->qvel, 2 * sizeof(double));
      get(d->qacc_warmstart, 2 * sizeof(double));
      std::array<uint64_t, 4> r;
      get(r.data(), sizeof(r));
      rng_[i].set_state(r);
    }
    get(goal_.data(), goal_.size() * sizeof(double));
    get(t_.data(), t_.size() * sizeof(int));
    get(obs_.data(), obs_.size() * sizeof(float));
    get(prev_.data(), prev_.size() * sizeof(float));
    get(styles_.data(), styles_.size() * sizeof(int));
  }

 private:
  void ResetEnv(int i) {
    mjData* d = data_[i].get();
    mj_resetData(model_.get(), d);
    goal_[2 * i] = rng_[i].Uniform(-1, 1);
    goal_[2 * i + 1] = rng_[i].Uniform(-1, 1);
    styles_[i] = static_cast<int>(rng_[i].UniformInt(2));
    t_[i] = 0;
    Observe(i);
  }
  void Observe(int i) {
    const mjData* d = data_[i].get();
    float* o = &obs_[4 * i];
    o[0] = static_cast<float>(goal_[2 * i] - d->qpos[0]);
    o[1] = static_cast<float>(goal_[2 * i + 1] - d->qpos[1]);
    o[2] = static_cast<float>(d->qvel[0]);
    o[3] = static_cast<float>(d->qvel[1]);
    float* a = &amp_[8 * i];
    const float now[4] = {static_cast<float>(d->qpos[0]), static_cast<float>(d->qpos[1]),
                          static_cast<float>(d->qvel[0]), static_cast<float>(d->qvel[1])};
    std::memcpy(a, now, sizeof(now));
    std::memcpy(a + 4, &prev_[4 * i], sizeof(now));
    std::memcpy(&prev_[4 * i], now, sizeof(now));
  }

  int n_;
  humanoid::MjModelPtr model_;
  std::vector<humanoid::MjDataPtr> data_;
  std::vector<Rng> rng_;
  std::vector<double> goal_;
  std::vector<int> t_, styles_;
  std::vector<float> obs_, term_obs_, rew_, amp_, prev_;
  std::vector<uint8_t> done_, terminated_, succ_;
};

// Two "clips": style 0 moves along +x at 0.5 m/s, style 1 circles at radius 0.5.
class ToyDemo : public DemoSource {
 public:
  ToyDemo() {
    for (int s = 0; s < 2; ++s) {
      Eigen::VectorXf z = Eigen::VectorXf::Zero(4);
      z[s] = 1.0f;
      z_.push_back(z);
    }
  }
  int amp_obs_dim() const override { return 8; }
  void Sample(int n, Rng& rng, float* out, int* style) const override {
    for (int i = 0; i < n; ++i) {
      const int s = static_cast<int>(rng.UniformInt(2));
      const double t = rng.Uniform(0, 5), dt = 0.04;
      for (int k = 0; k < 2; ++k) {
        const double tk = t - k * dt;
        float* o = out + 8 * i + 4 * k;
        if (s == 0) {
          o[0] = static_cast<float>(0.5 * tk), o[1] = 0, o[2] = 0.5f, o[3] = 0;
        } else {
          o[0] = static_cast<float>(0.5 * std::cos(tk)),
          o[1] = static_cast<float>(0.5 * std::sin(tk));
          o[2] = static_cast<float>(-0.5 * std::sin(tk)),
          o[3] = static_cast<float>(0.5 * std::cos(tk));
        }
      }
      style[i] = s;
    }
  }
  const std::vector<Eigen::VectorXf>& style_embeddings() const override { return z_; }

 private:
  std::vector<Eigen::VectorXf> z_;
};

}  // namespace sims::learning::testing
