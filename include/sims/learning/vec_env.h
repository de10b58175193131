// What the learner needs from an environment and from demonstration data. No torch here:
// environments run in OpenMP loops and must not depend on libtorch.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/core/rng.h"
#include "sims/sim/env.h"

namespace sims::learning {

/// A batch of environments with [num_envs, dim] buffers (sim::BatchedEnv through SimVecEnv,
/// or small test environments).
class VecEnv {
 public:
  virtual ~VecEnv() = default;
  /// Number of environments.
  virtual int num_envs() const = 0;
  /// Observation width.
  virtual int obs_dim() const = 0;
  /// Action width.
  virtual int action_dim() const = 0;
  /// AMP observation width (0 when the env has none).
  virtual int amp_obs_dim() const = 0;
  /// Layout of the observation, covering [0, obs_dim()).
  virtual std::vector<sim::ObsSegment> obs_segments() const = 0;
  /// Resets all envs.
  virtual void Reset() = 0;
  /// Steps all envs with actions [num_envs, action_dim()].
  virtual void Step(const float* actions) = 0;
  /// Observations [num_envs, obs_dim()].
  virtual const float* observations() const = 0;
  /// Last observations of finished episodes [num_envs, obs_dim()].
  virtual const float* terminal_observations() const = 0;
  /// Rewards [num_envs].
  virtual const float* rewards() const = 0;
  /// Episode ended [num_envs].
  virtual const uint8_t* dones() const = 0;
  /// Ended by failure (no bootstrap) [num_envs].
  virtual const uint8_t* terminated() const = 0;
  /// Task success at this step [num_envs].
  virtual const uint8_t* successes() const = 0;
  /// Task accomplished at this step (success held as long as required) [num_envs]; what the
  /// log's success rate counts. Default: successes().
  virtual const uint8_t* completions() const { return successes(); }
  /// Why each episode ended at this step [num_envs], or nullptr (then a termination counts as
  /// a fall).
  virtual const sim::EndReason* end_reasons() const { return nullptr; }
  /// 1 where this step's episode began from a reference state [num_envs], or nullptr (none).
  virtual const uint8_t* reference_starts() const { return nullptr; }
  /// Mean curriculum level over the envs that run one (TaskHook::curriculum_level), or NaN.
  virtual double curriculum_level() const { return std::numeric_limits<double>::quiet_NaN(); }
  /// AMP observations of this transition [num_envs, amp_obs_dim()].
  virtual const float* amp_observations() const = 0;
  /// Action the untrained policy should output on average (empty = zeros). For the humanoid
  /// it holds the standing pose, where a zero action would bend knees and elbows to mid-range.
  virtual std::vector<float> initial_action_mean() const { return {}; }
  /// Style id of each env's current episode (conditional AMP), or nullptr.
  virtual const int* style_ids() const { return nullptr; }
  /// Serialises all per-env state so training can resume bit-exactly.
  virtual std::string SaveState() const = 0;
  /// Restores SaveState() output; throws sims::Error if it does not fit.
  virtual void LoadState(const std::string& state) = 0;
};

/// Demonstration data for the discriminator.
class DemoSource {
 public:
  virtual ~DemoSource() = default;
  /// AMP observation width of one window.
  virtual int amp_obs_dim() const = 0;
  /// Fills n demo windows [n, amp_obs_dim()] and the style id of each.
  virtual void Sample(int n, Rng& rng, float* amp_out, int* style_out) const = 0;
  /// Style embeddings z (unit, 64-d) by style id; empty for unconditional AMP.
  virtual const std::vector<Eigen::VectorXf>& style_embeddings() const = 0;
};

}  // namespace sims::learning
