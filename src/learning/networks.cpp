#include "learning/networks.h"

#include "sims/core/error.h"

namespace sims::learning {

namespace {
torch::Tensor Activate(const torch::Tensor& x, const std::string& name) {
  if (name == "relu") return torch::relu(x);
  if (name == "elu") return torch::elu(x);
  return torch::tanh(x);
}

// OpenBLAS blocks a GEMM's inner dimension K in panels of GEMM_Q and splits the last
// remainder in (Q, 2Q) in two — rounded to its M unroll in the one-thread driver, halved in the
// threaded one — so for K > Q the partial sums, and the last bits of the product, depend on the
// thread count unless K is a multiple of 2 × unroll (measured: K > 320 and K % 32 != 0 differ
// between 1 and 2 threads on Debian's 0.3.21). Inputs up to this width need one panel.
constexpr int64_t kSinglePanelWidth = 256;
constexpr int64_t kPanelAlign = 64;  // 2 × the largest sgemm M unroll (32), a divisor of Q

// y = x W^T + b with K padded by zero columns to a multiple of kPanelAlign: the zeros add
// exact zeros, so the value is the same linear map, and its rounding no longer depends on how
// many threads the BLAS uses. The parameters keep their shapes (checkpoints load as before);
// the gradient of W is the slice of the padded weight's gradient.
torch::Tensor ThreadStableLinear(torch::nn::Linear& layer, const torch::Tensor& x) {
  const int64_t k = x.size(-1);
  if (k <= kSinglePanelWidth || k % kPanelAlign == 0) return layer->forward(x);
  const int64_t pad = kPanelAlign - k % kPanelAlign;
  const auto x_pad = torch::constant_pad_nd(x, {0, pad});
  const auto w_pad = torch::constant_pad_nd(layer->weight, {0, pad});
  return torch::nn::functional::linear(x_pad, w_pad, layer->bias);
}
}  // namespace

FixedOrderMoments ColumnMoments(const torch::Tensor& x) {
  const auto xd = x.to(torch::kFloat64).contiguous();
  const int64_t d = xd.dim() == 1 ? 1 : xd.size(-1);
  const int64_t rows = d > 0 ? xd.numel() / d : 0;
  FixedOrderMoments m;
  m.count = static_cast<double>(rows);
  m.sum = torch::zeros({d}, torch::kFloat64);
  m.sum_sq = torch::zeros({d}, torch::kFloat64);
  const double* p = xd.data_ptr<double>();
  double* s = m.sum.data_ptr<double>();
  double* q = m.sum_sq.data_ptr<double>();
  // A plain row loop: torch's reductions split long ones across threads (grain 32768), which
  // makes their rounding depend on the thread count.
  for (int64_t r = 0; r < rows; ++r, p += d)
    for (int64_t j = 0; j < d; ++j) {
      s[j] += p[j];
      q[j] += p[j] * p[j];
    }
  return m;
}

int64_t ObsWidth(const std::vector<sim::ObsSegment>& segments) {
  int64_t end = 0;
  for (const auto& s : segments) end = std::max<int64_t>(end, s.offset + s.size);
  return end;
}

std::vector<std::pair<int64_t, int64_t>> EncoderColumns(
    const std::vector<sim::ObsSegment>& segments, const NetworkConfig& config) {
  std::vector<std::pair<int64_t, int64_t>> out;
  int64_t at = 0;
  for (const auto& s : segments) {
    const int64_t w = s.kind == sim::ObsSegment::Kind::kHeightmap
                          ? (config.heightmap_hidden.empty() ? s.size : config.heightmap_hidden.back())
                          : s.size;
    out.emplace_back(at, w);
    at += w;
  }
  return out;
}

namespace {
// The segment of `list` with the same name, kind and size as `s` (−1: none).
int Matching(const std::vector<sim::ObsSegment>& list, const sim::ObsSegment& s) {
  for (size_t k = 0; k < list.size(); ++k)
    if (list[k].name == s.name && list[k].kind == s.kind && list[k].size == s.size)
      return static_cast<int>(k);
  return -1;
}
}  // namespace

LayoutImport ImportAcrossLayouts(ActorCritic& src, RunningMeanStd& src_norm,
                                 const std::vector<sim::ObsSegment>& src_segments,
                                 ActorCritic& dst, RunningMeanStd& dst_norm,
                                 const std::vector<sim::ObsSegment>& dst_segments,
                                 const NetworkConfig& config, double quiet_var) {
  torch::NoGradGuard guard;
  using Kind = sim::ObsSegment::Kind;
  const auto src_cols = EncoderColumns(src_segments, config);
  const auto dst_cols = EncoderColumns(dst_segments, config);
  LayoutImport result;
  // Per destination segment: the matching source segment and its quiet columns (a mask over
  // the segment's inputs, true = silence).
  std::vector<int> match(dst_segments.size(), -1);
  std::vector<torch::Tensor> quiet(dst_segments.size());
  for (size_t k = 0; k < dst_segments.size(); ++k) {
    const auto& d = dst_segments[k];
    match[k] = Matching(src_segments, d);
    if (match[k] < 0) {
      result.new_segments.push_back(d.name);
      continue;
    }
    const auto& sseg = src_segments[match[k]];
    quiet[k] = torch::zeros({d.size}, torch::kBool);
    if (d.kind != Kind::kStyle && d.name != "self" && quiet_var > 0)
      quiet[k] = src_norm->var().narrow(0, sseg.offset, d.size) < quiet_var;
    result.silenced += quiet[k].sum().item<int64_t>();
    if (d.kind == Kind::kStyle) continue;
    dst_norm->ImportColumns(*src_norm, sseg.offset, d.offset, d.size);
    dst_norm->ResetColumns(d.offset, quiet[k]);
  }
  const auto src_params = src->named_parameters();
  for (auto& item : dst->named_parameters()) {
    const std::string& name = item.key();
    torch::Tensor& to = item.value();
    const torch::Tensor* from = src_params.find(name);
    if (from && from->sizes() == to.sizes()) {
      to.copy_(*from);
      continue;
    }
    // The first layer after an encoder: columns follow the segments.
    if (from && (name == "actor.fc0.weight" || name == "critic.fc0.weight") && to.dim() == 2 &&
        from->dim() == 2 && from->size(0) == to.size(0)) {
      to.zero_();
      for (size_t k = 0; k < dst_segments.size(); ++k) {
        if (match[k] < 0) continue;
        to.narrow(1, dst_cols[k].first, dst_cols[k].second)
            .copy_(from->narrow(1, src_cols[match[k]].first, src_cols[match[k]].second));
      }
      continue;
    }
    ThrowInputError("warm-start policy", name, "a parameter of the same shape (same network)",
                    from ? "another shape" : "missing");
  }
  // Silence the quiet inputs where they are read: vector segments in the first MLP layer,
  // heightmaps in their encoder's first layer.
  auto params = dst->named_parameters();
  int heightmap = 0;
  for (size_t k = 0; k < dst_segments.size(); ++k) {
    const auto& d = dst_segments[k];
    const bool is_map = d.kind == Kind::kHeightmap;
    const int map_index = is_map ? heightmap++ : -1;
    if (match[k] < 0 || !quiet[k].defined() || !quiet[k].any().item<bool>()) continue;
    const auto cols = torch::nonzero(quiet[k]).flatten();
    for (const char* net : {"actor", "critic"}) {
      const std::string name =
          is_map ? std::string(net) + "_encoder.heightmap" + std::to_string(map_index) +
                       ".fc0.weight"
                 : std::string(net) + ".fc0.weight";
      torch::Tensor* w = params.find(name);
      SIMS_CHECK(w != nullptr);
      const int64_t first = is_map ? 0 : dst_cols[k].first;
      w->index_fill_(1, cols + first, 0.0);
    }
  }
  return result;
}

void RunningMeanStdImpl::ResetColumns(int64_t offset, const torch::Tensor& mask) {
  torch::NoGradGuard guard;
  if (!mask.defined() || mask.numel() == 0) return;
  const auto m = mask.to(torch::kBool);
  mean_.narrow(0, offset, m.numel()).masked_fill_(m, 0.0);
  var_.narrow(0, offset, m.numel()).masked_fill_(m, 1.0);
}

void RunningMeanStdImpl::ImportColumns(const RunningMeanStdImpl& src, int64_t src_offset,
                                       int64_t dst_offset, int64_t size) {
  torch::NoGradGuard guard;
  PerFeatureCount();
  mean_.narrow(0, dst_offset, size).copy_(src.mean_.narrow(0, src_offset, size));
  var_.narrow(0, dst_offset, size).copy_(src.var_.narrow(0, src_offset, size));
  count_.narrow(0, dst_offset, size)
      .copy_(src.count_.numel() == 1 ? src.count_.expand({size})
                                     : src.count_.narrow(0, src_offset, size));
}

RunningMeanStdImpl::RunningMeanStdImpl(int64_t size, double clip) : clip_(clip) {
  mean_ = register_buffer("mean", torch::zeros({size}, torch::kFloat64));
  var_ = register_buffer("var", torch::ones({size}, torch::kFloat64));
  // One count per feature: a warm start keeps the source's count for the inputs it shares
  // (proprioception) and restarts the task inputs (Soften on a column range).
  count_ = register_buffer("count", torch::full({size}, 1e-4, torch::kFloat64));
}

void RunningMeanStdImpl::Update(const torch::Tensor& x) {
  torch::NoGradGuard guard;
  MergeMoments(ColumnMoments(x.reshape({-1, mean_.size(0)})));
}

void RunningMeanStdImpl::MergeMoments(const FixedOrderMoments& m) {
  torch::NoGradGuard guard;
  if (m.count <= 0) return;
  const auto mean = m.sum / m.count;
  Merge(m.count, mean, torch::clamp_min(m.sum_sq / m.count - mean.pow(2), 0.0));
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

void RunningMeanStdImpl::PerFeatureCount() {
  torch::NoGradGuard guard;
  if (count_.numel() == 1 && mean_.numel() != 1)
    count_.set_(count_.expand({mean_.size(0)}).clone());
}

void RunningMeanStdImpl::CapCount(int64_t offset, int64_t size, double count) {
  torch::NoGradGuard guard;
  PerFeatureCount();
  count_.narrow(0, offset, size).clamp_max_(count);
}

int64_t RunningMeanStdImpl::Soften(double count, double constant_var) {
  torch::NoGradGuard guard;
  PerFeatureCount();
  count_.clamp_max_(count);
  const auto constant = var_ < constant_var;
  mean_.masked_fill_(constant, 0.0);
  var_.masked_fill_(constant, 1.0);
  return constant.sum().item<int64_t>();
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
    x = ThreadStableLinear(layers_[i], x);
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
