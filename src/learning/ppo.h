// PPO pieces as pure tensor functions (unit-tested against hand-computed values).
// Private to src/learning (and its tests): torch types never appear in public headers.
#pragma once

#include <torch/torch.h>

namespace sims::learning {

/// GAE over [T, N] tensors. next_values[t] is V(s_{t+1}), already 0 where the episode ended by
/// termination and V(terminal observation) where it ended by time-out (bootstrap);
/// dones[t] = 1 stops the recursion at t. Returns advantages [T, N].
torch::Tensor ComputeGae(const torch::Tensor& rewards, const torch::Tensor& values,
                         const torch::Tensor& next_values, const torch::Tensor& dones, double gamma,
                         double lambda);

/// log N(actions; μ, σ) summed over the action dimension, σ = exp(log_std).
torch::Tensor GaussianLogProb(const torch::Tensor& actions, const torch::Tensor& mean,
                              double log_std);

/// Clipped surrogate loss, mean over the batch: −min(r·A, clip(r, 1 ± ε)·A), r = exp(Δlogp).
torch::Tensor ClippedSurrogateLoss(const torch::Tensor& new_logp, const torch::Tensor& old_logp,
                                   const torch::Tensor& advantages, double clip);

/// Σ max(μ − 1, 0)² + min(μ + 1, 0)² over actions, mean over the batch.
torch::Tensor BoundsLoss(const torch::Tensor& mean);

/// Fraction of samples whose ratio left [1 − ε, 1 + ε].
double ClipFraction(const torch::Tensor& new_logp, const torch::Tensor& old_logp, double clip);

}  // namespace sims::learning
