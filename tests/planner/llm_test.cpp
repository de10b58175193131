// LLM back-end against a tiny HTTP server on 127.0.0.1 that replays recorded replies: valid
// replies are used, malformed ones, HTTP errors and time-outs fall back to the embedded planner.

#include <chrono>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "planner/fake_llm_server.h"
#include "sims/core/environment.h"
#include "sims/core/http.h"
#include "sims/planner/llm_client.h"
#include "sims/planner/planner.h"

namespace sims::planner {
namespace {

using test_support::FakeServer;
using test_support::HttpOk;
using ::testing::HasSubstr;

std::string ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string Recorded(const std::string& name) {
  return HttpOk(ReadFile(sims::testing::TestData("planner/llm/" + name)));
}

class LlmTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { config_ = new PlannerConfig(LoadPlannerConfig()); }
  static void TearDownTestSuite() {
    delete config_;
    config_ = nullptr;
  }
  StoryPlanner Planner(const std::string& endpoint, double timeout_s = 5.0) const {
    PlannerConfig c = *config_;
    c.llm.endpoint = endpoint;
    c.llm.model = "test-model";
    c.llm.api_key = "secret";
    c.llm.timeout_s = timeout_s;
    return StoryPlanner(c);
  }
  static PlannerConfig* config_;
};
PlannerConfig* LlmTest::config_ = nullptr;

const char* kTheme = "A person is happy at first, then gets depressed";

TEST_F(LlmTest, ValidReplyIsUsed) {
  FakeServer server({{Recorded("valid_reply.json")}});
  StoryPlanner planner = Planner(server.url());
  ScriptResult r = planner.ScriptForTheme(kTheme, Difficulty::kMid, 7);
  EXPECT_EQ(r.planner, "llm:test-model");
  EXPECT_TRUE(r.note.empty()) << r.note;
  EXPECT_EQ(r.script.script_ids,
            (std::vector<std::string>{"bedroom_happy_1", "living_room_sad_1"}));
  EXPECT_EQ(r.script.EmotionSequence(), (std::vector<std::string>{"happy", "sad"}));
  EXPECT_THAT(r.script.narrative, HasSubstr("Bursting with joy"));
  EXPECT_TRUE(CheckGrammar(r.script.keyframes).empty());
  // What the client sent: the chat-completions path, the key, the model and both prompts.
  std::vector<std::string> reqs = server.requests();
  ASSERT_EQ(reqs.size(), 1u);
  EXPECT_THAT(reqs[0], HasSubstr("POST /v1/chat/completions HTTP/1.1"));
  EXPECT_THAT(reqs[0], HasSubstr("Authorization: Bearer secret"));
  nlohmann::json body = nlohmann::json::parse(reqs[0].substr(reqs[0].find("\r\n\r\n") + 4));
  EXPECT_EQ(body["model"], "test-model");
  EXPECT_EQ(body["seed"], 7);
  EXPECT_EQ(body["messages"][0]["role"], "system");
  EXPECT_THAT(body["messages"][1]["content"].get<std::string>(), HasSubstr(kTheme));
  EXPECT_THAT(body["messages"][1]["content"].get<std::string>(),
              HasSubstr("\"id\":\"bedroom_happy_1\""));
  EXPECT_EQ(body["response_format"]["type"], "json_object");
  // The plan keeps the LLM's narrative.
  Plan plan = planner.Place(r, BuiltinLayoutDatabase());
  EXPECT_EQ(plan.planner, "llm:test-model");
  EXPECT_THAT(plan.narrative, HasSubstr("Bursting with joy"));
}

TEST_F(LlmTest, FencedReplyWithANewShortScriptIsValidated) {
  FakeServer server({{Recorded("fenced_custom_reply.json")}});
  ScriptResult r = Planner(server.url()).ScriptForTheme(kTheme, Difficulty::kMid, 1);
  EXPECT_EQ(r.planner, "llm:test-model") << r.note;
  ASSERT_GE(r.script.keyframes.size(), 3u);
  EXPECT_EQ(r.script.keyframes[0].furniture, "bookshelf");  // alias resolved by the loader
  EXPECT_EQ(r.script.keyframes[1].style, "left_high");
  EXPECT_EQ(r.script.script_ids.back(), "library_sad_1");
  EXPECT_FALSE(r.script.narrative.empty());  // none given: the template writes one
}

TEST_F(LlmTest, MalformedRepliesFallBack) {
  struct Case {
    std::string reply;
    std::string reason;
  };
  std::vector<Case> cases = {
      {Recorded("single_quotes_reply.json"), "single quotes"},
      {Recorded("bad_skill_reply.json"), "scripts[0]: field 'keyframes[1].skill'"},
      {Recorded("unknown_id_reply.json"), "field 'scripts[1]'"},
      {Recorded("too_short_reply.json"), "between 3 and 4 interactions"},
      {Recorded("not_a_completion.json"), "choices[0].message.content"},
      {"HTTP/1.1 500 Internal Server Error\r\nContent-Length: 5\r\n\r\noops!", "HTTP 500"},
      {"garbage that is not http\r\n\r\n", "not an HTTP response"},
  };
  StoryPlanner fallback_reference = Planner("");
  ScriptResult embedded = fallback_reference.EmbeddedScript(kTheme, Difficulty::kMid, 2);
  for (const Case& c : cases) {
    FakeServer server({{c.reply}});
    ScriptResult r = Planner(server.url()).ScriptForTheme(kTheme, Difficulty::kMid, 2);
    EXPECT_EQ(r.planner, "embedded") << c.reason;
    EXPECT_THAT(r.note, HasSubstr("fell back to the embedded planner"));
    EXPECT_THAT(r.note, HasSubstr(c.reason));
    EXPECT_EQ(KeyframesToJson(r.script.keyframes).dump(),
              KeyframesToJson(embedded.script.keyframes).dump());
  }
}

TEST_F(LlmTest, TimeOutFallsBackQuickly) {
  FakeServer server({{Recorded("valid_reply.json"), 1500}});
  auto start = std::chrono::steady_clock::now();
  ScriptResult r = Planner(server.url(), 0.3).ScriptForTheme(kTheme, Difficulty::kSimple, 4);
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.planner, "embedded");
  EXPECT_THAT(r.note, HasSubstr("timed out"));
  EXPECT_LT(elapsed, 1.2);
  EXPECT_EQ(r.script.Interactions(), 2);
}

