// imitate_scripts' library path: the offline template imitation gives N valid, distinct,
// deterministic scripts that extend the database; with a fake LLM on 127.0.0.1 every answer is
// validated and duplicates (of each other and of the database) are dropped.
#include <fstream>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "planner/fake_llm_server.h"
#include "sims/planner/imitation.h"
#include "sims/planner/planner.h"

namespace sims::planner {
namespace {

using test_support::ChatOk;
using test_support::FakeServer;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

const ScriptDatabase& Db() {
  static const ScriptDatabase* db = new ScriptDatabase(ScriptDatabase::Load());
  return *db;
}

std::string Dump(const ImitationResult& r) {
  std::string s;
  for (const ImitatedScript& i : r.scripts) s += ShortScriptToJson(i.script).dump() + "\n";
  return s;
}

TEST(ImitationTest, OfflineGivesDistinctValidDeterministicScripts) {
  ImitationOptions o;
  o.count = 5;
  o.seed = 0;
  ImitationResult r = ImitateScripts(Db(), o);
  ASSERT_EQ(r.scripts.size(), 5u);
  std::set<std::string> db_signatures, signatures, emotions;
  for (const ShortScript& s : Db().scripts()) db_signatures.insert(KeyframeSignature(s.keyframes));
  for (std::size_t i = 0; i < r.scripts.size(); ++i) {
    const ImitatedScript& s = r.scripts[i];
    EXPECT_EQ(s.script.id, "imitated_s0_00" + std::to_string(i));
    EXPECT_NO_THROW(CheckDatabaseScript(s.script, s.script.id));
    std::string sig = KeyframeSignature(s.script.keyframes);
    EXPECT_TRUE(signatures.insert(sig).second) << sig;
    EXPECT_FALSE(db_signatures.count(sig)) << sig;
    emotions.insert(s.script.emotion);
    EXPECT_EQ(s.provenance["method"], "template");
    EXPECT_GE(s.provenance["sources"].size(), 1u);
    for (const auto& src : s.provenance["sources"]) {
      const ShortScript* from = Db().Find(src.get<std::string>());
      ASSERT_NE(from, nullptr);
      EXPECT_EQ(from->emotion, s.script.emotion);  // recombines same-emotion scripts only
    }
  }
  EXPECT_GE(emotions.size(), 4u);                     // emotions take turns
  EXPECT_EQ(Dump(ImitateScripts(Db(), o)), Dump(r));  // deterministic by seed
  o.seed = 1;
  EXPECT_NE(Dump(ImitateScripts(Db(), o)), Dump(r));
}

TEST(ImitationTest, OfflineScalesAndTheFolderExtendsTheDatabase) {
  ImitationOptions o;
  o.count = 40;
  o.seed = 3;
  ImitationResult r = ImitateScripts(Db(), o);
  ASSERT_EQ(r.scripts.size(), 40u) << r.dropped.size() << " dropped";
  fs::path dir = sims::testing::TempDir("imitation_db");
  std::vector<fs::path> files = WriteImitatedScripts(r, dir);
  ASSERT_EQ(files.size(), 40u);
  std::ifstream in(files[0]);
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["provenance"]["seed"], 3);
  EXPECT_EQ(j["id"], files[0].stem().string());
  // Loadable as an extra database (strict grammar, unique ids) and used by the planner.
  ScriptDatabase extended = ScriptDatabase::LoadWithExtras({}, {dir});
  EXPECT_EQ(extended.size(), Db().size() + 40);
  PlannerConfig config = LoadPlannerConfig();
  config.extra_scripts = {dir.string()};
  StoryPlanner planner(config);
  EXPECT_EQ(planner.scripts().size(), Db().size() + 40);
  EXPECT_NE(planner.scripts().Find("imitated_s3_039"), nullptr);
  ScriptResult plan = planner.ScriptForTheme("a tired evening at home", Difficulty::kMid, 0);
  EXPECT_GE(plan.script.Interactions(), 3);
  // Missing extras and duplicate ids are clear errors.
  try {
    ScriptDatabase::LoadWithExtras({}, {dir, files[0]});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("field 'id': expected an id not used by"));
  }
  EXPECT_THROW(ScriptDatabase::LoadWithExtras({}, {dir / "nope"}), Error);
}

