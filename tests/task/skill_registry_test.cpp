// The registry binds every skill-vocabulary entry to code, and each skill's params are keys of
// the one skill config (policy files store it flat).
#include <gtest/gtest.h>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/task/skill.h"

namespace sims::task {
namespace {

TEST(SkillRegistryTest, EveryVocabularySkillHasCodeAndTheSameTraits) {
  for (const SkillTraits& t : SkillVocabulary()) {
    SCOPED_TRACE(t.name);
    const SkillInfo* info = nullptr;
    for (const SkillInfo& s : GetSkills())
      if (s.name() == t.name) info = &s;
    ASSERT_NE(info, nullptr);
    EXPECT_TRUE(info->create && info->build_scene);
    EXPECT_EQ(info->traits.description, t.description);
    EXPECT_EQ(info->traits.navigates, t.navigates);
  }
  EXPECT_EQ(GetSkills().size(), SkillVocabulary().size());
}

TEST(SkillRegistryTest, ParamsAreSkillConfigKeys) {
  const nlohmann::json all = ConfigToJson(SkillConfig{});
  for (const SkillInfo& s : GetSkills()) {
    SCOPED_TRACE(s.name());
    EXPECT_FALSE(s.params.empty());
    for (const auto& [key, value] : s.params.items()) {
      ASSERT_TRUE(all.contains(key)) << key;
      EXPECT_EQ(all.at(key), value) << key;
    }
  }
  EXPECT_TRUE(FindSkill("walk").params.contains("walk_success_radius"));
  EXPECT_TRUE(FindSkill("sit").params.contains("sit_back_contact"));
}

TEST(SkillRegistryTest, RegisteringATakenNameOrNoCodeIsAnError) {
  SkillInfo walk = FindSkill("walk");
  EXPECT_THROW(RegisterSkill(walk), Error);
  SkillInfo empty;
  empty.traits.name = "registry_test_empty";
  EXPECT_THROW(RegisterSkill(empty), Error);
  EXPECT_EQ(FindSkillTraits("registry_test_empty"), nullptr)
      << "a failed registration adds nothing";
}

}  // namespace
}  // namespace sims::task
