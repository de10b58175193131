// Networks of the learner (libtorch): running normalisers, the observation encoder that routes
// heightmaps through their own MLP and keeps the style embedding z un-normalised, the Gaussian
// actor with fixed log σ, the critic and the (conditional) discriminator.
// Private to src/learning (and its tests): torch types never appear in public headers.
#pragma once

#include <string>
#include <vector>

#include <torch/torch.h>

#include "sims/learning/config.h"
#include "sims/sim/task_hook.h"

namespace sims::learning {

/// Per-column count, sum and sum of squares in float64.
struct FixedOrderMoments {
  double count = 0;      ///< Rows.
  torch::Tensor sum;     ///< [d] column sums.
  torch::Tensor sum_sq;  ///< [d] column sums of squares.
};
/// Moments of x viewed as [rows, last dim] (a 1-d x is one column), summed row by row in a
/// fixed order so the result is the same at any thread count.
FixedOrderMoments ColumnMoments(const torch::Tensor& x);

/// rl_games RunningMeanStd: per-feature mean/variance with eps 1e-5, output clamped.
class RunningMeanStdImpl : public torch::nn::Module {
 public:
  /// `size` features; normalised values are clamped to ±clip.
  RunningMeanStdImpl(int64_t size, double clip = 5.0);
  /// Folds a batch [B, size] into the statistics (parallel Welford merge, float64).
  void Update(const torch::Tensor& x);
  /// Folds a batch given by its size, mean and population variance (float64 [size]); what
  /// Update() does after computing them, and what ranks do with all-reduced moments.
  void Merge(double n, const torch::Tensor& batch_mean, const torch::Tensor& batch_var);
  /// Merges a batch given by its column moments (what Update() and all-reduced ranks have).
  void MergeMoments(const FixedOrderMoments& m);
  /// Caps the sample count at `count` (later batches then weigh in at once) and restarts the
  /// inputs whose variance is below `constant_var` at mean 0, variance 1 (a warm start from
  /// another task, where those inputs never varied). Returns how many inputs restarted.
  int64_t Soften(double count, double constant_var);
  /// Caps the sample count of features [offset, offset + size) only.
  void CapCount(int64_t offset, int64_t size, double count);
  /// Files written before per-feature counts hold one count: spread it over the features.
  void PerFeatureCount();
  /// Copies `size` features' statistics from `src` (at src_offset) to this one (at
  /// dst_offset), and takes src's sample count: a warm start from another observation layout.
  void ImportColumns(const RunningMeanStdImpl& src, int64_t src_offset, int64_t dst_offset,
                     int64_t size);
  /// Feature count.
  int64_t size() const { return mean_.size(0); }
  /// Restarts the features offset + i where mask[i] (bool [n]) at mean 0, variance 1.
  void ResetColumns(int64_t offset, const torch::Tensor& mask);
  /// Per-feature variance (float64 [size]).
  const torch::Tensor& var() const { return var_; }
  /// (x − mean) / sqrt(var + eps), clamped.
  torch::Tensor Normalize(const torch::Tensor& x) const;
  /// x · sqrt(var + eps) + mean (for value de-normalisation).
  torch::Tensor Denormalize(const torch::Tensor& x) const;
  /// Number of samples folded in so far (the smallest per-feature count).
  double count() const { return count_.min().item<double>(); }

 private:
  torch::Tensor mean_, var_, count_;
  double clip_;
};
TORCH_MODULE(RunningMeanStd);

/// A plain MLP with a configurable activation; the last layer is linear.
class MlpImpl : public torch::nn::Module {
 public:
  /// in → hidden... → out (out ≤ 0 means: end after the last hidden layer, activated).
  MlpImpl(int64_t in, const std::vector<int>& hidden, int64_t out, const std::string& activation);
  /// Forward pass.
  torch::Tensor forward(torch::Tensor x);
  /// Output width.
  int64_t out_dim() const { return out_dim_; }
  /// The linear layers in order (for weight decay and logit regularisation).
  const std::vector<torch::nn::Linear>& layers() const { return layers_; }

 private:
  std::vector<torch::nn::Linear> layers_;
  std::string activation_;
  bool final_linear_;
  int64_t out_dim_;
};
TORCH_MODULE(Mlp);

/// Routes a (normalised) observation: vector segments pass through, heightmaps go through
/// their own MLP, style segments (z) are taken from the raw observation.
class ObsEncoderImpl : public torch::nn::Module {
 public:
  /// `segments` cover the whole observation (self observation first).
  ObsEncoderImpl(const std::vector<sim::ObsSegment>& segments, const NetworkConfig& config);
  /// normalised, raw: [B, obs_dim] → features [B, out_dim()].
  torch::Tensor forward(const torch::Tensor& normalised, const torch::Tensor& raw);
  /// Feature width.
  int64_t out_dim() const { return out_dim_; }

