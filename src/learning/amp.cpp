#include "learning/amp.h"

namespace sims::learning {

namespace {
// mean ‖∂(Σ logits)/∂x‖² for logits already computed from x (x requires grad).
torch::Tensor PenaltyOf(const torch::Tensor& logits, const torch::Tensor& x) {
  const auto grad = torch::autograd::grad({logits.sum()}, {x}, /*grad_outputs=*/{},
                                          /*retain_graph=*/true, /*create_graph=*/true)[0];
  return grad.pow(2).sum(-1).mean();
}
}  // namespace

void AppendMismatchedNegatives(const torch::Tensor& demo, const torch::Tensor& demo_style,
                               double fraction, int64_t num_styles, Rng& rng,
                               torch::Tensor* negative, torch::Tensor* negative_style) {
  const int64_t nm = static_cast<int64_t>(fraction * demo.size(0));
  if (nm <= 0 || num_styles < 2) return;
  std::vector<int64_t> wrong(nm);
  const auto ids = demo_style.contiguous();
  const int64_t* true_ids = ids.data_ptr<int64_t>();
  for (int64_t i = 0; i < nm; ++i)
    wrong[i] = (true_ids[i] + 1 + rng.UniformInt(num_styles - 1)) % num_styles;
  *negative = torch::cat({*negative, demo.slice(0, 0, nm)});
  *negative_style = torch::cat({*negative_style, torch::tensor(wrong, torch::kInt64)});
}

torch::Tensor GradientPenalty(Discriminator& disc, const torch::Tensor& demo,
                              const torch::Tensor& demo_style) {
  auto x = demo.detach().requires_grad_(true);
  return PenaltyOf(disc->forward(x, demo_style), x);
}

DiscLoss DiscriminatorLoss(Discriminator& disc, const torch::Tensor& demo,
                           const torch::Tensor& demo_style, const torch::Tensor& negative,
                           const torch::Tensor& negative_style, const AmpConfig& config) {
  DiscLoss out;
  // One forward of the demo batch serves both the classification term and the penalty.
  const auto x = demo.detach().requires_grad_(true);
  const auto pos = disc->forward(x, demo_style);
  const auto neg = disc->forward(negative, negative_style);
  torch::Tensor cls;
  if (config.loss == "lsgan") {
    cls = 0.5 * ((pos - 1.0).pow(2).mean() + (neg + 1.0).pow(2).mean());
  } else {
    cls = 0.5 * (torch::binary_cross_entropy_with_logits(pos, torch::ones_like(pos)) +
                 torch::binary_cross_entropy_with_logits(neg, torch::zeros_like(neg)));
  }
  const auto gp = PenaltyOf(pos, x);
  out.total = cls + config.logit_reg * disc->LogitWeightNorm() + config.grad_penalty * gp +
              config.weight_decay * disc->WeightNorm();
  torch::NoGradGuard guard;
  out.classification = cls.item<double>();
  out.grad_penalty = gp.item<double>();
  out.demo_accuracy = (pos > 0).to(torch::kFloat32).mean().item<double>();
  out.agent_accuracy = (neg < 0).to(torch::kFloat32).mean().item<double>();
  out.demo_logit = pos.mean().item<double>();
  out.agent_logit = neg.mean().item<double>();
  return out;
}

torch::Tensor StyleReward(const torch::Tensor& logits, const AmpConfig& config) {
  torch::NoGradGuard guard;
  if (config.loss == "lsgan")
    return torch::clamp_min(1.0 - 0.25 * (logits - 1.0).pow(2), 0.0) * config.reward_scale;
  const auto prob = torch::sigmoid(logits);
  return -torch::log(torch::clamp_min(1.0 - prob, 1e-4)) * config.reward_scale;
}

ReplayBuffer::ReplayBuffer(int64_t capacity, int64_t dim) {
  data_ = torch::zeros({capacity, dim}, torch::kFloat16);
  styles_ = torch::full({capacity}, -1, torch::kInt64);
}

void ReplayBuffer::Add(const torch::Tensor& windows, const torch::Tensor& styles, double keep_prob,
                       Rng& rng) {
  const int64_t n = windows.size(0), capacity = data_.size(0);
  const auto w16 = windows.to(torch::kFloat16).contiguous();
  const auto s64 = styles.to(torch::kInt64).contiguous();
  std::vector<int64_t> src, dst;
  for (int64_t i = 0; i < n; ++i) {
    if (size_ < capacity) {
      src.push_back(i);
      dst.push_back(size_++);
    } else if (rng.Uniform() < keep_prob) {
      src.push_back(i);
      dst.push_back(rng.UniformInt(capacity));
    }
  }
  if (src.empty()) return;
  const auto si = torch::tensor(src, torch::kInt64), di = torch::tensor(dst, torch::kInt64);
  data_.index_copy_(0, di, w16.index_select(0, si));
  styles_.index_copy_(0, di, s64.index_select(0, si));
}

std::pair<torch::Tensor, torch::Tensor> ReplayBuffer::Sample(int64_t n, Rng& rng) const {
  std::vector<int64_t> idx(n);
  for (auto& i : idx) i = rng.UniformInt(std::max<int64_t>(size_, 1));
  const auto t = torch::tensor(idx, torch::kInt64);
  return {data_.index_select(0, t).to(torch::kFloat32), styles_.index_select(0, t)};
}

}  // namespace sims::learning
