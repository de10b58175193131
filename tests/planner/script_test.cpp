// Short-script schema: accepted variants, clear errors for malformed scripts, grammar repair.
#include "sims/planner/script.h"

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/paths.h"
#include "sims/planner/composer.h"

namespace sims::planner {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::string& text, GrammarMode mode = GrammarMode::kLenient) {
  return sims::testing::ErrorOf([&] { ParseShortScriptText(text, "story.json", mode); });
}

TEST(ScriptTest, AcceptsSimsVariants) {
  ShortScript s =
      ParseShortScriptText(R"({"summary": "x", "emotion": "tired, sad", "scene": "Bed Room",
    "keyframes": [
      {"skill": "loco", "emotion/style": "tired, sad", "caption": "head bowed while walking", "furniture": "floor"},
      {"skill": "Sit Down", "emotion": ["sad"], "caption": "sits with head in hands", "furnitures": ["couch"]},
      {"skill": "standup", "emotion/style": "sad", "caption": "gets up", "furniture": "couch"},
      {"skill": "walk", "emotion/style": "sad", "caption": "walks to the bookcase", "furniture": "bookcase"},
      {"skill": "touch", "emotion/style": "sad", "caption": "reaches up with the left hand to the top shelf", "furniture": "bookcase"},
      {"skill": "loco", "emotions": "drunk; hurried", "caption": "goes to bed", "furniture": "bed"},
      {"skill": "liedown", "emotion/style": "tired", "caption": "curls up on the side", "furniture": "bed"},
      {"skill": "get_up", "caption": "gets out of bed"}]})",
                           "inline");
  EXPECT_EQ(s.emotion, "tired");  // first known emotion of "tired, sad"
  EXPECT_EQ(s.scene, "bedroom");
  ASSERT_EQ(s.keyframes.size(), 8u);
  EXPECT_EQ(s.keyframes[0].skill, Skill::kWalk);
  EXPECT_EQ(s.keyframes[0].style, "slow_bowed");
  EXPECT_EQ(s.keyframes[0].tags, (std::vector<std::string>{"tired", "sad"}));
  EXPECT_EQ(s.keyframes[1].skill, Skill::kSit);
  EXPECT_EQ(s.keyframes[1].furniture, "sofa");
  EXPECT_EQ(s.keyframes[1].emotion, "sad");
  EXPECT_EQ(s.keyframes[1].style, "hands_on_knees");
  EXPECT_EQ(s.keyframes[2].skill, Skill::kGetUp);
  EXPECT_EQ(s.keyframes[3].furniture, "bookshelf");
  EXPECT_EQ(s.keyframes[4].skill, Skill::kReach);
  EXPECT_EQ(s.keyframes[4].style, "left_high");
  EXPECT_EQ(s.keyframes[5].emotion, "drunk");
  EXPECT_EQ(s.keyframes[5].style, "drunk_sway");  // no caption phrase: the emotion's gait
  EXPECT_EQ(s.keyframes[6].skill, Skill::kLie);
  EXPECT_EQ(s.keyframes[6].style, "on_side");
  EXPECT_EQ(s.keyframes[7].skill, Skill::kGetUp);
  EXPECT_TRUE(CheckGrammar(s.keyframes).empty());
}

TEST(ScriptTest, ExplicitStyleAndEmotionAliases) {
  ShortScript s = ParseShortScriptText(R"({"emotion": "depressed", "scene": "study",
    "keyframes": [{"skill": "walk", "style": "tiptoe", "caption": "walks", "furniture": "desk"},
                  {"skill": "grab", "style": "left_low", "caption": "takes a pen", "furniture": "writing desk"}]})",
                                       "inline");
  EXPECT_EQ(s.emotion, "sad");
  EXPECT_EQ(s.scene, "library");
  EXPECT_EQ(s.keyframes[0].style, "tiptoe");
  EXPECT_EQ(s.keyframes[1].style, "left_low");
  EXPECT_EQ(s.keyframes[1].furniture, "desk");
}

