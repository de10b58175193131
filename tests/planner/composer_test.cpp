// Theme → long script: retrieval ranking, emotion arcs, difficulty counts, determinism.
#include "sims/planner/composer.h"

#include <set>

#include <gtest/gtest.h>

namespace sims::planner {
namespace {

class ComposerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { db_ = new ScriptDatabase(ScriptDatabase::Load()); }
  static void TearDownTestSuite() {
    delete db_;
    db_ = nullptr;
  }
  ThemePlanner Planner() const {
    return ThemePlanner(*db_, Vocabulary::Default(), EmotionLexicon::Default());
  }
  std::string Top(const std::string& theme) const {
    ThemePlanner p = Planner();
    const EmotionLexicon& lex = EmotionLexicon::Default();
    RetrievalQuery q{theme, theme, lex.Detect(theme), p.retriever().RoomsIn(theme), ""};
    return db_->scripts()[p.retriever().Rank(q).front().index].id;
  }
  static ScriptDatabase* db_;
};
ScriptDatabase* ComposerTest::db_ = nullptr;

TEST_F(ComposerTest, RanksTheObviousScriptFirst) {
  EXPECT_EQ(Top("a drunk person staggers into the bedroom and collapses onto the bed"),
            "bedroom_drunk_1");
  EXPECT_EQ(Top("someone in a hurry grabs the keys from the coffee table and the bag from the "
                "side table"),
            "living_room_hurried_1");
  EXPECT_EQ(Top("a lonely person sets a single plate on the dining table"), "dining_room_sad_2");
  EXPECT_EQ(Top("an angry reader slams a book onto the desk"), "library_angry_1");
  EXPECT_EQ(Top("in the study a relaxed reader browses the shelves and reads in the armchair with "
                "legs crossed"),
            "library_relaxed_1");
  EXPECT_EQ(Top("a happy kid takes a birthday cake out of the fridge"), "dining_room_happy_2");
  EXPECT_EQ(Top("an exhausted man puts his cup on the side table and slumps into the armchair"),
            "living_room_tired_2");
}

TEST_F(ComposerTest, EmbeddingSimilarityIsPluggedIn) {
  // A toy embedder: one dimension per word family; "sad" texts and "sorrow" share one.
  TextEmbedder embed = [](const std::string& text) {
    Eigen::VectorXf v = Eigen::VectorXf::Zero(2);
    if (text.find("sorrow") != std::string::npos || text.find("lonely") != std::string::npos)
      v[0] = 1;
    v[1] = 0.1f;
    return v;
  };
  RetrievalConfig rc;
  rc.w_text = 0.0;
  rc.w_emotion = 0.0;
  rc.w_embedding = 1.0;
  ScriptRetriever with(*db_, Vocabulary::Default(), rc, embed);
  RetrievalQuery q{"full of sorrow", "full of sorrow", "neutral", {}, ""};
  const ShortScript& top = db_->scripts()[with.Rank(q).front().index];
  EXPECT_NE(top.summary.find("lonely"), std::string::npos) << top.id;
  EXPECT_GT(with.Rank(q).front().embedding, 0.9);
  ScriptRetriever without(*db_, Vocabulary::Default(), rc);
  EXPECT_EQ(without.Rank(q).front().embedding, 0.0);
}

TEST_F(ComposerTest, ExpandsFurnitureAliasesAndFindsRooms) {
  ThemePlanner p = Planner();
  EXPECT_NE(p.retriever().ExpandFurniture("naps on the couch").find("sofa"), std::string::npos);
  EXPECT_EQ(p.retriever().RoomsIn("from the kitchen to the living room and then the study"),
            (std::vector<std::string>{"dining room", "living room", "library"}));
}

TEST(EmotionTest, DetectsEmotionsAndArcs) {
  const EmotionLexicon& lex = EmotionLexicon::Default();
  EXPECT_EQ(lex.Detect("she is exhausted after a long day"), "tired");
  EXPECT_EQ(lex.Detect("he is not happy at all"), "sad");  // negation uses the opposites table
  EXPECT_EQ(lex.Detect("a person walks around"), "neutral");
  auto emotions = [&](const std::string& theme) {
    std::vector<std::string> out;
    for (const ArcSegment& a : lex.Arc(theme)) out.push_back(a.emotion);
    return out;
  };
  EXPECT_EQ(emotions("happy at first, then depressed"), (std::vector<std::string>{"happy", "sad"}));
  EXPECT_EQ(emotions("She wakes up tired, then rushes around in a hurry, and finally relaxes on "
                     "the sofa"),
            (std::vector<std::string>{"tired", "hurried", "relaxed"}));
  EXPECT_EQ(emotions("an angry man. later he calms down. then he gets drunk"),
            (std::vector<std::string>{"angry", "relaxed", "drunk"}));
  EXPECT_EQ(emotions("someone reads a book"), (std::vector<std::string>{"neutral"}));
  // Neutral clauses join their neighbour instead of becoming steps.
  std::vector<ArcSegment> arc = lex.Arc("A person comes home, is happy, then reads a book");
  ASSERT_EQ(arc.size(), 1u);
  EXPECT_NE(arc[0].text.find("comes home"), std::string::npos);
  EXPECT_NE(arc[0].text.find("reads a book"), std::string::npos);
}

TEST_F(ComposerTest, FollowsTheEmotionalArcInOrder) {
  ThemePlanner p = Planner();
  for (uint64_t seed : {0u, 1u, 2u, 7u}) {
    for (Difficulty d : {Difficulty::kSimple, Difficulty::kMid, Difficulty::kHard}) {
      LongScript ls = p.Plan("A person is happy at first, then gets depressed", d, seed);
      EXPECT_EQ(ls.EmotionSequence(), (std::vector<std::string>{"happy", "sad"}))
          << DifficultyName(d) << " seed " << seed;
    }
    LongScript three =
        p.Plan("tired in the morning, then in a hurry, finally relaxed", Difficulty::kHard, seed);
    EXPECT_EQ(three.EmotionSequence(), (std::vector<std::string>{"tired", "hurried", "relaxed"}));
    // Two interactions for three steps keep the first and the last.
    LongScript two =
        p.Plan("tired in the morning, then in a hurry, finally relaxed", Difficulty::kSimple, seed);
    EXPECT_EQ(two.EmotionSequence(), (std::vector<std::string>{"tired", "relaxed"}));
  }
}

TEST_F(ComposerTest, DifficultyControlsInteractionCounts) {
  ThemePlanner p = Planner();
  const char* themes[] = {"a person relaxes at home, drinks a coke, reads a book",
                          "an angry man storms around the house",
                          "a drunk student comes back from a party, then feels sad",
                          "someone cleans the bedroom"};
  for (const char* theme : themes) {
    for (uint64_t seed = 0; seed < 4; ++seed) {
      LongScript s = p.Plan(theme, Difficulty::kSimple, seed);
      LongScript m = p.Plan(theme, Difficulty::kMid, seed);
      LongScript h = p.Plan(theme, Difficulty::kHard, seed);
      EXPECT_EQ(s.Interactions(), 2) << theme;
      EXPECT_GE(m.Interactions(), 3) << theme;
      EXPECT_LE(m.Interactions(), 4) << theme;
      EXPECT_GE(h.Interactions(), 4) << theme;
      EXPECT_LE(h.Interactions(), 6) << theme;
      for (const LongScript* ls : {&s, &m, &h}) {
        EXPECT_TRUE(CheckGrammar(ls->keyframes).empty()) << theme;
        std::set<std::string> captions;
        for (const Keyframe& k : ls->keyframes)
          if (!k.inserted) {
            EXPECT_TRUE(captions.insert(k.caption).second) << k.caption;
          }
      }
    }
  }
}

TEST_F(ComposerTest, SameThemeAndSeedGiveTheSameScript) {
  ThemePlanner p = Planner();
  const std::string theme = "a tired man comes home after a long day, then gets angry";
  for (uint64_t seed : {3u, 11u}) {
    LongScript a = p.Plan(theme, Difficulty::kHard, seed);
    LongScript b = Planner().Plan(theme, Difficulty::kHard, seed);
    EXPECT_EQ(KeyframesToJson(a.keyframes).dump(), KeyframesToJson(b.keyframes).dump());
    EXPECT_EQ(a.narrative, b.narrative);
    EXPECT_EQ(a.script_ids, b.script_ids);
  }
}

TEST_F(ComposerTest, NarrativeNamesFurnitureAndEmotions) {
  ThemePlanner p = Planner();
  LongScript ls = p.Plan("happy at first, then depressed", Difficulty::kMid, 5);
  EXPECT_NE(ls.narrative.find("feeling happy"), std::string::npos) << ls.narrative;
  EXPECT_NE(ls.narrative.find("feeling sad"), std::string::npos) << ls.narrative;
  for (const Keyframe& k : ls.keyframes) {
    if (!IsInteraction(k.skill)) continue;
    std::string f = k.furniture;
    std::replace(f.begin(), f.end(), '_', ' ');
    EXPECT_NE(ls.narrative.find(f), std::string::npos) << f << " in " << ls.narrative;
  }
  std::vector<std::string> names(ls.keyframes.size());
  for (std::size_t i = 0; i < names.size(); ++i)
    if (ls.keyframes[i].skill == Skill::kSit) names[i] = "stool";
  std::string substituted = TemplateNarrative(ls, names);
  if (ls.keyframes.end() !=
      std::find_if(ls.keyframes.begin(), ls.keyframes.end(),
                   [](const Keyframe& k) { return k.skill == Skill::kSit; })) {
    EXPECT_NE(substituted.find("a stool serves as the"), std::string::npos);
  }
}

TEST(DifficultyTest, ParsesNames) {
  EXPECT_EQ(ParseDifficulty("Simple"), Difficulty::kSimple);
  EXPECT_EQ(ParseDifficulty("medium"), Difficulty::kMid);
  EXPECT_EQ(ParseDifficulty("hard"), Difficulty::kHard);
  EXPECT_THROW(ParseDifficulty("extreme"), Error);
}

}  // namespace
}  // namespace sims::planner
