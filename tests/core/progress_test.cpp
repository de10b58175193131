#include "sims/core/progress.h"

#include <gtest/gtest.h>

namespace sims {
namespace {

TEST(ProgressTest, FormatsDurations) {
  EXPECT_EQ(ProgressReporter::FormatDuration(0), "00:00:00");
  EXPECT_EQ(ProgressReporter::FormatDuration(3725), "01:02:05");
  EXPECT_EQ(ProgressReporter::FormatDuration(-1), "--:--:--");
}

TEST(ProgressTest, RateCountsUnits) {
  ProgressReporter p("test", 100, "steps", 1000.0);
  p.Update(50);
  EXPECT_GT(p.Rate(), 0.0);
  p.Finish();
}

}  // namespace
}  // namespace sims