TEST(ScriptTest, RoundTripsThroughCanonicalJson) {
  ShortScript a = LoadShortScript(ProjectRoot() / "assets/scripts/bedroom/bedroom_sad_2.json",
                                  GrammarMode::kStrict);
  ShortScript b = ParseShortScript(ShortScriptToJson(a), "roundtrip", GrammarMode::kStrict);
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    EXPECT_EQ(a.keyframes[i].skill, b.keyframes[i].skill);
    EXPECT_EQ(a.keyframes[i].style, b.keyframes[i].style);
    EXPECT_EQ(a.keyframes[i].furniture, b.keyframes[i].furniture);
    EXPECT_EQ(a.keyframes[i].emotion, b.keyframes[i].emotion);
  }
  EXPECT_EQ(b.id, "bedroom_sad_2");
  // Saving again gives the same text: the style is not repeated among the mood words.
  EXPECT_EQ(ShortScriptToJson(b).dump(), ShortScriptToJson(a).dump());
  ShortScript c = ParseShortScript(ShortScriptToJson(b), "roundtrip", GrammarMode::kStrict);
  EXPECT_EQ(ShortScriptToJson(c).dump(), ShortScriptToJson(a).dump());
}

TEST(ScriptTest, SingleQuotesAreRejectedWithAFix) {
  std::string e = ErrorOf("{'summary': 'x', 'keyframes': [{'skill': 'loco'}]}");
  EXPECT_THAT(e, HasSubstr("story.json"));
  EXPECT_THAT(e, HasSubstr("single quotes"));
  EXPECT_THAT(e, HasSubstr("replace '"));
}

// Regression input of the script fuzzer: a number beyond double range made nlohmann throw
// out_of_range, which escaped as a non-project exception.
TEST(ScriptTest, NumberOverflowIsAProjectError) {
  std::string e = ErrorOf("3e40000000000000desk.\",\n  \"em");
  EXPECT_THAT(e, HasSubstr("story.json"));
  EXPECT_THAT(e, HasSubstr("numbers a double can hold"));
  EXPECT_THROW(ParseShortScriptText("{\"summary\": 1e999999}", "s.json"), Error);
}

TEST(ScriptTest, ParseErrorsNameTheLine) {
  std::string e = ErrorOf("{\"summary\": \"x\",\n \"keyframes\": [,]}");
  EXPECT_THAT(e, HasSubstr("story.json"));
  EXPECT_THAT(e, HasSubstr("valid JSON"));
  EXPECT_THAT(e, HasSubstr("line 2"));
}

TEST(ScriptTest, UnknownSkillNamesKeyframeAndField) {
  std::string e = ErrorOf(R"({"keyframes": [{"skill": "loco", "furniture": "floor"},
                                            {"skill": "sitdwn", "furniture": "chair"}]})");
  EXPECT_THAT(e, HasSubstr("story.json: field 'keyframes[1].skill'"));
  EXPECT_THAT(e, HasSubstr("did you mean 'sitdown'"));
}

TEST(ScriptTest, UnknownFurnitureSuggestsTheClosest) {
  std::string e = ErrorOf(R"({"keyframes": [{"skill": "loco", "furniture": "sofaa"}]})");
  EXPECT_THAT(e, HasSubstr("field 'keyframes[0].furniture'"));
  EXPECT_THAT(e, HasSubstr("did you mean 'sofa'"));
  e = ErrorOf(R"({"keyframes": [{"skill": "loco", "furnitures": "spaceship"}]})");
  EXPECT_THAT(e, HasSubstr("field 'keyframes[0].furnitures'"));
  EXPECT_THAT(e, HasSubstr("configs/planner/vocabulary.json"));
}

