// Exponential smoothing of one character's actions (PD targets) between control steps.
//
// The bundled policies were trained without it, and their mean action changes so much from one
// 30 Hz step to the next that a standing character's feet tap in place (eval::FootSliding);
// blending each action with the one applied before damps that jitter. It is a run-time choice
// per policy (fsm::PolicySet's action_smoothing, eval_policy --action-smoothing), measured on
// held-out trials before a policy set turns it on.
#pragma once

#include <string>
#include <vector>

namespace sims::sim {

/// a_applied = α·a_previous + (1 − α)·a_policy for one character, α in [0, kMaxActionSmoothing].
class ActionFilter {
 public:
  /// A filter for `dim` action values (humanoid::kNumDofs).
  explicit ActionFilter(int dim);
  /// Replaces `action` (dim values) by its smoothed value and remembers it; α = 0, or no
  /// action since the last Reset(), passes it through unchanged.
  void Apply(double alpha, float* action);
  /// Forgets the previous action (a new episode or a reset character).
  void Reset();
  /// True once an action has passed since the last Reset().
  bool has_previous() const { return has_previous_; }

 private:
  std::vector<float> previous_;
  bool has_previous_ = false;
};

/// Largest smoothing accepted: at α → 1 the character would stop responding to its policy.
inline constexpr double kMaxActionSmoothing = 0.9;

/// Throws sims::Error naming `source` and `field` unless 0 ≤ alpha ≤ kMaxActionSmoothing.
void CheckActionSmoothing(double alpha, const std::string& source, const std::string& field);

}  // namespace sims::sim
