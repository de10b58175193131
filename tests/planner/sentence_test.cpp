#include "sims/planner/sentence.h"

#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/error.h"

namespace sims::planner {
namespace {

TEST(SentenceTest, InstructionSentenceBecomesAKeyframe) {
  const auto j = InstructionToScriptJson("sit on the armchair with legs crossed");
  EXPECT_EQ(j["keyframes"][0]["skill"], "sit");
  EXPECT_EQ(j["keyframes"][0]["furniture"], "armchair");
  EXPECT_EQ(j["keyframes"][0]["caption"], "sit on the armchair with legs crossed");
  EXPECT_THROW(InstructionToScriptJson("the weather is nice"), Error);
}

TEST(SentenceTest, FallbackVerbsApplyOnlyWhenNoAliasMatches) {
  // "bed" is furniture, not a skill alias: only the fallback table makes it a lie.
  const auto lie = InstructionToScriptJson("get into bed");
  EXPECT_EQ(lie["keyframes"][0]["skill"], "lie");
  EXPECT_EQ(lie["keyframes"][0]["furniture"], "bed");
  const auto walk = InstructionToScriptJson("walk to the bed");
  EXPECT_EQ(walk["keyframes"][0]["skill"], "walk");
  EXPECT_EQ(walk["keyframes"][0]["furniture"], "bed");
  EXPECT_EQ(InstructionToScriptJson("she goes to the sofa")["keyframes"][0]["skill"], "walk");
}

TEST(SentenceTest, SentenceConfigNamesOnlyKnownSkills) {
  EXPECT_FALSE(LoadSentenceConfig().fallback_verbs.empty());
  const auto dir = sims::testing::TempDir("sentence");
  std::ofstream(dir / "bad.json") << R"({"fallback_verbs": {"hop": "jump"}})";
  const std::string e = sims::testing::ErrorOf([&] { LoadSentenceConfig(dir / "bad.json"); });
  EXPECT_NE(e.find("fallback_verbs.hop"), std::string::npos) << e;
}

TEST(SentenceTest, ReachHeightAndHandFromCaption) {
  EXPECT_EQ(ReachHeightFromCaption("pick up the cup from the floor"), "low");
  EXPECT_EQ(ReachHeightFromCaption("touch the top shelf"), "high");
  EXPECT_EQ(ReachHeightFromCaption("touch the lamp"), "medium");
  EXPECT_TRUE(ReachUsesLeftHand("reach with the left hand"));
  EXPECT_FALSE(ReachUsesLeftHand("reach for the lamp"));
}

}  // namespace
}  // namespace sims::planner
