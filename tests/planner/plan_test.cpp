// The plan file and the planner front door: theme → plan on the built-in layouts, file round
// trip, validation messages, determinism, script input and binding to a given scene.
#include "sims/planner/plan.h"

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/planner/planner.h"
#include "sims/scene/builtin.h"

namespace sims::planner {
namespace {

using ::testing::HasSubstr;

class PlanTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    PlannerConfig c = LoadPlannerConfig();
    c.llm.endpoint = "";
    planner_ = new StoryPlanner(c);
    layouts_ = new LayoutDatabase(BuiltinLayoutDatabase());
  }
  static void TearDownTestSuite() {
    delete planner_;
    delete layouts_;
  }
  static StoryPlanner* planner_;
  static LayoutDatabase* layouts_;
};
StoryPlanner* PlanTest::planner_ = nullptr;
LayoutDatabase* PlanTest::layouts_ = nullptr;

TEST_F(PlanTest, ThemeToPlanBindsEveryKeyframe) {
  for (Difficulty d : {Difficulty::kSimple, Difficulty::kMid, Difficulty::kHard}) {
    for (uint64_t seed : {0u, 5u}) {
      ScriptResult s = planner_->ScriptForTheme(
          "A person is happy at first, then gets depressed and goes to bed", d, seed);
      Plan p = planner_->Place(s, *layouts_);
      EXPECT_EQ(p.arc, (std::vector<std::string>{"happy", "sad"}));
      EXPECT_TRUE(p.AllPlaced()) << ::testing::PrintToString(p.warnings);
      for (const PlanKeyframe& k : p.keyframes) {
        if (k.skill != "walk") {
          EXPECT_FALSE(k.object.empty()) << k.index;
        }
        EXPECT_FALSE(k.style.empty());
      }
      EXPECT_FALSE(p.layout.rooms.empty());
      EXPECT_NE(p.narrative.find("happy"), std::string::npos);
      EXPECT_NO_THROW(ValidateConfig(p, "plan"));
    }
  }
}

TEST_F(PlanTest, SameThemeAndSeedGiveTheSamePlanFile) {
  auto run = [&] {
    ScriptResult s =
        planner_->ScriptForTheme("a drunk student stumbles home and sleeps", Difficulty::kHard, 9);
    return PlanToJson(planner_->Place(s, *layouts_)).dump();
  };
  EXPECT_EQ(run(), run());
}

TEST_F(PlanTest, RoundTripsThroughTheFileAndRejectsBadFields) {
  ScriptResult s = planner_->ScriptForTheme("an angry man, later relaxed", Difficulty::kMid, 2);
  Plan p = planner_->Place(s, *layouts_);
  auto dir = sims::testing::TempDir("planner_plan");
  SavePlan(dir / "plan.json", p);
  Plan back = LoadPlan(dir / "plan.json");
  EXPECT_EQ(PlanToJson(back).dump(), PlanToJson(p).dump());
  nlohmann::json j = PlanToJson(p);
  j["keyframes"][1]["skill"] = "fly";
  try {
    PlanFromJson(j, "plan.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("plan.json: field 'keyframes[1].skill'"));
  }
  j = PlanToJson(p);
  j["difficulty"] = "extreme";
  EXPECT_THROW(PlanFromJson(j, "plan.json"), Error);
  j = PlanToJson(p);
  j["layout"]["mode"] = "floating";
  EXPECT_THROW(PlanFromJson(j, "plan.json"), Error);
}

TEST_F(PlanTest, ScriptFileInputAndAGivenScene) {
  auto dir = sims::testing::TempDir("planner_script_input");
  std::ofstream(dir / "story.json")
      << R"({"summary": "sits then lies", "emotion": "tired", "scene": "living room",
      "keyframes": [{"skill": "sitdown", "caption": "slumps into the couch", "furniture": "couch"},
                    {"skill": "liedown", "caption": "curls up on the side", "furniture": "couch"}]})";
  ScriptResult s = planner_->ScriptFromFile(dir / "story.json");
  EXPECT_EQ(s.planner, "script");
  EXPECT_EQ(s.script.keyframes.front().skill, Skill::kWalk);  // inserted
  scene::Scene house = scene::BuiltinHouse();
  Plan p = planner_->Place(s, house);
  EXPECT_EQ(p.layout.mode, "given");
  EXPECT_TRUE(p.AllPlaced());
  EXPECT_EQ(p.keyframes[1].object, "sofa_0");
  EXPECT_EQ(p.keyframes[1].room, "living_room");
  EXPECT_THAT(p.narrative, HasSubstr("sofa"));
  // A plan from the database materialises into a scene that holds every bound object.
  Plan q = planner_->Place(s, *layouts_);
  scene::Scene built = MaterializeLayout(q.layout);
  for (const PlanKeyframe& k : q.keyframes) {
    if (k.object.empty()) continue;
    EXPECT_NE(std::find_if(built.objects.begin(), built.objects.end(),
                           [&](const scene::Object& o) { return o.instance == k.object; }),
              built.objects.end())
        << k.object;
  }
}

}  // namespace
}  // namespace sims::planner
