#include "sims/bench/train_bench.h"

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "common/tiny_training.h"
#include "sims/core/config.h"

namespace sims::bench {
namespace {

// bench_train's figure: real iterations through RunTraining, a time split that adds up, and
// references measured in the same run.
TEST(TrainBenchTest, ReportsEndToEndRate) {
  const auto dir = sims::testing::TempDir("bench_train");
  learning::TrainConfig c = sims::testing::TinyTrainConfig("walk");
  c.checkpoint_every = 2;
  c.iterations = 3;
  SaveConfig(dir / "tiny.json", c);
  TrainBenchOptions o;
  o.config = dir / "tiny.json";
  o.iterations = 2;
  o.warmup = 1;
  const auto r = RunTrainBenchmark(o);
  EXPECT_EQ(r.at("samples").get<int64_t>(), 2 * 4 * 2);
  EXPECT_GT(r.at("samples_per_s").get<double>(), 0);
  EXPECT_NEAR(r.at("samples_per_s").get<double>() * r.at("wall_seconds").get<double>(), 16.0, 1e-6);
  double total = 0;
  for (const auto& [k, v] : r.at("time_share").items()) total += v.get<double>();
  EXPECT_NEAR(total, 1.0, 1e-9);
  EXPECT_GT(r.at("raw_mj_step_per_s").get<double>(), 0);
  EXPECT_GT(r.at("sgemm_gflops").get<double>(), 0);
  EXPECT_GT(r.at("env_vs_raw").get<double>(), 0);
}

}  // namespace
}  // namespace sims::bench
