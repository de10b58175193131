#include "sims/learning/sim_vec_env.h"

#include <cmath>
#include <limits>

namespace sims::learning {

SimVecEnv::SimVecEnv(std::shared_ptr<sim::BatchedEnv> env) : env_(std::move(env)) {
  styles_.assign(env_->num_envs(), -1);
  RefreshStyles();
}

std::vector<sim::ObsSegment> SimVecEnv::obs_segments() const {
  sim::ObsSegment self;
  self.name = "self";
  self.size = humanoid::kSelfObsDim;
  std::vector<sim::ObsSegment> out{self};
  if (env_->task()) {
    for (auto s : env_->task()->obs_segments()) {
      s.offset += humanoid::kSelfObsDim;
      if (s.size > 0) out.push_back(s);
    }
  }
  return out;
}

void SimVecEnv::Step(const float* actions) {
  env_->Step(actions);
  RefreshStyles();
}

std::vector<float> SimVecEnv::initial_action_mean() const {
  std::vector<float> a(humanoid::kNumDofs);
  const double standing[humanoid::kNumDofs] = {0};
  env_->humanoid().TargetsToAction(standing, a.data());
  return a;
}

const int* SimVecEnv::style_ids() const { return env_->task() ? styles_.data() : nullptr; }

double SimVecEnv::curriculum_level() const {
  double sum = 0;
  int count = 0;
  if (env_->task())
    for (int i = 0; i < env_->num_envs(); ++i) {
      const double level = env_->task()->curriculum_level(i);
      if (std::isnan(level)) continue;
      sum += level;
      ++count;
    }
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

void SimVecEnv::RefreshStyles() {
  if (!env_->task()) return;
  for (int i = 0; i < env_->num_envs(); ++i) styles_[i] = env_->task()->style_id(i);
}

}  // namespace sims::learning