TEST_F(LlmTest, NoEndpointOrUnreachableServerFallsBack) {
  ScriptResult none = Planner("").ScriptForTheme(kTheme, Difficulty::kMid, 1);
  EXPECT_EQ(none.planner, "embedded");
  EXPECT_THAT(none.note, HasSubstr("no LLM endpoint configured"));
  int port;
  {
    FakeServer closed({});
    port = std::stoi(closed.url().substr(17, 5));
  }  // nothing listens there any more
  ScriptResult refused = Planner("http://127.0.0.1:" + std::to_string(port) + "/v1")
                             .ScriptForTheme(kTheme, Difficulty::kMid, 1);
  EXPECT_EQ(refused.planner, "embedded");
  EXPECT_THAT(refused.note, HasSubstr("cannot connect"));
  ScriptResult https =
      Planner("https://api.example.com/v1").ScriptForTheme(kTheme, Difficulty::kMid, 1);
  EXPECT_THAT(https.note, HasSubstr("https is not supported"));
}

// Tests (and the library) never read $SIMS_LLM_ENDPOINT: only an explicit Environment fills an
// empty endpoint. With an endpoint installed process-wide (as the test main does from a user's
// shell), the "no LLM" planners here must still not contact it; the last request, which passes
// the environment on as plan_story does, shows the server would have answered.
TEST_F(LlmTest, InstalledEnvironmentIsNeverConsultedImplicitly) {
  struct Restore {
    Environment saved = InstalledEnvironment();
    ~Restore() { InstallEnvironment(saved); }
  } restore;
  FakeServer server({{Recorded("valid_reply.json")}});
  Environment with_llm = restore.saved;
  with_llm.llm_endpoint = server.url();
  with_llm.llm_model = "env-model";
  InstallEnvironment(with_llm);
  ScriptResult none = Planner("").ScriptForTheme(kTheme, Difficulty::kMid, 1);
  EXPECT_EQ(none.planner, "embedded");
  EXPECT_THAT(none.note, HasSubstr("no LLM endpoint configured"));
  PlanRequest req;
  req.theme = kTheme;
  EXPECT_EQ(PlanStory(req).planner, "embedded");
  EXPECT_TRUE(server.requests().empty());
  req.environment = InstalledEnvironment();
  const Plan used = PlanStory(req);
  EXPECT_EQ(used.planner, "llm:env-model");
  EXPECT_EQ(server.requests().size(), 1u);
}

TEST(HttpClientTest, DecodesChunkedRepliesAndParsesUrls) {
  std::string body = ReadFile(sims::testing::TestData("planner/llm/valid_reply.json"));
  std::string chunked = "HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n";
  for (std::size_t pos = 0; pos < body.size(); pos += 100) {
    std::string piece = body.substr(pos, 100);
    std::stringstream hex;
    hex << std::hex << piece.size();
    chunked += hex.str() + "\r\n" + piece + "\r\n";
  }
  chunked += "0\r\n\r\n";
  FakeServer server({{chunked}});
  http::Response r = http::Post(server.url() + "/chat/completions", {}, "{}", 5.0);
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.body, body);

  http::Url u = http::ParseUrl("http://localhost:8080/v1/chat/completions?x=1");
  EXPECT_EQ(u.host, "localhost");
  EXPECT_EQ(u.port, 8080);
  EXPECT_EQ(u.path, "/v1/chat/completions?x=1");
  EXPECT_EQ(http::ParseUrl("http://[::1]:9000/").host, "::1");
  EXPECT_EQ(ChatCompletionsUrl("http://h:1/v1/"), "http://h:1/v1/chat/completions");
  EXPECT_EQ(ChatCompletionsUrl("http://h:1"), "http://h:1/v1/chat/completions");
  EXPECT_EQ(ChatCompletionsUrl("http://h/api/chat/completions"), "http://h/api/chat/completions");
  EXPECT_THROW(http::ParseUrl("ftp://h"), http::HttpError);
  EXPECT_THROW(http::ParseUrl("http://h:99999/"), http::HttpError);
  EXPECT_THROW(ChatCompletionsUrl("ftp://h"), LlmError);  // the planner's error, for fall-back
  EXPECT_EQ(StripToJson("Sure!\n```json\n{\"a\": 1}\n```\n"), "{\"a\": 1}");
}

}  // namespace
}  // namespace sims::planner
