#include "learning/networks.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sims::learning
