// AMP pieces: discriminator loss (BCE or LSGAN + gradient penalty + logit and weight
// regularisation), the style reward and the replay buffer of policy AMP observations.
// Private to src/learning (and its tests): torch types never appear in public headers.
#pragma once

#include <torch/torch.h>

#include "learning/networks.h"
#include "sims/core/rng.h"
#include "sims/learning/config.h"

namespace sims::learning {

/// The discriminator loss and its parts (for logging).
struct DiscLoss {
  torch::Tensor total;        ///< Weighted sum to back-propagate.
  double classification = 0;  ///< BCE or LSGAN term.
  double grad_penalty = 0;    ///< mean ‖∇ₓ D(demo)‖².
  double demo_accuracy = 0;   ///< Fraction of demo logits > 0.
  double agent_accuracy = 0;  ///< Fraction of negative logits < 0.
  double demo_logit = 0;      ///< Mean demo logit.
  double agent_logit = 0;     ///< Mean negative logit.
};

/// L = ½(ℓ(neg, 0) + ℓ(pos, 1)) + logit_reg·‖w_logit‖² + grad_penalty·mean‖∇ₓD(demo)‖²
///     + weight_decay·Σ‖W‖², ℓ = BCE or LSGAN (targets ±1). Inputs are normalised.
DiscLoss DiscriminatorLoss(Discriminator& disc, const torch::Tensor& demo,
                           const torch::Tensor& demo_style, const torch::Tensor& negative,
                           const torch::Tensor& negative_style, const AmpConfig& config);

/// SIMS conditional negatives (eq. 7): the first ⌊fraction·n⌋ demo windows, each paired with
/// another style id (uniform over the other num_styles − 1), appended to the negatives.
void AppendMismatchedNegatives(const torch::Tensor& demo, const torch::Tensor& demo_style,
                               double fraction, int64_t num_styles, Rng& rng,
                               torch::Tensor* negative, torch::Tensor* negative_style);

/// mean over the batch of ‖∇ₓ D(x, z)‖², differentiable (create_graph).
torch::Tensor GradientPenalty(Discriminator& disc, const torch::Tensor& demo,
                              const torch::Tensor& demo_style);

/// BCE: −log(max(1 − sigmoid(logit), 1e-4))·scale; LSGAN: max(0, 1 − ¼(logit − 1)²)·scale.
torch::Tensor StyleReward(const torch::Tensor& logits, const AmpConfig& config);

/// Fixed-capacity buffer of policy AMP windows (stored as float16) and their style ids.
class ReplayBuffer {
 public:
  /// `capacity` windows of `dim` floats.
  ReplayBuffer(int64_t capacity, int64_t dim);
  /// Appends n windows until full; afterwards each replaces a random slot with probability
  /// keep_prob (ASE).
  void Add(const torch::Tensor& windows, const torch::Tensor& styles, double keep_prob, Rng& rng);
  /// n windows (float32) and style ids drawn uniformly.
  std::pair<torch::Tensor, torch::Tensor> Sample(int64_t n, Rng& rng) const;
  /// Number of stored windows.
  int64_t size() const { return size_; }
  /// Storage tensors for checkpoints.
  torch::Tensor& data() { return data_; }
  /// Style ids for checkpoints.
  torch::Tensor& styles() { return styles_; }
  /// Sets the fill level after loading a checkpoint.
  void set_size(int64_t size) { size_ = size; }

 private:
  torch::Tensor data_, styles_;
  int64_t size_ = 0;
};

}  // namespace sims::learning
