// train_policy end to end in one process on the humanoid with AMP on: killed with SIGKILL
// mid-run and continued with --resume, it ends with the same log rows and the same weights as a
// run that was never interrupted; --init-policy starts from another run's policy.

#include <chrono>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "common/tiny_training.h"
#include "sims/core/config.h"
#include "sims/io/subprocess.h"
#include "sims/motion/synthetic.h"

namespace sims::learning {
namespace {

namespace fs = std::filesystem;

std::string ReadText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Complete lines of a file another process is appending to (a torn last line does not count).
int CompleteLines(const fs::path& p) {
  const std::string text = ReadText(p);
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

std::vector<std::string> Split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string cell; std::getline(in, cell, sep);) out.push_back(cell);
  return out;
}

// The tiny walk run with AMP on: synthetic walk clips as demonstrations, a small discriminator,
// replay buffer and demo pool, a checkpoint every 2 iterations, one thread.
fs::path WriteAmpConfig(const fs::path& dir, int iterations) {
  motion::SyntheticOptions so;
  so.variants = 1;
  so.skills = {"walk"};
  const auto manifest =
      motion::WriteMotionDataset(motion::GenerateSyntheticClips(so), dir / "clips", "test clips");
  TrainConfig c = sims::testing::TinyTrainConfig("walk");
  c.skill.motion.manifest = manifest.string();
  c.skill.motion.skills = {"walk"};
  c.learner.amp.enabled = true;
  c.learner.network.disc_hidden = {8};
  c.learner.amp.replay_size = 64;
  c.learner.amp.demo_pool_size = 64;
  c.learner.amp.batch_size = 8;
  c.iterations = iterations;
  c.checkpoint_every = 2;
  const auto path = dir / "tiny_amp_walk.json";
  SaveConfig(path, c);
  return path;
}

io::SubprocessOptions LogTo(const fs::path& log) {
  io::SubprocessOptions o;
  o.stdout_file = log;
  o.stderr_to_stdout = true;
  o.env = {"OMP_NUM_THREADS=1"};
  return o;
}

std::vector<std::string> TrainArgs(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {SIMS_TRAIN_POLICY_BIN, "--threads", "1", "--log-level", "warn"};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

int Train(const std::vector<std::string>& args, const fs::path& log) {
  io::Subprocess p(TrainArgs(args), LogTo(log));
  return p.Wait();
}

// log.csv rows with the wall-clock columns blanked: the rest must match bit for bit.
std::vector<std::string> DeterministicRows(const fs::path& csv) {
  std::vector<std::string> rows = Split(ReadText(csv), '\n');
  EXPECT_FALSE(rows.empty());
  if (rows.empty()) return rows;
  const auto header = Split(rows[0], ',');
  for (size_t r = 1; r < rows.size(); ++r) {
    auto cells = Split(rows[r], ',');
    EXPECT_EQ(cells.size(), header.size()) << csv << " row " << r;
    std::string kept;
    for (size_t c = 0; c < cells.size() && c < header.size(); ++c) {
      const std::string& h = header[c];
      const bool timing = h.find("seconds") != std::string::npos ||
                          h.find("per_s") != std::string::npos || h == "update_gflops";
      kept += (c ? "," : "") + (timing ? std::string("-") : cells[c]);
    }
    rows[r] = kept;
  }
  return rows;
}

// Same rows; on a difference, names the first differing row instead of printing both logs.
void ExpectSameRows(const std::vector<std::string>& got, const std::vector<std::string>& want) {
  EXPECT_EQ(got.size(), want.size());
  for (size_t r = 0; r < std::min(got.size(), want.size()); ++r)
    if (got[r] != want[r]) {
      ADD_FAILURE() << "log row " << r << " differs:\n  got  " << got[r] << "\n  want " << want[r];
      return;
    }
}

TEST(TrainPolicyResumeTest, KilledAmpRunResumesToTheUninterruptedResult) {
  const auto dir = sims::testing::TempDir("resume_amp");
  const int kIterations = 24;
  const auto config = WriteAmpConfig(dir, kIterations);
  const std::vector<std::string> common = {"--config", config.string()};

  auto args = common;
  args.insert(args.end(), {"--out", (dir / "straight").string()});
  ASSERT_EQ(Train(args, dir / "straight.log"), 0) << ReadText(dir / "straight.log");

  // The same command, killed (SIGKILL) once a checkpoint exists and the log has moved past it.
  const auto out = dir / "killed";
  args = common;
  args.insert(args.end(), {"--out", out.string()});
  {
    io::Subprocess run(TrainArgs(args), LogTo(dir / "killed.log"));
    const auto t0 = std::chrono::steady_clock::now();
    while (!(fs::exists(out / "checkpoint.pt") && CompleteLines(out / "log.csv") >= 4)) {
      int code = 0;
      ASSERT_FALSE(run.WaitFor(0, &code))
          << "exited (" << code << ") " << ReadText(dir / "killed.log");
      ASSERT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(120))
          << ReadText(dir / "killed.log");
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    int code = 0;
    ASSERT_FALSE(run.WaitFor(0, &code)) << "the run ended (" << code << ") before it was killed";
    run.Kill();
  }
  const int logged = CompleteLines(out / "log.csv") - 1;
  ASSERT_LT(logged, kIterations) << "killed too late to test anything";

  ASSERT_EQ(Train({"--resume", "--out", out.string()}, dir / "resume.log"), 0)
      << ReadText(dir / "resume.log");
  const auto straight_rows = DeterministicRows(dir / "straight" / "log.csv");
  const auto resumed_rows = DeterministicRows(out / "log.csv");
  ASSERT_EQ(straight_rows.size(), kIterations + 1u);
  ExpectSameRows(resumed_rows, straight_rows);
  EXPECT_TRUE(ReadText(out / "policy.pt") == ReadText(dir / "straight" / "policy.pt"))
      << "policy.pt differs";
  // checkpoint.pt cannot be compared byte for byte (libtorch keys the optimiser state by
  // tensor addresses); the rest of the learner state (optimiser moments, discriminator, replay
  // buffer, RNG, environment state) must agree too, so both runs continue for 3 iterations.
  for (const auto& run : {dir / "straight", out})
    ASSERT_EQ(
        Train({"--resume", "--out", run.string(), "--iterations", std::to_string(kIterations + 3)},
              dir / "more.log"),
        0)
        << ReadText(dir / "more.log");
  ExpectSameRows(DeterministicRows(out / "log.csv"),
                 DeterministicRows(dir / "straight" / "log.csv"));
  EXPECT_TRUE(ReadText(out / "policy.pt") == ReadText(dir / "straight" / "policy.pt"))
      << "policy.pt differs after 3 more iterations";
}

// --init-policy: the run starts from the given policy's actor and critic (its first rollout
// differs from a fresh start's with the same seed) and records where it came from; a policy
// that cannot be read is an error naming it.
TEST(TrainPolicyResumeTest, InitPolicyStartsFromAnotherRunsPolicy) {
  const auto dir = sims::testing::TempDir("init_policy");
  const auto config = WriteAmpConfig(dir, 3);
  ASSERT_EQ(Train({"--config", config.string(), "--out", (dir / "a").string()}, dir / "a.log"), 0)
      << ReadText(dir / "a.log");
  const auto policy = dir / "a" / "policy.pt";
  ASSERT_EQ(Train({"--config", config.string(), "--out", (dir / "b").string(), "--iterations", "1",
                   "--init-policy", policy.string()},
                  dir / "b.log"),
            0)
      << ReadText(dir / "b.log");
  EXPECT_EQ(ReadJsonFile(dir / "b" / "init_policy.json")["policy"], policy.string());
  const auto fresh = DeterministicRows(dir / "a" / "log.csv");
  const auto init = DeterministicRows(dir / "b" / "log.csv");
  ASSERT_EQ(init.size(), 2u);
  const auto header = Split(fresh[0], ',');
  const int task_reward =
      static_cast<int>(std::find(header.begin(), header.end(), "task_reward") - header.begin());
  ASSERT_LT(task_reward, static_cast<int>(header.size()));
  EXPECT_NE(Split(init[1], ',')[task_reward], Split(fresh[1], ',')[task_reward])
      << "the first rollout did not use the initial policy";

  const auto missing = dir / "nowhere" / "policy.pt";
  EXPECT_NE(Train({"--config", config.string(), "--out", (dir / "c").string(), "--init-policy",
                   missing.string()},
                  dir / "c.log"),
            0);
  EXPECT_NE(ReadText(dir / "c.log").find(missing.string()), std::string::npos)
      << ReadText(dir / "c.log");
}

}  // namespace
}  // namespace sims::learning
