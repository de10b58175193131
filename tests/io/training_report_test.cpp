#include "sims/io/training_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <utility>

#include "common/test_util.h"
#include "sims/core/error.h"

namespace sims::io {
namespace {

// The columns train_policy logs (learning/train_run.cpp).
const std::vector<std::string> kColumns = {
    "iteration",      "samples",          "task_reward",       "style_reward",
    "total_reward",   "episode_return",   "episode_length",    "episodes",
    "success_rate",   "fall_rate",        "actor_loss",        "critic_loss",
    "bounds_loss",    "disc_loss",        "grad_penalty",      "disc_acc_demo",
    "disc_acc_agent", "clip_fraction",    "env_samples_per_s", "train_samples_per_s",
    "update_gflops",  "iteration_seconds"};

std::filesystem::path WriteLog(const std::filesystem::path& dir, int rows) {
  const auto csv = dir / "log.csv";
  std::ofstream out(csv);
  for (std::size_t c = 0; c < kColumns.size(); ++c) out << (c ? "," : "") << kColumns[c];
  out << "\n";
  for (int r = 1; r <= rows; ++r) {
    for (std::size_t c = 0; c < kColumns.size(); ++c) {
      out << (c ? "," : "");
      if (c == 0)
        out << r;
      else if (c == 5 && r == 3)
        out << "nan";  // no episode ended in iteration 3
      else
        out << std::sin(0.3 * r + c) * (c + 1);
    }
    out << "\n";
  }
  return csv;
}

// Number of plotted points per data-series value (all polylines of that series summed).
std::map<std::string, std::vector<int>> Series(const std::string& html) {
  std::map<std::string, std::vector<int>> out;
  const std::regex re("<polyline class='series' data-series='([^']*)'[^>]*points='([^']*)'");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), re); it != std::sregex_iterator();
       ++it) {
    const std::string pts = (*it)[2];
    int n = 0;
    for (char c : pts) n += c == ',';
    out[(*it)[1]].push_back(n);
  }
  return out;
}

// The (x, y) points of the first plot that draws series `name`, in drawing order.
std::vector<std::pair<double, double>> Points(const std::string& html, const std::string& name) {
  const std::regex re("<polyline class='series' data-series='" + name + "'[^>]*points='([^']*)'");
  std::smatch m;
  std::vector<std::pair<double, double>> out;
  if (!std::regex_search(html, m, re)) return out;
  std::istringstream in(m[1].str());
  double x = 0, y = 0;
  char comma = 0;
  while (in >> x >> comma >> y) out.emplace_back(x, y);
  return out;
}

TEST(TrainingReportTest, EveryCsvColumnIsAPlottedSeries) {
  const auto dir = sims::testing::TempDir("io_report");
  const int rows = 40;
  WriteTrainingReport(WriteLog(dir, rows), dir / "report.html", "train_policy walk");
  std::ifstream in(dir / "report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("<h1>train_policy walk</h1>"), std::string::npos);
  const auto series = Series(html);
  for (std::size_t c = 1; c < kColumns.size(); ++c) {
    ASSERT_TRUE(series.count(kColumns[c])) << "no plotted series for " << kColumns[c];
    int best = 0;
    for (int n : series.at(kColumns[c])) best = std::max(best, n);
    // The missing value splits episode_return into two pieces; all others are one line.
    if (kColumns[c] == "episode_return")
      EXPECT_EQ(best, rows - 3) << kColumns[c];
    else
      EXPECT_EQ(best, rows) << kColumns[c];
  }
  EXPECT_FALSE(series.count("iteration")) << "the x axis is not a series";
  // The learning curves people look for first are grouped plots (several series per figure).
  for (const char* title :
       {"Reward per step", "Success and falls", "Discriminator accuracy", "Throughput (samples/s)"})
    EXPECT_NE(html.find(title), std::string::npos) << title;
  // Grouped plots draw each series again: reward columns appear twice.
  EXPECT_EQ(series.at("task_reward").size(), 2u);
  EXPECT_EQ(series.at("disc_acc_demo").size(), 2u);
  EXPECT_EQ(series.at("env_samples_per_s").size(), 2u);
}

TEST(TrainingReportTest, LongLogsAreReducedButKeepSpikes) {
  const auto dir = sims::testing::TempDir("io_report_long");
  const auto csv = dir / "log.csv";
  {
    std::ofstream out(csv);
    out << "iteration,reward\n";
    for (int r = 0; r < 20000; ++r) out << r << "," << (r == 12345 ? 100.0 : 1.0) << "\n";
  }
  TrainingReportOptions opt;
  opt.max_points = 600;
  const CsvTable t = ReadCsvTable(csv);
  ASSERT_EQ(t.rows(), 20000u);
  const std::string html = TrainingReportHtml(t, "long", opt);
  const auto series = Series(html);
  ASSERT_TRUE(series.count("reward"));
  EXPECT_LE(series.at("reward")[0], 700);
  EXPECT_NE(html.find(">100<"), std::string::npos) << "spike lost from the table / axis";
  // The axis and table see every row, so only the drawn line shows whether the reduction kept
  // the spike: exactly one drawn point stands above the flat 1.0 line, at iteration 12345.
  const auto points = Points(html, "reward");
  ASSERT_GE(points.size(), 3u);
  double x_lo = points[0].first, x_hi = points[0].first, y_flat = points[0].second;
  for (const auto& [x, y] : points) x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
  std::vector<std::pair<double, double>> above;
  for (const auto& p : points)
    if (p.second < y_flat - 1.0) above.push_back(p);  // SVG y grows downwards
  ASSERT_EQ(above.size(), 1u) << "the spike was dropped (or more than one point left the line)";
  EXPECT_NEAR((above[0].first - x_lo) / (x_hi - x_lo), 12345.0 / 19999.0, 1e-3);
}

TEST(TrainingReportTest, BadCsvNamesLineAndColumn) {
  const auto dir = sims::testing::TempDir("io_report_bad");
  {
    std::ofstream out(dir / "log.csv");
    out << "iteration,reward\n1,0.5\n2,abc\n";
  }
  try {
    WriteTrainingReport(dir / "log.csv", dir / "r.html", "x");
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("line 3, column reward"), std::string::npos) << m;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "r.html"));
  EXPECT_THROW(WriteTrainingReport(dir / "none.csv", dir / "r.html", "x"), Error);
}

}  // namespace
}  // namespace sims::io
