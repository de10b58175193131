#include "learning/amp.h"

#include <gtest/gtest.h>

#include "point_mass_env.h"

namespace sims::learning {
namespace {

NetworkConfig SmallNet() {
  NetworkConfig n;
  n.disc_hidden = {32, 32};
  return n;
}

TEST(AmpTest, GradientPenaltyMatchesFiniteDifferences) {
  torch::manual_seed(0);
  Discriminator disc(6, 0, SmallNet());
  disc->to(torch::kFloat64);
  const auto x = torch::randn({3, 6}, torch::kFloat64);
  const auto gp = GradientPenalty(disc, x, torch::Tensor()).item<double>();
  double expect = 0;
  for (int i = 0; i < 3; ++i) {
    double norm2 = 0;
    for (int k = 0; k < 6; ++k) {
      auto xp = x[i].clone().unsqueeze(0), xm = x[i].clone().unsqueeze(0);
      xp[0][k] += 1e-6;
      xm[0][k] -= 1e-6;
      const double g =
          (disc->forward(xp, {}).item<double>() - disc->forward(xm, {}).item<double>()) / 2e-6;
      norm2 += g * g;
    }
    expect += norm2 / 3;
  }
  EXPECT_NEAR(gp, expect, 1e-5 * std::max(1.0, expect));
}

TEST(AmpTest, StyleRewardIsMonotoneInLogit) {
  AmpConfig c;
  const auto r = StyleReward(torch::tensor({-5.0f, 0.0f, 5.0f}), c);
  EXPECT_LT(r[0].item<double>(), r[1].item<double>());
  EXPECT_LT(r[1].item<double>(), r[2].item<double>());
  EXPECT_NEAR(r[1].item<double>(), -std::log(0.5) * 2.0, 1e-5);
}

// The discriminator learns to tell a toy pair of clips from random transitions, and the
// conditional one also tells which clip a window belongs to.
TEST(AmpTest, DiscriminatorSeparatesDemoFromRandom) {
  torch::manual_seed(1);
  testing::ToyDemo demo;
  AmpConfig c;
  c.grad_penalty = 0.1;
  Discriminator disc(8, 4, SmallNet());
  torch::optim::Adam opt(disc->parameters(), 3e-3);
  Rng rng(2);
  const int n = 256;
  auto style_of = [&](const std::vector<int>& ids) {
    auto z = torch::zeros({static_cast<int64_t>(ids.size()), 4});
    for (size_t i = 0; i < ids.size(); ++i) z[i][ids[i]] = 1.0;
    return z;
  };
  for (int step = 0; step < 300; ++step) {
    auto pos = torch::empty({n, 8});
    std::vector<int> ids(n);
    demo.Sample(n, rng, pos.data_ptr<float>(), ids.data());
    const auto neg = torch::randn({n, 8});
    std::vector<int> neg_ids(n), wrong(n);
    for (int i = 0; i < n; ++i)
      neg_ids[i] = static_cast<int>(rng.UniformInt(2)), wrong[i] = 1 - ids[i];
    auto loss = DiscriminatorLoss(disc, pos, style_of(ids), torch::cat({neg, pos}),
                                  torch::cat({style_of(neg_ids), style_of(wrong)}), c);
    opt.zero_grad();
    loss.total.backward();
    opt.step();
  }
  torch::NoGradGuard guard;
  auto pos = torch::empty({n, 8});
  std::vector<int> ids(n), wrong(n);
  demo.Sample(n, rng, pos.data_ptr<float>(), ids.data());
  for (int i = 0; i < n; ++i) wrong[i] = 1 - ids[i];
  const double acc_demo =
      (disc->forward(pos, style_of(ids)) > 0).to(torch::kFloat32).mean().item<double>();
  const double acc_rand = (disc->forward(torch::randn({n, 8}), style_of(ids)) < 0)
                              .to(torch::kFloat32)
                              .mean()
                              .item<double>();
  const double acc_wrong =
      (disc->forward(pos, style_of(wrong)) < 0).to(torch::kFloat32).mean().item<double>();
  EXPECT_GT(acc_demo, 0.9);
  EXPECT_GT(acc_rand, 0.9);
  EXPECT_GT(acc_wrong, 0.8);
}

TEST(AmpTest, ReplayBufferFillsThenSubsamples) {
  ReplayBuffer buf(10, 3);
  Rng rng(0);
  buf.Add(torch::ones({6, 3}), torch::zeros({6}, torch::kInt64), 0.5, rng);
  EXPECT_EQ(buf.size(), 6);
  buf.Add(2 * torch::ones({100, 3}), torch::ones({100}, torch::kInt64), 0.1, rng);
  EXPECT_EQ(buf.size(), 10);
  auto [x, s] = buf.Sample(200, rng);
  EXPECT_EQ(x.size(0), 200);
  const double twos = (x.select(1, 0) == 2).to(torch::kFloat32).mean().item<double>();
  EXPECT_GT(twos, 0.4);  // ~4 fill slots + ~10 random replacements of 10 slots
}

// The conditional discriminator's negatives include real demo motion paired with a wrong z: a
// quarter of the demo windows, each with a style id other than its own, every other id used.
TEST(AmpTest, MismatchedNegativesPairRealMotionWithAnotherStyle) {
  const int64_t n = 400, styles = 5;
  const auto demo = torch::arange(n * 2, torch::kFloat32).reshape({n, 2});
  const auto demo_style = torch::arange(n, torch::kInt64).remainder(styles);
  auto neg = torch::zeros({10, 2});
  auto neg_style = torch::zeros({10}, torch::kInt64);
  Rng rng(4);
  AppendMismatchedNegatives(demo, demo_style, 0.25, styles, rng, &neg, &neg_style);
  ASSERT_EQ(neg.size(0), 10 + n / 4);
  ASSERT_EQ(neg_style.size(0), 10 + n / 4);
  EXPECT_TRUE(torch::equal(neg.slice(0, 10), demo.slice(0, 0, n / 4)));
  std::vector<int> used(styles, 0);
  for (int64_t i = 0; i < n / 4; ++i) {
    const int64_t wrong = neg_style[10 + i].item<int64_t>();
    ASSERT_GE(wrong, 0);
    ASSERT_LT(wrong, styles);
    EXPECT_NE(wrong, demo_style[i].item<int64_t>());
    ++used[wrong];
  }
  for (int s = 0; s < styles; ++s) EXPECT_GT(used[s], 5) << s;
  // One style, or no fraction: nothing to mismatch.
  AppendMismatchedNegatives(demo, demo_style, 0.25, 1, rng, &neg, &neg_style);
  AppendMismatchedNegatives(demo, demo_style, 0.0, styles, rng, &neg, &neg_style);
  EXPECT_EQ(neg.size(0), 10 + n / 4);
}

}  // namespace
}  // namespace sims::learning
