#include "sims/core/rng.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sims {
namespace {

TEST(RngTest, SameSeedSameStream) {
  Rng a(42), b(42);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.NextU64(), b.NextU64());
}

TEST(RngTest, EnvSeedIsSeedPlusEnvId) {
  Rng a = Rng::ForEnv(10, 3), b(13), c = Rng::ForEnv(10, 4);
  EXPECT_EQ(a.NextU64(), b.NextU64());
  EXPECT_NE(Rng::ForEnv(10, 3).NextU64(), c.NextU64());
}

TEST(RngTest, MomentsAreRight) {
  Rng r(7);
  const int n = 200000;
  double su = 0, sn = 0, sn2 = 0;
  for (int i = 0; i < n; ++i) {
    su += r.Uniform();
    const double x = r.Normal();
    sn += x;
    sn2 += x * x;
  }
  EXPECT_NEAR(su / n, 0.5, 0.005);
  EXPECT_NEAR(sn / n, 0.0, 0.01);
  EXPECT_NEAR(sn2 / n, 1.0, 0.02);
}

TEST(RngTest, UniformIntCoversRange) {
  Rng r(1);
  int counts[5] = {0};
  for (int i = 0; i < 5000; ++i) ++counts[r.UniformInt(5)];
  for (int c : counts) EXPECT_GT(c, 850);
}

TEST(RngTest, StateRestoresStream) {
  Rng r(5);
  r.NextU64();
  const auto s = r.state();
  const uint64_t next = r.NextU64();
  Rng q;
  q.set_state(s);
  EXPECT_EQ(q.NextU64(), next);
}

}  // namespace
}  // namespace sims
