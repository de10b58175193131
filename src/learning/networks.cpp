#include "learning/networks.h"

#include "sims/core/error.h"

namespace sims::learning {

namespace {
torch::Tensor Activate(const torch::Tensor& x, const std::string& name) {
  if (name == "relu") return torch::relu(x);
  if (name == "elu") return torch::elu(x);
  return torch::tanh(x);
}
}  // namespace

int64_t ObsWidth(const std::vector<sim::ObsSegment>& segments) {
  int64_t end = 0;
  for (const auto& s : segments) end = std::max<int64_t>(end, s.offset + s.size);
  return end;
}

RunningMeanStdImpl::RunningMeanStdImpl(int64_t size, double clip) : clip_(clip) {
  mean_ = register_buffer("mean", torch::zeros({size}, torch::kFloat64));
  var_ = register_buffer("var", torch::ones({size}, torch::kFloat64));
  count_ = register_buffer("count", torch::full({1}, 1e-4, torch::kFloat64));
}

void RunningMeanStdImpl::Update(const torch::Tensor& x) {
  torch::NoGradGuard guard;
  const auto xd = x.to(torch::kFloat64).reshape({-1, mean_.size(0)});
  const double n = static_cast<double>(xd.size(0));
  if (n == 0) return;
  Merge(n, xd.mean(0), xd.var(0, /*unbiased=*/false));
}

void RunningMeanStdImpl::Merge(double n, const torch::Tensor& batch_mean,
                               const torch::Tensor& batch_var) {
  torch::NoGradGuard guard;
  if (n <= 0) return;
  const auto delta = batch_mean - mean_;
  const auto total = count_ + n;
  const auto new_mean = mean_ + delta * n / total;
  const auto m2 = var_ * count_ + batch_var * n + delta.pow(2) * count_ * n / total;
  mean_.copy_(new_mean);
  var_.copy_(m2 / total);
  count_.copy_(total);
}

torch::Tensor RunningMeanStdImpl::Normalize(const torch::Tensor& x) const {
  const auto mean = mean_.to(torch::kFloat32), std = torch::sqrt(var_ + 1e-5).to(torch::kFloat32);
  return torch::clamp((x - mean) / std, -clip_, clip_);
}

torch::Tensor RunningMeanStdImpl::Denormalize(const torch::Tensor& x) const {
  const auto mean = mean_.to(torch::kFloat32), std = torch::sqrt(var_ + 1e-5).to(torch::kFloat32);
  return x * std + mean;
}

MlpImpl::MlpImpl(int64_t in, const std::vector<int>& hidden, int64_t out,
                 const std::string& activation)
    : activation_(activation), final_linear_(out > 0) {
  int64_t width = in;
  for (size_t i = 0; i < hidden.size(); ++i) {
    layers_.push_back(
        register_module("fc" + std::to_string(i), torch::nn::Linear(width, hidden[i])));
    width = hidden[i];
  }
  if (final_linear_) {
    layers_.push_back(register_module("out", torch::nn::Linear(width, out)));
    width = out;
  }
  out_dim_ = width;
}

torch::Tensor MlpImpl::forward(torch::Tensor x) {
  for (size_t i = 0; i < layers_.size(); ++i) {
    x = layers_[i]->forward(x);
    if (!(final_linear_ && i + 1 == layers_.size())) x = Activate(x, activation_);
  }
  return x;
}

ObsEncoderImpl::ObsEncoderImpl(const std::vector<sim::ObsSegment>& segments,
                               const NetworkConfig& config)
    : segments_(segments) {
  int k = 0;
  for (const auto& s : segments_) {
    if (s.kind == sim::ObsSegment::Kind::kHeightmap) {
      heightmap_encoders_.push_back(
          register_module("heightmap" + std::to_string(k++),
                          Mlp(s.size, config.heightmap_hidden, 0, config.activation)));
      out_dim_ += heightmap_encoders_.back()->out_dim();
    } else {
      out_dim_ += s.size;
    }
  }
}

torch::Tensor ObsEncoderImpl::forward(const torch::Tensor& normalised, const torch::Tensor& raw) {
  std::vector<torch::Tensor> parts;
  size_t k = 0;
  // Merge runs of plain vector segments into one slice to keep the op count low.
  int64_t run_start = -1, run_end = -1;
  auto flush = [&]() {
    if (run_start >= 0) parts.push_back(normalised.slice(1, run_start, run_end));
    run_start = run_end = -1;
  };
  for (const auto& s : segments_) {
    if (s.kind == sim::ObsSegment::Kind::kVector) {
      if (run_start >= 0 && run_end == s.offset) {
        run_end = s.offset + s.size;
      } else {
        flush();
        run_start = s.offset;
        run_end = s.offset + s.size;
      }
      continue;
    }
    flush();
    if (s.kind == sim::ObsSegment::Kind::kHeightmap)
      parts.push_back(
          heightmap_encoders_[k++]->forward(normalised.slice(1, s.offset, s.offset + s.size)));
    else
      parts.push_back(raw.slice(1, s.offset, s.offset + s.size));
  }
  flush();
  return parts.size() == 1 ? parts[0] : torch::cat(parts, 1);
}

ActorCriticImpl::ActorCriticImpl(const std::vector<sim::ObsSegment>& segments, int64_t action_dim,
                                 const NetworkConfig& config)
    : log_std_(config.action_log_std) {
  actor_encoder_ = register_module("actor_encoder", ObsEncoder(segments, config));
  critic_encoder_ = register_module("critic_encoder", ObsEncoder(segments, config));
  actor_ = register_module(
      "actor", Mlp(actor_encoder_->out_dim(), config.actor_hidden, action_dim, config.activation));
  critic_ = register_module(
      "critic", Mlp(critic_encoder_->out_dim(), config.critic_hidden, 1, config.activation));
  // Small initial action means keep the first rollouts near the PD offsets (ASE-like init).
  {
    torch::NoGradGuard guard;
    auto& last = actor_->layers().back();
    last->weight.mul_(0.01);
    last->bias.zero_();
  }
}

void ActorCriticImpl::SetInitialActionMean(const std::vector<float>& mean) {
  torch::NoGradGuard guard;
  auto& last = actor_->layers().back();
  SIMS_CHECK(static_cast<int64_t>(mean.size()) == last->bias.size(0));
  last->bias.copy_(torch::tensor(mean));
}

torch::Tensor ActorCriticImpl::Mean(const torch::Tensor& normalised, const torch::Tensor& raw) {
  return actor_->forward(actor_encoder_->forward(normalised, raw));
}

torch::Tensor ActorCriticImpl::Value(const torch::Tensor& normalised, const torch::Tensor& raw) {
  return critic_->forward(critic_encoder_->forward(normalised, raw)).squeeze(-1);
}

DiscriminatorImpl::DiscriminatorImpl(int64_t amp_dim, int64_t style_dim,
                                     const NetworkConfig& config)
    : style_dim_(style_dim) {
  trunk_ =
      register_module("trunk", Mlp(amp_dim + style_dim, config.disc_hidden, 0, config.activation));
  logit_ = register_module("logit", torch::nn::Linear(trunk_->out_dim(), 1));
  torch::NoGradGuard guard;
  // ASE initialises the logit layer uniformly in [−1, 1].
  logit_->weight.uniform_(-1.0, 1.0);
  logit_->bias.zero_();
}

torch::Tensor DiscriminatorImpl::forward(const torch::Tensor& amp, const torch::Tensor& style) {
  const auto x = style_dim_ > 0 ? torch::cat({amp, style}, 1) : amp;
  return logit_->forward(trunk_->forward(x)).squeeze(-1);
}

torch::Tensor DiscriminatorImpl::LogitWeightNorm() const { return logit_->weight.pow(2).sum(); }

torch::Tensor DiscriminatorImpl::WeightNorm() const {
  auto total = logit_->weight.pow(2).sum();
  for (const auto& l : trunk_->layers()) total = total + l->weight.pow(2).sum();
  return total;
}

}  // namespace sims::learning
