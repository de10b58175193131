// train_policy as separate processes on 127.0.0.1: a 2-rank run started the way a plain shell
// loop (or mpirun) starts it, a rank killed mid-run, and --resume of that run with one process.

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "common/tiny_training.h"
#include "sims/core/config.h"
#include "sims/io/subprocess.h"
#include "sims/io/training_report.h"
#include "sims/learning/distributed.h"

namespace sims::learning {
namespace {

std::string ReadText(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Starts rank `rank` of `world` with the torchrun variables, output to `log`.
std::unique_ptr<io::Subprocess> StartRank(int rank, int world, int port,
                                          const std::vector<std::string>& args,
                                          const std::filesystem::path& log) {
  std::vector<std::string> argv = {SIMS_TRAIN_POLICY_BIN};
  argv.insert(argv.end(), args.begin(), args.end());
  io::SubprocessOptions o;
  o.stdout_file = log;
  o.stderr_to_stdout = true;
  o.env = {"RANK=" + std::to_string(rank), "WORLD_SIZE=" + std::to_string(world),
           "MASTER_ADDR=127.0.0.1", "MASTER_PORT=" + std::to_string(port), "OMP_NUM_THREADS=1"};
  return std::make_unique<io::Subprocess>(argv, o);
}

std::filesystem::path WriteConfig(const std::filesystem::path& dir, int checkpoint_every) {
  auto c = sims::testing::TinyTrainConfig("walk");
  c.checkpoint_every = checkpoint_every;
  c.iterations = 2;
  const auto path = dir / "tiny_walk.json";
  SaveConfig(path, c);
  return path;
}

int Rows(const std::filesystem::path& csv) {
  return static_cast<int>(io::ReadCsvTable(csv).rows());
}

// Column `name` of a train_policy log.
std::vector<double> Column(const std::filesystem::path& csv, const std::string& name) {
  const auto t = io::ReadCsvTable(csv);
  const int c = t.Find(name);
  EXPECT_GE(c, 0) << name;
  return c < 0 ? std::vector<double>{} : t.values[c];
}

TEST(TrainPolicyRanksTest, TwoRanksOnLoopbackTrainOneRunThatRankZeroWrites) {
  const auto dir = sims::testing::TempDir("ranks_loop");
  const auto config = WriteConfig(dir, 1);
  const int port = FreeLoopbackPort();
  std::vector<std::unique_ptr<io::Subprocess>> ranks;
  for (int r = 0; r < 2; ++r)
    ranks.push_back(StartRank(
        r, 2, port,
        {"--config", config.string(), "--out", (dir / "out").string(), "--log-level", "warn"},
        dir / ("rank" + std::to_string(r) + ".log")));
  for (int r = 0; r < 2; ++r)
    EXPECT_EQ(ranks[r]->Wait(), 0) << ReadText(dir / ("rank" + std::to_string(r) + ".log"));
  const auto samples = Column(dir / "out" / "log.csv", "samples");
  ASSERT_EQ(samples.size(), 2u);
  // Both ranks' environments count: 2 ranks × 2 envs × 4 steps per iteration.
  EXPECT_EQ(samples[1], 32.0);
  EXPECT_EQ(ReadJsonFile(dir / "out" / "ranks.json")["world_size"], 2);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "checkpoint.pt"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "policy.pt"));
}

TEST(TrainPolicyRanksTest, AKilledRankEndsTheRunAndItResumesWithOneProcess) {
  const auto dir = sims::testing::TempDir("ranks_kill");
  const auto config = WriteConfig(dir, 1);
  const auto out = dir / "out";
  const int port = FreeLoopbackPort();
  const std::vector<std::string> args = {
      "--config",     config.string(), "--out",          out.string(),
      "--iterations", "100000",        "--dist-timeout", "10"};
  auto rank0 = StartRank(0, 2, port, args, dir / "rank0.log");
  auto rank1 = StartRank(1, 2, port, args, dir / "rank1.log");
  // Wait for a few logged iterations (each one is checkpointed), then kill rank 1.
  const auto t0 = std::chrono::steady_clock::now();
  while (!(std::filesystem::exists(out / "log.csv") && Rows(out / "log.csv") >= 3)) {
    ASSERT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(120))
        << ReadText(dir / "rank0.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  rank1->Kill();
  const auto killed = std::chrono::steady_clock::now();
  int code = 0;
  ASSERT_TRUE(rank0->WaitFor(30000, &code)) << "rank 0 did not stop after its peer died";
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
  EXPECT_NE(code, 0);
  EXPECT_LT(waited, 15.0) << "within the 10 s timeout (plus the iteration in flight)";
  const auto text = ReadText(dir / "rank0.log");
  EXPECT_NE(text.find("distributed training, rank 0 of 2"), std::string::npos) << text;

  // The last checkpoint stands; one process resumes it and appends after its iteration.
  io::SubprocessOptions o;
  o.stdout_file = dir / "resume.log";
  o.stderr_to_stdout = true;
  const int done = Rows(out / "log.csv");
  io::Subprocess resume({SIMS_TRAIN_POLICY_BIN, "--resume", "--out", out.string(), "--iterations",
                         std::to_string(done + 2), "--log-level", "warn"},
                        o);
  ASSERT_EQ(resume.Wait(), 0) << ReadText(dir / "resume.log");
  const auto iterations = Column(out / "log.csv", "iteration");
  const auto samples = Column(out / "log.csv", "samples");
  ASSERT_EQ(iterations.size(), static_cast<size_t>(done + 2));
  for (size_t i = 0; i < iterations.size(); ++i) EXPECT_EQ(iterations[i], i + 1.0);
  // Rows written by 2 ranks count 16 samples per iteration, the resumed ones 8.
  EXPECT_EQ(samples[1] - samples[0], 16.0);
  EXPECT_EQ(samples.back() - samples[samples.size() - 2], 8.0);
}

TEST(TrainPolicyRanksTest, MpirunLaunchesTwoRanks) {
  if (!io::ProgramAvailable("mpirun")) GTEST_SKIP() << "mpirun (openmpi-bin) not installed";
  const auto dir = sims::testing::TempDir("ranks_mpirun");
  const auto config = WriteConfig(dir, 2);
  io::SubprocessOptions o;
  o.stdout_file = dir / "mpirun.log";
  o.stderr_to_stdout = true;
  o.env = {"MASTER_PORT=" + std::to_string(FreeLoopbackPort()), "OMP_NUM_THREADS=1"};
  io::Subprocess mpi(
      {"mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", SIMS_TRAIN_POLICY_BIN,
       "--config", config.string(), "--out", (dir / "out").string(), "--log-level", "warn"},
      o);
  ASSERT_EQ(mpi.Wait(), 0) << ReadText(dir / "mpirun.log");
  EXPECT_EQ(ReadJsonFile(dir / "out" / "ranks.json")["world_size"], 2);
  EXPECT_EQ(Rows(dir / "out" / "log.csv"), 2);
}

}  // namespace
}  // namespace sims::learning
