// The shipped short-script database: coverage, sizes, grammar and caption/style agreement.
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "sims/planner/script.h"

namespace sims::planner {
namespace {

TEST(ScriptDatabaseTest, CoversEveryEmotionAndRoom) {
  ScriptDatabase db = ScriptDatabase::Load();
  EXPECT_GE(db.size(), 64u);
  const Vocabulary& vocab = Vocabulary::Default();
  std::map<std::pair<std::string, std::string>, int> cells;
  for (const ShortScript& s : db.scripts()) {
    ++cells[{s.emotion, s.scene}];
    EXPECT_GE(s.keyframes.size(), 3u) << s.id;
    EXPECT_LE(s.keyframes.size(), 7u) << s.id;
    EXPECT_FALSE(s.summary.empty()) << s.id;
    EXPECT_GE(s.Interactions(), 1) << s.id;
    EXPECT_TRUE(CheckGrammar(s.keyframes).empty()) << s.id;
  }
  for (const EmotionSpec& e : vocab.emotions)
    for (const RoomTypeSpec& r : vocab.room_types)
      EXPECT_GE((cells[{e.name, r.name}]), 1) << e.name << " in " << r.name;
}

TEST(ScriptDatabaseTest, CaptionsExpressTheirStyles) {
  ScriptDatabase db = ScriptDatabase::Load();
  const Vocabulary& vocab = Vocabulary::Default();
  std::set<std::string> walk_styles, sit_styles, lie_styles, reach_styles;
  std::set<std::string> captions;
  for (const ShortScript& s : db.scripts()) {
    for (std::size_t i = 0; i < s.keyframes.size(); ++i) {
      const Keyframe& k = s.keyframes[i];
      EXPECT_TRUE(vocab.IsValidStyle(k.skill, k.style)) << s.id << " #" << i;
      // Every sit, lie and reach caption names its posture / hand and height explicitly.
      if (IsInteraction(k.skill)) {
        EXPECT_TRUE(vocab.ResolveStyle(k.skill, k.caption, "neutral").from_caption)
            << s.id << " #" << i << ": '" << k.caption << "' -> " << k.style;
      }
      if (IsInteraction(k.skill)) {
        EXPECT_TRUE(captions.insert(k.caption).second) << "caption repeated: " << k.caption;
      }
      if (k.skill == Skill::kWalk) walk_styles.insert(k.style);
      if (k.skill == Skill::kSit) sit_styles.insert(k.style);
      if (k.skill == Skill::kLie) lie_styles.insert(k.style);
      if (k.skill == Skill::kReach) reach_styles.insert(k.style);
    }
  }
  EXPECT_EQ(walk_styles.size(), 6u);  // every gait is used somewhere
  EXPECT_EQ(sit_styles.size(), 4u);
  EXPECT_EQ(lie_styles.size(), 3u);
  EXPECT_EQ(reach_styles.size(), 6u);  // left/right x low/medium/high
}

}  // namespace
}  // namespace sims::planner
