// The torch side of MotionTextModel, shared by the model and the trainer (private header).
#pragma once

#include <mutex>

#include <torch/torch.h>

#include "sims/language/motion_text.h"

namespace sims::language::internal {

/// Encoder, decoder, MLP_d and MLP_u, with feature normalisation as buffers.
struct MotionTextNetImpl : torch::nn::Module {
  MotionTextNetImpl(const MotionTextModelConfig& config, int text_dim);

  /// Raw windows [B, T, F] -> unit z [B, z_dim].
  torch::Tensor EncodeMotion(const torch::Tensor& x);
  /// z [B, z_dim] -> normalised-feature windows [B, T, F].
  torch::Tensor Decode(const torch::Tensor& z);
  /// Raw windows -> normalised windows (the reconstruction target).
  torch::Tensor Normalize(const torch::Tensor& x) const;
  /// Text features [B, text_dim] -> MLP_d output [B, z_dim] (not normalised).
  torch::Tensor TextDown(const torch::Tensor& t);
  /// MLP_u.
  torch::Tensor TextUp(const torch::Tensor& zt);

  MotionTextModelConfig config;
  int text_dim;
  int tokens;
  torch::nn::Linear in_proj{nullptr}, to_z{nullptr}, from_z{nullptr}, out_proj{nullptr};
  torch::Tensor cls, enc_pos, dec_pos, feat_mean, feat_std;
  torch::nn::TransformerEncoder encoder{nullptr}, decoder{nullptr};
  torch::nn::Sequential mlp_d{nullptr}, mlp_u{nullptr};
};
TORCH_MODULE(MotionTextNet);

/// MotionTextModel's state.
struct MotionTextModelState {
  MotionTextModelConfig config;
  TextEncoderConfig text_encoder;
  int text_dim = 0;
  MotionTextNet net{nullptr};
  std::mutex mutex;  // serialises inference calls on the shared module
};

/// Eigen window [T, F] -> tensor [1, T, F].
torch::Tensor WindowTensor(const Eigen::MatrixXf& window);

}  // namespace sims::language::internal

namespace sims::language {
/// Gives the trainer access to a model's network.
struct MotionTextTrainerAccess {
  static internal::MotionTextModelState& State(MotionTextModel& m);
};
}  // namespace sims::language
