// configs/planner/planner.json against PlannerConfig's C++ defaults. LoadPlannerConfig reads the
// file on every run, so its values are the ones the apps use; the struct must say the same so
// that code building a PlannerConfig{} (tests, other callers) plans as the apps do.
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/config.h"
#include "sims/core/paths.h"
#include "sims/planner/planner.h"

namespace sims::planner {
namespace {

TEST(ConfigFileTest, PlannerJsonMatchesPlannerConfigDefaults) {
  const auto diffs = testing::ConfigFileDifferences(ConfigPath("planner/planner.json"),
                                                    ConfigToJson(PlannerConfig{}));
  std::string all;
  for (const std::string& d : diffs) all += "\n  " + d;
  EXPECT_TRUE(diffs.empty()) << "configs/planner/planner.json differs from PlannerConfig{}:" << all;
}

}  // namespace
}  // namespace sims::planner
