#include "learning/networks.h"

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "sims/core/parallel.h"

namespace sims::learning {
namespace {

TEST(NormalizerTest, MatchesBatchStatistics) {
  RunningMeanStd n(2);
  const auto a = torch::tensor({{1.0f, 10.0f}, {3.0f, 30.0f}});
  const auto b = torch::tensor({{5.0f, 50.0f}, {7.0f, 70.0f}, {9.0f, 90.0f}});
  n->Update(a);
  n->Update(b);
  // mean 5 / 50, population variance 8 / 800 over all five samples.
  const auto z = n->Normalize(torch::tensor({{5.0f + 2.0f * std::sqrt(8.0f), 50.0f}}));
  EXPECT_NEAR(z[0][0].item<double>(), 2.0, 1e-3);
  EXPECT_NEAR(z[0][1].item<double>(), 0.0, 1e-3);
  EXPECT_NEAR(n->Denormalize(torch::tensor({{1.0f, 1.0f}}))[0][1].item<double>(),
              50 + std::sqrt(800.0), 1e-2);
  EXPECT_NEAR(n->Normalize(torch::tensor({{1000.0f, 0.0f}}))[0][0].item<double>(), 5.0, 1e-6)
      << "clamped";
}

TEST(NetworksTest, EncoderRoutesSegments) {
  std::vector<sim::ObsSegment> segs(3);
  segs[0] = {"self", sim::ObsSegment::Kind::kVector, 0, 5, 0, 0};
  segs[1] = {"heightmap", sim::ObsSegment::Kind::kHeightmap, 5, 16, 4, 4};
  segs[2] = {"z", sim::ObsSegment::Kind::kStyle, 21, 3, 0, 0};
  NetworkConfig c;
  c.heightmap_hidden = {8, 6};
  ObsEncoder enc(segs, c);
  EXPECT_EQ(enc->out_dim(), 5 + 6 + 3);
  const auto raw = torch::randn({2, 24});
  const auto out = enc->forward(torch::zeros({2, 24}), raw);
  // The style slice comes from the raw observation, untouched.
  EXPECT_TRUE(torch::equal(out.slice(1, 11, 14), raw.slice(1, 21, 24)));
  ActorCritic ac(segs, 4, c);
  EXPECT_EQ(ac->Mean(torch::zeros({2, 24}), raw).sizes(), (std::vector<int64_t>{2, 4}));
  EXPECT_EQ(ac->Value(torch::zeros({2, 24}), raw).sizes(), (std::vector<int64_t>{2}));
}

// Each feature has its own count, so a warm start can restart the task inputs alone; a file
// written with one shared count spreads it over the features.
TEST(NormalizerTest, PerFeatureCountsAndLegacyFiles) {
  RunningMeanStd n(3);
  n->Update(torch::randn({100, 3}));
  n->CapCount(1, 2, 5.0);
  const auto counts = n->named_buffers()["count"];
  ASSERT_EQ(counts.numel(), 3);
  EXPECT_NEAR(counts[0].item<double>(), 100.0, 1e-3);
  EXPECT_EQ(counts[1].item<double>(), 5.0);
  EXPECT_EQ(n->count(), 5.0);
  // The next batch moves the capped features' means ~7× more than the uncapped one's.
  const auto before = n->Denormalize(torch::zeros({1, 3}));
  n->Update(torch::full({10, 3}, 10.0f));
  const auto shift = n->Denormalize(torch::zeros({1, 3})) - before;
  EXPECT_GT(shift[0][1].item<double>(), 5 * shift[0][0].item<double>());
  RunningMeanStd legacy(3);
  legacy->named_buffers()["count"].set_(torch::full({1}, 7.0, torch::kFloat64));
  legacy->PerFeatureCount();
  EXPECT_TRUE(
      torch::equal(legacy->named_buffers()["count"], torch::full({3}, 7.0, torch::kFloat64)));
}

// A warm start from another task's layout (walk → an object skill with a new "task" segment):
// the new inputs start with zero weights and unit statistics, so the warm-started networks
// act exactly as the source on the inputs they share, whatever the new inputs hold.
TEST(NetworksTest, ImportAcrossLayoutsKeepsTheSourcePolicy) {
  using Kind = sim::ObsSegment::Kind;
  const std::vector<sim::ObsSegment> src_segs = {{"self", Kind::kVector, 0, 5, 0, 0},
                                                 {"contact_goal", Kind::kVector, 5, 4, 0, 0},
                                                 {"heightmap", Kind::kHeightmap, 9, 16, 4, 4},
                                                 {"z", Kind::kStyle, 25, 3, 0, 0}};
  const std::vector<sim::ObsSegment> dst_segs = {{"self", Kind::kVector, 0, 5, 0, 0},
                                                 {"contact_goal", Kind::kVector, 5, 4, 0, 0},
                                                 {"task", Kind::kVector, 9, 6, 0, 0},
                                                 {"heightmap", Kind::kHeightmap, 15, 16, 4, 4},
                                                 {"z", Kind::kStyle, 31, 3, 0, 0}};
  NetworkConfig c;
  c.actor_hidden = {16, 16};
  c.critic_hidden = {16};
  c.heightmap_hidden = {8, 6};
  torch::manual_seed(5);
  ActorCritic src(src_segs, 4, c), dst(dst_segs, 4, c);
  {
    torch::NoGradGuard g;
    for (auto& p : src->parameters()) p.copy_(torch::randn_like(p));  // not the small init
  }
  RunningMeanStd src_norm(28), dst_norm(34);
  src_norm->Update(torch::randn({64, 28}) * 3 + 1);
  const auto imported = ImportAcrossLayouts(src, src_norm, src_segs, dst, dst_norm, dst_segs, c);
  EXPECT_EQ(imported.new_segments, std::vector<std::string>{"task"});
  EXPECT_EQ(imported.silenced, 0);
  const auto raw_src = torch::randn({8, 28}) * 2;
  const auto task = torch::randn({8, 6}) * 10;
  const auto raw_dst =
      torch::cat({raw_src.slice(1, 0, 9), task, raw_src.slice(1, 9, 28)}, 1).contiguous();
  const auto n_src = src_norm->Normalize(raw_src), n_dst = dst_norm->Normalize(raw_dst);
  EXPECT_TRUE(torch::allclose(n_dst.slice(1, 0, 9), n_src.slice(1, 0, 9)));
  EXPECT_TRUE(torch::allclose(n_dst.slice(1, 15, 31), n_src.slice(1, 9, 25)));
  // New inputs: mean 0, variance 1 (then clamped at ±5).
  EXPECT_TRUE(torch::allclose(n_dst.slice(1, 9, 15),
                              torch::clamp(task / std::sqrt(1 + 1e-5), -5, 5), 1e-4));
  EXPECT_TRUE(torch::allclose(dst->Mean(n_dst, raw_dst), src->Mean(n_src, raw_src), 1e-5, 1e-5));
  EXPECT_TRUE(torch::allclose(dst->Value(n_dst, raw_dst), src->Value(n_src, raw_src), 1e-5, 1e-5));
  // Quiet inputs: the source's contact-goal columns barely moved (variance 1e-6) and its
  // heightmap cell 0 neither; with quiet_var 1e-3 they start silent, so the warm-started
  // policy acts as the source did with those inputs at their means, whatever they hold now.
  RunningMeanStd quiet_norm(28);
  auto batch = torch::randn({256, 28}) * 3 + 1;
  batch.slice(1, 5, 9).mul_(1e-3);
  batch.slice(1, 9, 10).mul_(1e-3);
  quiet_norm->Update(batch);
  ActorCritic dst2(dst_segs, 4, c);
  RunningMeanStd dst2_norm(34);
  const auto q = ImportAcrossLayouts(src, quiet_norm, src_segs, dst2, dst2_norm, dst_segs, c, 1e-3);
  EXPECT_EQ(q.silenced, 5);
  auto at_mean = raw_src.clone();
  {
    auto mean = quiet_norm->Denormalize(torch::zeros({1, 28}));
    at_mean.slice(1, 5, 10).copy_(mean.slice(1, 5, 10).expand({8, 5}));
  }
  const auto n_mean = quiet_norm->Normalize(at_mean), n_q = dst2_norm->Normalize(raw_dst);
  EXPECT_TRUE(torch::allclose(dst2->Mean(n_q, raw_dst), src->Mean(n_mean, at_mean), 1e-4, 1e-4));
  EXPECT_TRUE(torch::allclose(n_q.slice(1, 5, 9),
                              torch::clamp(raw_dst.slice(1, 5, 9) / std::sqrt(1 + 1e-5), -5, 5)));
  // A different network cannot be imported.
  NetworkConfig other = c;
  other.actor_hidden = {32, 16};
  ActorCritic wide(dst_segs, 4, other);
  EXPECT_THROW(ImportAcrossLayouts(src, src_norm, src_segs, wide, dst_norm, dst_segs, other),
               Error);
}

// OpenBLAS splits a GEMM's inner dimension differently with one thread than with several once
// it exceeds one panel (K > 320, K % 32 != 0 here); Mlp pads such inputs so that a layer's
// output and gradients are bit-identical at any thread count. A batch this size makes OpenBLAS
// use its threads; the widths cover a padded (600, 1050) and an unpadded (256) input.
TEST(NetworksTest, MlpIsBitIdenticalAcrossThreadCounts) {
  const int before = ThreadCount();
  for (const int64_t in : {600, 1050, 256}) {
    torch::manual_seed(3);
    Mlp mlp(in, std::vector<int>{256, 128}, 4, "relu");
    const auto x = torch::randn({1024, in});
    std::vector<std::vector<torch::Tensor>> grads;
    std::vector<torch::Tensor> outs;
    for (const int threads : {1, 2}) {
      SetThreadCount(threads);
      mlp->zero_grad();
      const auto y = mlp->forward(x);
      y.pow(2).mean().backward();
      outs.push_back(y.detach().clone());
      grads.emplace_back();
      for (const auto& p : mlp->parameters()) grads.back().push_back(p.grad().clone());
    }
    EXPECT_TRUE(torch::equal(outs[0], outs[1])) << "forward, input width " << in;
    for (size_t i = 0; i < grads[0].size(); ++i)
      EXPECT_TRUE(torch::equal(grads[0][i], grads[1][i])) << "gradient " << i << ", width " << in;
  }
  SetThreadCount(before);
}

// The normaliser's batch moments are summed row by row: torch's own sum splits a long reduction
// across threads (grain 32768), which changes its last bits with the thread count.
TEST(NormalizerTest, UpdateIsBitIdenticalAcrossThreadCounts) {
  const int before = ThreadCount();
  torch::manual_seed(4);
  const auto x = torch::randn({70000, 1}) * 3.0 + 1.0;
  std::vector<torch::Tensor> means, vars;
  for (const int threads : {1, 2}) {
    SetThreadCount(threads);
    RunningMeanStd n(1);
    n->Update(x);
    means.push_back(n->named_buffers()["mean"].clone());
    vars.push_back(n->named_buffers()["var"].clone());
  }
  EXPECT_TRUE(torch::equal(means[0], means[1]));
  EXPECT_TRUE(torch::equal(vars[0], vars[1]));
  EXPECT_NEAR(means[0].item<double>(), 1.0, 0.05);
  EXPECT_NEAR(std::sqrt(vars[0].item<double>()), 3.0, 0.05);
  SetThreadCount(before);
}

// A warm start keeps what the source task learnt but lets the new task's batches weigh in at
// once, and restarts inputs that never varied there (they would sit at the clip bound).
TEST(NormalizerTest, SoftenCapsTheCountAndRestartsConstantInputs) {
  RunningMeanStd n(2);
  auto x = torch::zeros({1000, 2});
  x.select(1, 0).copy_(torch::linspace(-1.0, 1.0, 1000));  // column 1 stays 0
  for (int i = 0; i < 100; ++i) n->Update(x);
  EXPECT_EQ(n->Soften(10.0, 1e-6), 1);
  auto buffers = n->named_buffers();
  EXPECT_TRUE(torch::equal(buffers["count"], torch::full({2}, 10.0, torch::kFloat64)));
  EXPECT_DOUBLE_EQ(buffers["mean"][1].item<double>(), 0.0);
  EXPECT_DOUBLE_EQ(buffers["var"][1].item<double>(), 1.0);
  EXPECT_NEAR(buffers["var"][0].item<double>(), 1.0 / 3.0, 1e-2) << "varied input kept";
  // A new batch (column 1 now at 4) moves the mean almost all the way: 1000 / 1010.
  n->Update(torch::full({1000, 2}, 4.0));
  EXPECT_NEAR(n->named_buffers()["mean"][1].item<double>(), 4.0 * 1000.0 / 1010.0, 1e-9);
}

}  // namespace
}  // namespace sims::learning
