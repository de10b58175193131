#include "sims/sim/action_filter.h"

#include <gtest/gtest.h>

#include "common/test_util.h"

namespace sims::sim {
namespace {

TEST(ActionFilterTest, BlendsWithThePreviousAppliedAction) {
  ActionFilter f(2);
  float a[2] = {1.0f, -2.0f};
  f.Apply(0.3, a);  // nothing before: passes through
  EXPECT_FLOAT_EQ(a[0], 1.0f);
  EXPECT_FLOAT_EQ(a[1], -2.0f);
  float b[2] = {0.0f, 2.0f};
  f.Apply(0.3, b);  // 0.3·previous + 0.7·new
  EXPECT_FLOAT_EQ(b[0], 0.3f);
  EXPECT_FLOAT_EQ(b[1], 0.3f * -2.0f + 0.7f * 2.0f);
  float c[2] = {1.0f, 1.0f};
  f.Apply(0.5, c);  // blends with what was applied (b), not with what the policy asked
  EXPECT_FLOAT_EQ(c[0], 0.5f * 0.3f + 0.5f);
  EXPECT_FLOAT_EQ(c[1], 0.5f * b[1] + 0.5f);
}

TEST(ActionFilterTest, ZeroPassesThroughButRemembersAndResetForgets) {
  ActionFilter f(1);
  float a = 4.0f;
  f.Apply(0.0, &a);  // a skill without smoothing still leaves its action for the next one
  EXPECT_FLOAT_EQ(a, 4.0f);
  EXPECT_TRUE(f.has_previous());
  float b = 0.0f;
  f.Apply(0.25, &b);
  EXPECT_FLOAT_EQ(b, 1.0f);
  f.Reset();
  EXPECT_FALSE(f.has_previous());
  float c = -3.0f;
  f.Apply(0.25, &c);
  EXPECT_FLOAT_EQ(c, -3.0f);
}

TEST(ActionFilterTest, SmoothingOutOfRangeNamesSourceAndField) {
  CheckActionSmoothing(0.0, "p.json", "action_smoothing.walk");
  CheckActionSmoothing(kMaxActionSmoothing, "p.json", "action_smoothing.walk");
  for (double bad : {-0.1, 0.95, 1.0}) {
    const std::string e = sims::testing::ErrorOf(
        [&] { CheckActionSmoothing(bad, "p.json", "action_smoothing.walk"); });
    EXPECT_NE(e.find("p.json"), std::string::npos) << e;
    EXPECT_NE(e.find("action_smoothing.walk"), std::string::npos) << e;
    EXPECT_NE(e.find("[0, 0.9]"), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace sims::sim
