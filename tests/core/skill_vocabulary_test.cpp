#include "sims/core/skill_vocabulary.h"

#include <gtest/gtest.h>

#include "sims/core/error.h"

namespace sims {
namespace {

TEST(SkillVocabularyTest, ScriptedSkillsComeFirstInThePlannersOrder) {
  std::vector<std::string> names;
  for (const SkillTraits* t : ScriptedSkills()) names.push_back(t->name);
  EXPECT_EQ(names, (std::vector<std::string>{"walk", "sit", "lie", "reach", "getup"}));
}

TEST(SkillVocabularyTest, TraitsReplaceNameTests) {
  // What the FSM, eval and planner used to test by name, now read from the table.
  EXPECT_TRUE(SkillTraitsOf("walk").navigates);
  EXPECT_TRUE(SkillTraitsOf("walk").required);
  EXPECT_TRUE(SkillTraitsOf("walk").flat_scene);
  EXPECT_EQ(SkillTraitsOf("walk").timing, StoryTiming::kWalk);
  EXPECT_EQ(SkillTraitsOf("sit").timing, StoryTiming::kObject);
  EXPECT_EQ(SkillTraitsOf("sit").follow_up, "getup");
  EXPECT_EQ(SkillTraitsOf("lie").follow_up, "getup");
  EXPECT_TRUE(SkillTraitsOf("reach").hand_target);
  EXPECT_TRUE(SkillTraitsOf("getup").recovers_falls);
  EXPECT_FALSE(SkillTraitsOf("getup").needs_object);
  EXPECT_TRUE(SkillTraitsOf("unified").contact_steps);
  EXPECT_EQ(SkillNames([](const SkillTraits& t) { return t.affordance; }), "sit, lie, reach");
  for (const SkillTraits& t : SkillVocabulary())
    if (!t.follow_up.empty()) EXPECT_NE(FindSkillTraits(t.follow_up), nullptr) << t.name;
}

TEST(SkillVocabularyTest, UnknownAndDuplicateNamesAreErrors) {
  EXPECT_EQ(FindSkillTraits("fly"), nullptr);
  try {
    SkillTraitsOf("fly");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("walk, sit, lie"), std::string::npos) << e.what();
  }
  SkillTraits walk;
  walk.name = "walk";
  EXPECT_THROW(RegisterSkillTraits(walk), Error);
  SkillTraits hop;
  hop.name = "vocabulary_test_hop";
  const SkillTraits& added = RegisterSkillTraits(hop);
  EXPECT_EQ(&added, FindSkillTraits("vocabulary_test_hop"));
  EXPECT_EQ(ScriptedSkills().size(), 5u) << "unscripted skills stay out of the planner";
}

}  // namespace
}  // namespace sims
