#include "sims/learning/train_run.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "common/tiny_training.h"
#include "sims/core/error.h"
#include "sims/io/training_report.h"

namespace sims::learning {
namespace {

// A walk run small enough for a unit test, three iterations with a checkpoint after the second.
TrainConfig TinyWalk() {
  TrainConfig c = sims::testing::TinyTrainConfig("walk");
  c.checkpoint_every = 2;
  c.iterations = 3;
  return c;
}

std::vector<std::string> ReadLines(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

int Column(const io::CsvTable& t, const std::string& name) {
  for (size_t i = 0; i < t.columns.size(); ++i)
    if (t.columns[i] == name) return static_cast<int>(i);
  ADD_FAILURE() << "no column " << name;
  return 0;
}

// log.csv carries the end-to-end rate and the time split of every iteration, the same figures
// the observer (bench_train) receives; the row after a checkpoint carries its logging time.
TEST(TrainRunTest, LogsEndToEndRateAndTimeSplit) {
  const auto dir = sims::testing::TempDir("train_run");
  TrainOptions o;
  o.out_dir = dir;
  std::vector<IterationTiming> seen;
  o.on_iteration = [&](const IterationStats& s, const IterationTiming& t) {
    EXPECT_GT(s.env_seconds, 0);
    EXPECT_GT(s.inference_seconds, 0);
    EXPECT_GT(s.ppo_seconds, 0);
    EXPECT_EQ(s.disc_seconds, 0);  // AMP off
    EXPECT_LE(s.env_seconds + s.inference_seconds + s.ppo_seconds, s.iteration_seconds);
    EXPECT_GE(t.interval_seconds, s.iteration_seconds);
    EXPECT_NEAR(t.samples_per_s * t.interval_seconds, 8.0, 1e-9);
    seen.push_back(t);
  };
  EXPECT_EQ(RunTraining(TinyWalk(), o), 3);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].logging_seconds, 0);
  EXPECT_GT(seen[2].logging_seconds, 0);  // the checkpoint after iteration 2
  const io::CsvTable t = io::ReadCsvTable(dir / "log.csv");
  ASSERT_EQ(t.rows(), 3);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(t.values[Column(t, "samples_per_s")][r], seen[r].samples_per_s,
                1e-6 * seen[r].samples_per_s);
    EXPECT_GT(t.values[Column(t, "env_seconds")][r], 0);
    EXPECT_GT(t.values[Column(t, "ppo_seconds")][r], 0);
  }
  EXPECT_GT(t.values[Column(t, "logging_seconds")][2], 0);
  // Falls, force terminations and success by start kind are separate columns.
  for (const char* name : {"fall_rate", "force_end_rate", "reference_start_share",
                           "success_rate_reference", "success_rate_default"})
    EXPECT_GE(Column(t, name), 0) << name;
  // Walk runs no curriculum: its level column is empty (NaN).
  for (int r = 0; r < 3; ++r) EXPECT_TRUE(std::isnan(t.values[Column(t, "curriculum_level")][r]));
}

// An object skill with the spawn curriculum logs its envs' mean level: every env starts at
// level 0 and a level moves by at most one step per episode.
TEST(TrainRunTest, LogsTheCurriculumLevel) {
  const auto dir = sims::testing::TempDir("train_run_level");
  TrainConfig c = sims::testing::TinyTrainConfig("sit");
  c.skill.object.spawn_curriculum = true;
  c.skill.object.spawn_curriculum_step = 0.1;
  c.skill.reference_init_prob = 0;
  c.iterations = 2;
  TrainOptions o;
  o.out_dir = dir;
  EXPECT_EQ(RunTraining(c, o), 2);
  const io::CsvTable t = io::ReadCsvTable(dir / "log.csv");
  ASSERT_EQ(t.rows(), 2);
  for (int r = 0; r < 2; ++r) {
    const double level = t.values[Column(t, "curriculum_level")][r];
    EXPECT_GE(level, 0.0);
    EXPECT_LE(level, 0.1 + 1e-12);
  }
}

// A run logged by an older train_policy (fewer trailing columns) resumes: the header becomes
// the current one, old rows stay (their new cells read as missing); a corrupt row is one
// project error naming the file.
TEST(TrainRunTest, ResumeMigratesAnOlderLogAndRejectsBadRows) {
  const auto dir = sims::testing::TempDir("train_run_resume");
  TrainOptions o;
  o.out_dir = dir;
  TrainConfig c = TinyWalk();
  c.iterations = 2;
  RunTraining(c, o);
  auto lines = ReadLines(dir / "log.csv");
  ASSERT_EQ(lines.size(), 3u);
  const auto cut = [](const std::string& line, int cells) {
    size_t pos = 0;
    for (int k = 0; k < cells; ++k) pos = line.find(',', pos) + 1;
    return line.substr(0, pos - 1);
  };
  {
    std::ofstream out(dir / "log.csv");
    for (const auto& l : lines) out << cut(l, 22) << "\n";  // the layout before samples_per_s
  }
  o.resume = true;
  o.iterations = 3;
  EXPECT_EQ(RunTraining(c, o), 3);
  const auto migrated = ReadLines(dir / "log.csv");
  ASSERT_EQ(migrated.size(), 4u);
  EXPECT_EQ(migrated[0], lines[0]);
  const io::CsvTable t = io::ReadCsvTable(dir / "log.csv");
  EXPECT_TRUE(std::isnan(t.values[Column(t, "samples_per_s")][0]));
  EXPECT_GT(t.values[Column(t, "samples_per_s")][2], 0);

  // A row whose iteration is not an integer: one project error naming the file, the line, the
  // column and the expectation (std::stoll threw std::invalid_argument here, or read "2.5" and
  // "1x" as 2 and 1), and the log is left as it was.
  o.iterations = 4;
  for (const std::string bad : {"not-a-number", "2.5", "1x", "", "-1", "99999999999999999999"}) {
    SCOPED_TRACE(bad);
    {
      std::ofstream out(dir / "log.csv");
      out << lines[0] << "\n" << lines[1] << "\n" << bad << ",1,2\n";
    }
    const std::string what = sims::testing::ErrorOf([&] { RunTraining(c, o); });
    EXPECT_NE(what.find("log.csv"), std::string::npos) << what;
    EXPECT_NE(what.find("line 3, column iteration"), std::string::npos) << what;
    EXPECT_NE(what.find("expected a non-negative integer"), std::string::npos) << what;
    EXPECT_NE(what.find("'" + bad + "'"), std::string::npos) << what;
    EXPECT_EQ(ReadLines(dir / "log.csv").size(), 3u);
  }

  // A row cut off by a crash (no newline yet) is dropped, not read as iteration "1".
  {
    std::ofstream out(dir / "log.csv");
    for (const auto& l : migrated) out << l << "\n";
    out << "1";
  }
  EXPECT_EQ(RunTraining(c, o), 4);
  const auto after_cut = ReadLines(dir / "log.csv");
  ASSERT_EQ(after_cut.size(), 5u);
  for (int r = 1; r <= 4; ++r) EXPECT_EQ(after_cut[r].substr(0, 2), std::to_string(r) + ",");
}

}  // namespace
}  // namespace sims::learning
