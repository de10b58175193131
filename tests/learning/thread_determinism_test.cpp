// Training gives bit-identical results at any thread count: the env loops are per-env, the
// update pads GEMM inputs to whole BLAS panels and sums its statistics in a fixed order.
#include <cstdio>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "common/tiny_training.h"
#include "sims/core/parallel.h"
#include "sims/io/training_report.h"
#include "sims/learning/train_run.h"
#include "task/task_test_util.h"

namespace sims::learning {
namespace {

std::string ReadBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Humanoid walk with AMP on synthetic walk clips, three iterations. 8 envs × 8 steps give
// 64-row minibatches and 64-unit layers: big enough that OpenBLAS runs the update's GEMMs on
// both threads (smaller ones stay on one and would hide a difference); the policy input and
// the discriminator's 10-frame window are both wider than one BLAS panel.
TrainConfig TinyAmpWalk() {
  TrainConfig c = sims::testing::TinyTrainConfig("walk");
  c.env.num_envs = 8;
  c.env.threads = 0;  // follow SetThreadCount
  c.skill.motion.manifest = task::testing::SyntheticManifest({"walk"});
  c.skill.motion.skills = {"walk"};
  c.learner.network.actor_hidden = {64};
  c.learner.network.critic_hidden = {64};
  c.learner.network.disc_hidden = {64};
  c.learner.ppo.horizon = 8;
  c.learner.ppo.minibatch_size = 64;
  c.learner.ppo.mini_epochs = 2;
  c.learner.amp.enabled = true;
  c.learner.amp.batch_size = 32;
  c.learner.amp.replay_size = 256;
  c.learner.amp.demo_pool_size = 256;
  c.iterations = 3;
  return c;
}

// Every log cell except the wall-clock ones, as text (NaN, e.g. no finished episode, compares
// equal to NaN).
std::vector<std::string> DeterministicCells(const std::filesystem::path& log) {
  const io::CsvTable t = io::ReadCsvTable(log);
  std::vector<std::string> out;
  for (size_t i = 0; i < t.columns.size(); ++i) {
    const auto& name = t.columns[i];
    if (name.find("seconds") != std::string::npos || name.find("_per_s") != std::string::npos ||
        name.find("flops") != std::string::npos)
      continue;
    for (const double v : t.values[i]) {
      char cell[64];
      std::snprintf(cell, sizeof(cell), "%s=%.17g", name.c_str(), v);
      out.push_back(cell);
    }
  }
  return out;
}

TEST(ThreadDeterminismTest, AmpWalkTrainsBitIdenticallyOnOneAndTwoThreads) {
  const int before = ThreadCount();
  std::vector<std::filesystem::path> dirs;
  for (const int threads : {1, 2}) {
    SetThreadCount(threads);
    TrainOptions o;
    o.out_dir = sims::testing::TempDir("threads" + std::to_string(threads));
    o.seed = 3;
    ASSERT_EQ(RunTraining(TinyAmpWalk(), o), 3);
    dirs.push_back(o.out_dir);
  }
  SetThreadCount(before);
  const auto cells = DeterministicCells(dirs[0] / "log.csv");
  EXPECT_EQ(cells.size(), 3u * 26u);  // 3 rows × 26 non-timing columns
  EXPECT_EQ(cells, DeterministicCells(dirs[1] / "log.csv"));
  const std::string policy = ReadBytes(dirs[0] / "policy.pt");
  ASSERT_FALSE(policy.empty());
  EXPECT_TRUE(policy == ReadBytes(dirs[1] / "policy.pt")) << "policy.pt differs";
}

}  // namespace
}  // namespace sims::learning