// Answers in the short-script format, as a model would write them.
std::string Answer(const std::string& furniture, const std::string& caption) {
  nlohmann::json j = {{"summary", "A sad person sits down for a while."},
                      {"emotion", "sad"},
                      {"scene", "living room"},
                      {"keyframes",
                       {{{"skill", "loco"},
                         {"emotion/style", "sad"},
                         {"caption", "walks slowly with the head bowed"},
                         {"furniture", furniture}},
                        {{"skill", "sitdown"},
                         {"emotion/style", "sad"},
                         {"caption", caption},
                         {"furniture", furniture}}}}};
  return j.dump();
}

TEST(ImitationTest, FakeEndpointAnswersAreValidatedAndDuplicatesDropped) {
  const ShortScript& existing = Db().scripts().front();
  std::vector<FakeServer::Reply> replies = {
      {ChatOk(Answer("couch", "sits on the sofa leaning back"))},
      {ChatOk(Answer("sofa", "sits on the sofa leaning back, sighing"))},  // same keyframes
      {ChatOk(ShortScriptToJson(existing).dump())},                        // copies the database
      {ChatOk(R"({"summary": "x", "emotion": "sad", "scene": "living room",
                 "keyframes": [{"skill": "fly", "furniture": "sofa"}]})")},
      {ChatOk("no script today")},
      {ChatOk(Answer("footstool", "sits on the stool with legs crossed"))},
  };
  FakeServer server(replies);
  ImitationOptions o;
  o.count = 2;
  o.seed = 5;
  o.endpoint = server.url();
  o.model = "fake-llm";
  ImitationResult r = ImitateScripts(Db(), o);
  ASSERT_EQ(r.scripts.size(), 2u);
  EXPECT_EQ(r.attempts, 6);
  ASSERT_EQ(r.dropped.size(), 4u);
  EXPECT_THAT(r.dropped[0], HasSubstr("duplicate keyframe sequence"));
  EXPECT_THAT(r.dropped[1], HasSubstr("duplicate keyframe sequence"));
  EXPECT_THAT(r.dropped[2], HasSubstr("field 'keyframes[0].skill'"));
  EXPECT_THAT(r.dropped[3], HasSubstr("expected valid JSON"));
  EXPECT_EQ(r.scripts[0].script.keyframes[1].furniture, "sofa");
  EXPECT_EQ(r.scripts[1].script.keyframes[1].furniture, "stool");
  EXPECT_EQ(r.scripts[1].script.keyframes[1].style, "legs_crossed");
  const nlohmann::json& p = r.scripts[1].provenance;
  EXPECT_EQ(p["method"], "llm");
  EXPECT_EQ(p["model"], "fake-llm");
  EXPECT_EQ(p["seed"], 5);
  EXPECT_EQ(p["attempt"], 5);
  EXPECT_EQ(p["sources"].size(), 3u);  // the few-shot examples
  // Each request shows same-emotion examples and asks for that emotion.
  std::vector<std::string> reqs = server.requests();
  ASSERT_EQ(reqs.size(), 6u);
  nlohmann::json body = nlohmann::json::parse(reqs[0].substr(reqs[0].find("\r\n\r\n") + 4));
  EXPECT_EQ(body["model"], "fake-llm");
  std::string user = body["messages"][1]["content"];
  std::string emotion = r.scripts[0].provenance["requested_emotion"];
  EXPECT_THAT(user, HasSubstr("Emotion: " + emotion));
  for (const auto& id : r.scripts[0].provenance["sources"])
    EXPECT_THAT(user, HasSubstr(Db().Find(id.get<std::string>())->summary));
}

TEST(ImitationTest, UnreachableOrSlowEndpointStopsWithAClearError) {
  FakeServer server({{ChatOk(Answer("sofa", "sits")), 2000}});
  ImitationOptions o;
  o.count = 3;
  o.endpoint = server.url();
  o.timeout_s = 0.3;
  try {
    ImitateScripts(Db(), o);
    ADD_FAILURE() << "no error";
  } catch (const LlmError& e) {
    EXPECT_EQ(e.kind(), LlmError::Kind::kTimeout);
    EXPECT_THAT(e.what(), HasSubstr("LLM endpoint " + server.url()));
  }
}

}  // namespace
}  // namespace sims::planner
