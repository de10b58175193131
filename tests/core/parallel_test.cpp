#include "sims/core/parallel.h"

#include <gtest/gtest.h>
#include <omp.h>

namespace sims {
namespace {

TEST(ParallelTest, SettingReachesOpenMpAndListeners) {
  int seen = -1;
  AddThreadCountListener([&](int n) { seen = n; });
  EXPECT_EQ(SetThreadCount(2), 2);
  EXPECT_EQ(ThreadCount(), 2);
  EXPECT_EQ(omp_get_max_threads(), 2);
  EXPECT_EQ(seen, 2);
  EXPECT_EQ(SetThreadCount(0), HardwareThreads());
}

}  // namespace
}  // namespace sims