TEST(ScriptTest, AffordancesAreChecked) {
  std::string e =
      ErrorOf(R"({"keyframes": [{"skill": "loco"}, {"skill": "sit", "furniture": "bookshelf"}]})");
  EXPECT_THAT(e, HasSubstr("keyframes[1].furniture"));
  EXPECT_THAT(e, HasSubstr("furniture that affords 'sit'"));
  e = ErrorOf(R"({"keyframes": [{"skill": "loco"}, {"skill": "liedown"}]})");
  EXPECT_THAT(e, HasSubstr("keyframes[1].furniture"));
  EXPECT_THAT(e, HasSubstr("a furniture category for 'lie'"));
}

TEST(ScriptTest, BadTypesAndMissingFields) {
  EXPECT_THAT(ErrorOf(R"({"summary": "x"})"), HasSubstr("field 'keyframes'"));
  EXPECT_THAT(ErrorOf(R"({"keyframes": []})"), HasSubstr("non-empty list"));
  EXPECT_THAT(ErrorOf(R"({"keyframes": [3]})"), HasSubstr("keyframes[0]"));
  EXPECT_THAT(ErrorOf(R"({"keyframes": [{"skill": 3}]})"), HasSubstr("keyframes[0].skill"));
  EXPECT_THAT(ErrorOf(R"({"emotion": "grumpy-ish", "keyframes": [{"skill": "walk"}]})"),
              HasSubstr("field 'emotion'"));
  EXPECT_THAT(ErrorOf(R"({"scene": "garage", "keyframes": [{"skill": "walk"}]})"),
              HasSubstr("field 'scene': expected a room type"));
  EXPECT_THAT(ErrorOf(R"({"keyframes": [{"skill": "walk", "instance": -1}]})"),
              HasSubstr("keyframes[0].instance"));
  EXPECT_THAT(ErrorOf("[1, 2]"), HasSubstr("a JSON object"));
}

// A get-up needs something to get up from: a seat or bed the character is on, or the floor
// right after a walk (SIMS scripts write that after a fall: a drunk character has fallen).
TEST(ScriptTest, GetUpOnlyAfterSitOrLieOrFromTheFloorAfterAWalk) {
  std::string e = ErrorOf(R"({"keyframes": [{"skill": "standup"}, {"skill": "loco"}]})");
  EXPECT_THAT(e, HasSubstr("keyframes[0].skill"));
  EXPECT_THAT(e, HasSubstr("get-up only after sit or lie"));
  e = ErrorOf(
      R"({"keyframes": [{"skill": "loco", "furniture": "sofa"}, {"skill": "getup", "furniture": "sofa"}]})");
  EXPECT_THAT(e, HasSubstr("keyframes[1].skill"));
  // After a walk, from the floor: accepted, and the get-up stays on the floor.
  const ShortScript fell = ParseShortScriptText(
      R"({"keyframes": [{"skill": "loco", "caption": "staggers"},
                        {"skill": "getup", "furniture": "floor", "caption": "gets up after falling"},
                        {"skill": "loco", "furniture": "sofa"}, {"skill": "sitdown", "furniture": "sofa"}]})",
      "fell.json");
  const auto with = InsertTransitions(fell.keyframes, "fell.json");
  ASSERT_EQ(with.size(), 4u);
  EXPECT_EQ(with[1].skill, Skill::kGetUp);
  EXPECT_EQ(with[1].furniture, "floor");
  EXPECT_EQ(with[1].style, "floor");
  e = ErrorOf(
      R"({"keyframes": [{"skill": "loco", "furniture": "chair"}, {"skill": "sit", "furniture": "chair"},
                                {"skill": "getup", "furniture": "bed"}]})");
  EXPECT_THAT(e, HasSubstr("keyframes[2].furniture"));
}

