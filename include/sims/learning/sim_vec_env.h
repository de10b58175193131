// VecEnv over the batched humanoid environment.
#pragma once

#include <memory>

#include "sims/learning/vec_env.h"

namespace sims::learning {

/// Adapts sim::BatchedEnv (and its task hook) to the learner.
class SimVecEnv : public VecEnv {
 public:
  /// Takes shared ownership of the environment.
  explicit SimVecEnv(std::shared_ptr<sim::BatchedEnv> env);
  /// The wrapped environment.
  sim::BatchedEnv& env() { return *env_; }

  int num_envs() const override { return env_->num_envs(); }
  int obs_dim() const override { return env_->obs_dim(); }
  int action_dim() const override { return env_->action_dim(); }
  int amp_obs_dim() const override { return env_->amp_obs_dim(); }
  std::vector<sim::ObsSegment> obs_segments() const override;
  void Reset() override { env_->Reset(); }
  void Step(const float* actions) override;
  const float* observations() const override { return env_->observations(); }
  const float* terminal_observations() const override { return env_->terminal_observations(); }
  const float* rewards() const override { return env_->rewards(); }
  const uint8_t* dones() const override { return env_->dones(); }
  const uint8_t* terminated() const override { return env_->terminated(); }
  const uint8_t* successes() const override { return env_->successes(); }
  const uint8_t* completions() const override { return env_->completions(); }
  const sim::EndReason* end_reasons() const override { return env_->end_reasons(); }
  const uint8_t* reference_starts() const override { return env_->reference_starts(); }
  const float* amp_observations() const override { return env_->amp_observations(); }
  const int* style_ids() const override;
  double curriculum_level() const override;
  std::vector<float> initial_action_mean() const override;
  std::string SaveState() const override { return env_->SaveState(); }
  void LoadState(const std::string& state) override { env_->LoadState(state); }

 private:
  void RefreshStyles();
  std::shared_ptr<sim::BatchedEnv> env_;
  std::vector<int> styles_;
};

}  // namespace sims::learning
