#include "learning/ppo.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sims::learning {
namespace {

TEST(PpoTest, GaeMatchesHandComputedExample) {
  // One env, three steps; the episode times out after step 1 (bootstrap with V(terminal)=2)
  // and a new one starts at step 2.
  const double g = 0.9, l = 0.8;
  const auto r = torch::tensor({1.0f, 0.5f, 2.0f}).reshape({3, 1});
  const auto v = torch::tensor({0.5f, 1.0f, 1.5f}).reshape({3, 1});
  const auto next_v = torch::tensor({1.0f, 2.0f, 3.0f}).reshape({3, 1});
  const auto done = torch::tensor({0.0f, 1.0f, 0.0f}).reshape({3, 1});
  const auto adv = ComputeGae(r, v, next_v, done, g, l);
  const double d2 = 2.0 + g * 3.0 - 1.5;  // 5.2
  const double a2 = d2;
  const double d1 = 0.5 + g * 2.0 - 1.0;  // 1.3, episode ends: no carry from a2
  const double a1 = d1;
  const double d0 = 1.0 + g * 1.0 - 0.5;  // 1.4
  const double a0 = d0 + g * l * a1;
  EXPECT_NEAR(adv[0][0].item<double>(), a0, 1e-5);
  EXPECT_NEAR(adv[1][0].item<double>(), a1, 1e-5);
  EXPECT_NEAR(adv[2][0].item<double>(), a2, 1e-5);
}

TEST(PpoTest, ClippedSurrogateLoss) {
  const auto old_logp = torch::zeros({4});
  const auto new_logp = torch::log(torch::tensor({1.5f, 0.5f, 1.1f, 0.7f}));
  const auto adv = torch::tensor({1.0f, 1.0f, -1.0f, -2.0f});
  const double clip = 0.2;
  // min(r·A, clip(r)·A): 1.2·1, 0.5·1, 1.1·(−1), 0.8·(−2) → mean = (1.2 + 0.5 − 1.1 − 1.6)/4
  const double expect = -(1.2 + 0.5 - 1.1 - 1.6) / 4.0;
  EXPECT_NEAR(ClippedSurrogateLoss(new_logp, old_logp, adv, clip).item<double>(), expect, 1e-5);
  EXPECT_NEAR(ClipFraction(new_logp, old_logp, clip), 0.75, 1e-6);  // 1.5, 0.5, 0.7 left [0.8, 1.2]
}

TEST(PpoTest, GaussianLogProbAndBounds) {
  const auto mu = torch::tensor({{0.0f, 0.0f}});
  const auto a = torch::tensor({{1.0f, -1.0f}});
  const double log_std = std::log(0.5);
  const double expect = 2 * (-0.5 * 1.0 / 0.25 - std::log(0.5) - 0.5 * std::log(2 * M_PI));
  EXPECT_NEAR(GaussianLogProb(a, mu, log_std)[0].item<double>(), expect, 1e-5);
  EXPECT_NEAR(BoundsLoss(torch::tensor({{1.5f, -2.0f, 0.3f}})).item<double>(), 0.25 + 1.0, 1e-6);
}

}  // namespace
}  // namespace sims::learning
