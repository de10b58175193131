#include "learning/ppo.h"

#include <cmath>

namespace sims::learning {

torch::Tensor ComputeGae(const torch::Tensor& rewards, const torch::Tensor& values,
                         const torch::Tensor& next_values, const torch::Tensor& dones, double gamma,
                         double lambda) {
  const int64_t horizon = rewards.size(0);
  auto adv = torch::zeros_like(rewards);
  auto last = torch::zeros_like(rewards[0]);
  for (int64_t t = horizon - 1; t >= 0; --t) {
    const auto not_done = 1.0 - dones[t];
    const auto delta = rewards[t] + gamma * next_values[t] - values[t];
    last = delta + gamma * lambda * not_done * last;
    adv[t] = last;
  }
  return adv;
}

torch::Tensor GaussianLogProb(const torch::Tensor& actions, const torch::Tensor& mean,
                              double log_std) {
  const double var = std::exp(2.0 * log_std);
  const int64_t dim = actions.size(-1);
  return -0.5 * (actions - mean).pow(2).sum(-1) / var -
         static_cast<double>(dim) * (log_std + 0.5 * std::log(2.0 * M_PI));
}

torch::Tensor ClippedSurrogateLoss(const torch::Tensor& new_logp, const torch::Tensor& old_logp,
                                   const torch::Tensor& advantages, double clip) {
  const auto ratio = torch::exp(new_logp - old_logp);
  const auto a = ratio * advantages;
  const auto b = torch::clamp(ratio, 1.0 - clip, 1.0 + clip) * advantages;
  return -torch::min(a, b).mean();
}

torch::Tensor BoundsLoss(const torch::Tensor& mean) {
  const auto high = torch::clamp_min(mean - 1.0, 0.0).pow(2);
  const auto low = torch::clamp_max(mean + 1.0, 0.0).pow(2);
  return (high + low).sum(-1).mean();
}

double ClipFraction(const torch::Tensor& new_logp, const torch::Tensor& old_logp, double clip) {
  torch::NoGradGuard guard;
  const auto ratio = torch::exp(new_logp - old_logp);
  return ((ratio - 1.0).abs() > clip).to(torch::kFloat32).mean().item<double>();
}

}  // namespace sims::learning