TEST(ScriptTest, StrictModeRequiresWalksLenientInsertsThem) {
  const char* text = R"({"emotion": "sad", "keyframes": [
      {"skill": "sit", "caption": "sits upright", "furniture": "chair"},
      {"skill": "touch", "caption": "reaches up with the left hand", "furniture": "bookshelf"},
      {"skill": "liedown", "caption": "lies on the back", "furniture": "bed"}]})";
  std::string e = ErrorOf(text, GrammarMode::kStrict);
  EXPECT_THAT(e, HasSubstr("keyframes[0].skill"));
  EXPECT_THAT(e, HasSubstr("a walk to the chair"));
  ShortScript s = ParseShortScriptText(text, "lenient");
  EXPECT_EQ(CheckGrammar(s.keyframes).size(), 3u);
  std::vector<Keyframe> fixed = InsertTransitions(s.keyframes, "lenient");
  EXPECT_TRUE(CheckGrammar(fixed).empty());
  std::vector<Skill> skills;
  for (const Keyframe& k : fixed) skills.push_back(k.skill);
  EXPECT_EQ(skills, (std::vector<Skill>{Skill::kWalk, Skill::kSit, Skill::kGetUp, Skill::kWalk,
                                        Skill::kReach, Skill::kWalk, Skill::kLie}));
  EXPECT_TRUE(fixed[0].inserted);
  EXPECT_EQ(fixed[0].furniture, "chair");
  EXPECT_EQ(fixed[0].style, "slow_bowed");  // inserted walks take the emotion's gait
  EXPECT_EQ(fixed[2].style, "seat");
  EXPECT_FALSE(fixed[1].inserted);
}

TEST(ScriptTest, LoadErrorsNameTheFile) {
  auto dir = sims::testing::TempDir("planner_script");
  EXPECT_THROW(LoadShortScript(dir / "missing.json"), Error);
  std::ofstream(dir / "bad.json") << "{\"keyframes\": [{\"skill\": \"fly\"}]}";
  try {
    LoadShortScript(dir / "bad.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.json: field 'keyframes[0].skill'"));
  }
  std::ofstream(dir / "long.json") << "[{'skill': 'loco'}]";
  try {
    LoadLongScript(dir / "long.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("long.json"));
    EXPECT_THAT(e.what(), HasSubstr("single quotes"));
  }
}

TEST(ScriptTest, LongScriptForms) {
  nlohmann::json bare = nlohmann::json::parse(R"([{"skill": "sit", "furniture": "sofa"},
                                                  {"skill": "liedown", "furniture": "bed"}])");
  LongScript a = LongScriptFromJson(bare, "bare");
  EXPECT_EQ(a.Interactions(), 2);
  EXPECT_TRUE(CheckGrammar(a.keyframes).empty());
  nlohmann::json multi = nlohmann::json::parse(R"({"scripts": [
      {"emotion": "happy", "scene": "bedroom", "keyframes": [{"skill": "loco", "furniture": "bed"}, {"skill": "sit", "furniture": "bed"}]},
      {"emotion": "sad", "scene": "library", "keyframes": [{"skill": "loco", "furniture": "chair"}, {"skill": "sit", "furniture": "chair"}]}]})");
  LongScript b = LongScriptFromJson(multi, "multi");
  EXPECT_EQ(b.script_ids.size(), 2u);
  EXPECT_EQ(b.segment_rooms, (std::vector<std::string>{"bedroom", "library"}));
  EXPECT_EQ(b.EmotionSequence(), (std::vector<std::string>{"happy", "sad"}));
  EXPECT_EQ(b.keyframes.back().segment, 1);
  EXPECT_TRUE(CheckGrammar(b.keyframes).empty());
  std::string e;
  try {
    LongScriptFromJson(
        nlohmann::json::parse(R"([{"skill": "sit", "furniture": "sofa"}, {"skill": "dance"}])"),
        "bare.json");
  } catch (const Error& ex) {
    e = ex.what();
  }
  EXPECT_THAT(e, HasSubstr("bare.json: field '[1].skill'"));
}

}  // namespace
}  // namespace sims::planner
