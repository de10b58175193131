#include "learning/networks.h"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "sims/core/error.h"

namespace sims::learning {

namespace {
torch::Tensor Activate(const torch::Tensor& x, const std::string& name) {
  if (name == "relu") return torch::relu(x);
  if (name == "elu") return torch::elu(x);
  return torch::tanh(x);
}

// How many threads a GEMM uses changes its rounding on some CPUs and not on others: OpenBLAS
// 0.3.21 blocks the inner dimension in panels whose size and threaded split depend on the
// CPU's kernel (an Intel machine here differed only for K > 320, K % 32 != 0; an AMD EPYC for
// every K tried). So no GEMM here is ever threaded: the rows of a batch go in fixed chunks of
// kRowChunk, each chunk is one single-threaded GEMM (BLAS inside an active OpenMP region
// runs on the calling thread), the chunks run in parallel, and the weight gradient, a sum over
// rows, adds the chunks' partial products in chunk order. Every value is then computed by the same
// operations at any thread count.
constexpr int64_t kRowChunk = 128;

int64_t Chunks(int64_t rows) { return (rows + kRowChunk - 1) / kRowChunk; }

// f(c) for each chunk c in [0, n) on the process's threads. With several threads the calls run
// inside an active OpenMP region (even for one chunk), where OpenBLAS keeps to the calling
// thread; with one thread the BLAS has one thread anyway. While autograd records (a backward
// pass with create_graph, for the gradient penalty) the chunks run in order on this thread:
// the same single-threaded operations, without building one graph from several threads.
template <class F>
void ForChunks(int64_t n, const F& f) {
  const int threads = omp_get_max_threads();
  if (threads <= 1) {
    for (int64_t c = 0; c < n; ++c) f(c);
  } else if (torch::GradMode::is_enabled()) {
    // The encountering thread (number 0, whose autograd state this is) runs every chunk.
#pragma omp parallel num_threads(threads)
    if (omp_get_thread_num() == 0)
      for (int64_t c = 0; c < n; ++c) f(c);
  } else {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int64_t c = 0; c < n; ++c) f(c);
  }
}

// The row chunks f(first row, rows) of a result, concatenated.
template <class F>
torch::Tensor ByRowChunks(int64_t rows, const F& f) {
  std::vector<torch::Tensor> parts(Chunks(rows));
  ForChunks(static_cast<int64_t>(parts.size()), [&](int64_t c) {
    const int64_t r0 = c * kRowChunk;
    parts[c] = f(r0, std::min(kRowChunk, rows - r0));
  });
  return parts.size() == 1 ? parts[0] : torch::cat(parts, 0);
}

// The row chunks of a product are added in chunk order (the weight gradient, a sum over rows).
torch::Tensor SumOfChunks(std::vector<torch::Tensor>& parts) {
  for (size_t c = 1; c < parts.size(); ++c) parts[0] = parts[0] + parts[c];
  return parts[0];
}

// a · b for a [R, K], b [K, N], by row chunks of a; differentiable to any order with the
// same chunking (the gradient penalty differentiates a backward pass).
class ChunkedMatmul : public torch::autograd::Function<ChunkedMatmul> {
 public:
  static torch::Tensor forward(torch::autograd::AutogradContext* ctx, const torch::Tensor& a,
                               const torch::Tensor& b) {
    ctx->save_for_backward({a, b});
    return ByRowChunks(a.size(0),
                       [&](int64_t r0, int64_t n) { return torch::mm(a.narrow(0, r0, n), b); });
  }
  static torch::autograd::tensor_list backward(torch::autograd::AutogradContext* ctx,
                                               torch::autograd::tensor_list grads) {
    const auto saved = ctx->get_saved_variables();
    const auto& a = saved[0];
    const auto& b = saved[1];
    const auto g = grads[0];
    const int64_t rows = a.size(0);
    std::vector<torch::Tensor> parts(Chunks(rows));
    if (!torch::GradMode::is_enabled()) {
      // A plain backward: each chunk's products once, single-threaded, chunks in parallel.
      const auto bt = b.t();
      const auto ga = ByRowChunks(
          rows, [&](int64_t r0, int64_t n) { return torch::mm(g.narrow(0, r0, n), bt); });
      ForChunks(static_cast<int64_t>(parts.size()), [&](int64_t c) {
        const int64_t r0 = c * kRowChunk, n = std::min(kRowChunk, rows - r0);
        parts[c] = torch::mm(a.narrow(0, r0, n).t(), g.narrow(0, r0, n));
      });
      return {ga, SumOfChunks(parts)};
    }
    // Recorded for a second derivative: the same chunking, through this function again.
    const auto ga = ChunkedMatmul::apply(g, b.t());
    // ∂/∂b = Σ_chunks a_cᵀ g_c, each a [K, n] × [n, N] product by K-row chunks, in order.
    for (size_t c = 0; c < parts.size(); ++c) {
      const int64_t r0 = static_cast<int64_t>(c) * kRowChunk, n = std::min(kRowChunk, rows - r0);
      parts[c] = ChunkedMatmul::apply(a.narrow(0, r0, n).t(), g.narrow(0, r0, n));
    }
    return {ga, SumOfChunks(parts)};
  }
};

// x + b (b broadcast over rows) whose bias gradient sums the rows in fixed chunks.
class AddBias : public torch::autograd::Function<AddBias> {
 public:
  static torch::Tensor forward(torch::autograd::AutogradContext* ctx, const torch::Tensor& x,
                               const torch::Tensor& b) {
    ctx->saved_data["rows"] = x.size(0);
    return x + b;
  }
  static torch::autograd::tensor_list backward(torch::autograd::AutogradContext* ctx,
                                               torch::autograd::tensor_list grads) {
    const auto g = grads[0];
    const int64_t rows = ctx->saved_data["rows"].toInt();
    // Slices small enough that torch sums each on one thread.
    const int64_t slice = std::max<int64_t>(1, 16384 / std::max<int64_t>(g.size(1), 1));
    std::vector<torch::Tensor> parts;
    for (int64_t r0 = 0; r0 < rows; r0 += slice)
      parts.push_back(g.narrow(0, r0, std::min(slice, rows - r0)).sum(0));
    return {g, SumOfChunks(parts)};
  }
};

torch::Tensor ThreadStableLinear(torch::nn::Linear& layer, const torch::Tensor& x) {
  if (x.dim() != 2 || x.size(0) == 0) return layer->forward(x);
  return AddBias::apply(ChunkedMatmul::apply(x, layer->weight.t()), layer->bias);
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
    const int64_t w =
        s.kind == sim::ObsSegment::Kind::kHeightmap
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
                                 const std::vector<sim::ObsSegment>& src_segments, ActorCritic& dst,
                                 RunningMeanStd& dst_norm,
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
      const std::string name = is_map ? std::string(net) + "_encoder.heightmap" +
                                            std::to_string(map_index) + ".fc0.weight"
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
  return ThreadStableLinear(logit_, trunk_->forward(x)).squeeze(-1);
}

torch::Tensor DiscriminatorImpl::LogitWeightNorm() const {
  return StableSum(logit_->weight.pow(2));
}

torch::Tensor DiscriminatorImpl::WeightNorm() const {
  auto total = StableSum(logit_->weight.pow(2));
  for (const auto& l : trunk_->layers()) total = total + StableSum(l->weight.pow(2));
  return total;
}

torch::Tensor StableSum(const torch::Tensor& x) {
  // torch splits a sum over more than 32768 elements by thread; sum fixed slices of fewer,
  // then the partial sums in order.
  constexpr int64_t kSlice = 16384;
  const auto flat = x.reshape({-1});
  const int64_t n = flat.size(0);
  if (n <= kSlice) return flat.sum();
  std::vector<torch::Tensor> parts;
  for (int64_t i = 0; i < n; i += kSlice)
    parts.push_back(flat.narrow(0, i, std::min(kSlice, n - i)).sum());
  return torch::stack(parts).sum();
}

double ClipGradNorm(const std::vector<torch::Tensor>& params, double max_norm) {
  torch::NoGradGuard guard;
  double sq = 0;
  for (const auto& p : params)
    if (p.grad().defined()) sq += StableSum(p.grad().to(torch::kFloat64).pow(2)).item<double>();
  const double norm = std::sqrt(sq);
  const double scale = max_norm / (norm + 1e-6);
  if (scale < 1)
    for (const auto& p : params)
      if (p.grad().defined()) p.grad().mul_(scale);
  return norm;
}

}  // namespace sims::learning