 private:
  std::vector<sim::ObsSegment> segments_;
  std::vector<Mlp> heightmap_encoders_;
  int64_t out_dim_ = 0;
};
TORCH_MODULE(ObsEncoder);

/// Separate actor and critic (ASE), each with its own encoder.
class ActorCriticImpl : public torch::nn::Module {
 public:
  /// Builds both networks for an observation layout and action width.
  ActorCriticImpl(const std::vector<sim::ObsSegment>& segments, int64_t action_dim,
                  const NetworkConfig& config);
  /// Action mean μ [B, A] from normalised + raw observations.
  torch::Tensor Mean(const torch::Tensor& normalised, const torch::Tensor& raw);
  /// Value [B] (in the critic's normalised units when value normalisation is on).
  torch::Tensor Value(const torch::Tensor& normalised, const torch::Tensor& raw);
  /// Fixed log σ.
  double log_std() const { return log_std_; }
  /// Sets the bias of the actor's output layer (the mean action of the fresh policy).
  void SetInitialActionMean(const std::vector<float>& mean);

 private:
  ObsEncoder actor_encoder_{nullptr}, critic_encoder_{nullptr};
  Mlp actor_{nullptr}, critic_{nullptr};
  double log_std_;
};
TORCH_MODULE(ActorCritic);

/// AMP discriminator D(s_window[, z]) → logit; conditional when style_dim > 0.
class DiscriminatorImpl : public torch::nn::Module {
 public:
  /// amp_dim input (normalised AMP window) plus style_dim (0 = unconditional).
  DiscriminatorImpl(int64_t amp_dim, int64_t style_dim, const NetworkConfig& config);
  /// Logits [B].
  torch::Tensor forward(const torch::Tensor& amp, const torch::Tensor& style);
  /// Squared norm of the logit layer's weights (logit regularisation).
  torch::Tensor LogitWeightNorm() const;
  /// Σ‖W‖² over all weight matrices (weight decay; biases excluded).
  torch::Tensor WeightNorm() const;
  /// Style width (0 = unconditional).
  int64_t style_dim() const { return style_dim_; }

 private:
  Mlp trunk_{nullptr};
  torch::nn::Linear logit_{nullptr};
  int64_t style_dim_;
};
TORCH_MODULE(Discriminator);

/// Σ x over all elements in an order that does not depend on the thread count (torch's own
/// sum splits long reductions by thread); differentiable.
torch::Tensor StableSum(const torch::Tensor& x);
/// clip_grad_norm_ with a thread-count-independent norm: scales the gradients of `params` so
/// their joint norm is at most max_norm (factor max_norm / (norm + 1e-6)); returns the norm.
double ClipGradNorm(const std::vector<torch::Tensor>& params, double max_norm);

/// Total width of a segment list.
int64_t ObsWidth(const std::vector<sim::ObsSegment>& segments);

/// Where each segment's features land in an ObsEncoder's output: {first column, width} per
/// segment (heightmaps: their encoder's output width).
std::vector<std::pair<int64_t, int64_t>> EncoderColumns(
    const std::vector<sim::ObsSegment>& segments, const NetworkConfig& config);

/// What ImportAcrossLayouts did.
struct LayoutImport {
  std::vector<std::string> new_segments;  ///< Segments the source did not have.
  int64_t silenced = 0;  ///< Shared task inputs that were near-constant in the source.
};

/// Initialises `dst` (with normaliser dst_norm, layout dst_segments) from a policy trained on
/// another layout (`src`, src_norm, src_segments) with the same network config: parameters of
/// equal name and shape are copied; the first layer of the actor and critic MLPs takes the
/// input columns of segments present in both (same name, kind and size) and zero weights for
/// the new ones, so the warm-started policy acts as the source did; the normaliser takes the
/// shared segments' statistics, the new ones start at mean 0, variance 1. Task inputs (all but
/// "self" and style segments) whose source variance is below `quiet_var` are treated as new
/// too (zero weights in the layer that reads them, fresh statistics): a walk policy saw its
/// pelvis-goal height and flat-floor heightmap barely move, and the new task's values would
/// otherwise hit the normaliser's clip bound through weights trained on that noise. Throws
/// sims::Error when a parameter cannot be matched.
LayoutImport ImportAcrossLayouts(ActorCritic& src, RunningMeanStd& src_norm,
                                 const std::vector<sim::ObsSegment>& src_segments, ActorCritic& dst,
                                 RunningMeanStd& dst_norm,
                                 const std::vector<sim::ObsSegment>& dst_segments,
                                 const NetworkConfig& config, double quiet_var = 0);

}  // namespace sims::learning
