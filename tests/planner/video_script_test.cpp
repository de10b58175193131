// extract_script's library path against a fake vision-language server on 127.0.0.1: frames
// sampled from a 10 s ffmpeg test video, a well-formed answer, malformed ones, a time-out and
// out-of-vocabulary furniture; every failure names the endpoint and field and writes nothing.
#include <chrono>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "planner/fake_llm_server.h"
#include "sims/io/subprocess.h"
#include "sims/io/video_frames.h"
#include "sims/planner/llm_client.h"
#include "sims/planner/video_script.h"

namespace sims::planner {
namespace {

using test_support::ChatOk;
using test_support::FakeServer;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

nlohmann::json ReadJson(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

// A valid answer a VLM could give: aliases (couch, sitdown), no get-up before the walk.
const char* kGoodAnswer = R"({
  "summary": "A tired person drags themself to the couch, sits down and then lies on the bed.",
  "emotion": "exhausted", "scene": "bedroom",
  "keyframes": [
    {"skill": "loco", "emotion/style": "tired", "caption": "shuffles slowly with the head bowed", "furniture": "couch"},
    {"skill": "sitdown", "emotion/style": "tired", "caption": "sits on the couch leaning back", "furniture": "couch"},
    {"skill": "liedown", "emotion/style": "tired", "caption": "lies on the bed on the side", "furniture": "bed"}
  ]})";

// Furniture a model may name that is not in the vocabulary.
const char* kUnknownFurnitureAnswer = R"({
  "summary": "Someone relaxes in a rocking chair, then takes a book from the bookcases.",
  "emotion": "relaxed", "scene": "cozy living room",
  "keyframes": [
    {"skill": "walking", "emotion/style": "calm", "caption": "strolls to the chair", "furniture": "wooden rocking chair"},
    {"skill": "sitting down", "emotion/style": "calm", "caption": "sits leaning back", "furniture": "wooden rocking chair"},
    {"skill": "stand up", "emotion/style": "calm", "caption": "gets up", "furniture": "wooden rocking chair"},
    {"skill": "touch", "emotion/style": "calm", "caption": "reaches with the right hand high to the shelf", "furniture": "tall bookcases"}
  ]})";

class VideoScriptTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!io::ProgramAvailable("ffmpeg") || !io::ProgramAvailable("ffprobe")) return;
    dir_ = new fs::path(sims::testing::TempDir("video_script"));
    video_ = new fs::path(*dir_ / "clip.mp4");
    std::string log;
    int code = io::RunCommand(
        {"ffmpeg", "-nostdin", "-v", "error", "-y", "-f", "lavfi", "-i",
         "testsrc=duration=10:size=160x120:rate=10", "-pix_fmt", "yuv420p", video_->string()},
        &log);
    ASSERT_EQ(code, 0) << log;
    io::FrameSamplingOptions o;
    o.count = 4;
    o.width = 96;
    frames_ = new std::vector<ScriptFrame>;
    for (const io::VideoFrame& f : io::SampleVideoFrames(*video_, o, *dir_ / "sampled"))
      frames_->push_back({f.path, f.time_s});
  }
  static void TearDownTestSuite() {
    delete frames_;
    delete video_;
    delete dir_;
    frames_ = nullptr;
    video_ = nullptr;
    dir_ = nullptr;
  }
  void SetUp() override {
    if (!frames_) GTEST_SKIP() << "ffmpeg is not installed (cmake/setup.sh installs it)";
    out_dir_ = sims::testing::TempDir("video_script_out");
  }
  VideoScriptOptions Options(const std::string& endpoint, double timeout_s = 5.0) const {
    VideoScriptOptions o;
    o.endpoint = endpoint;
    o.model = "fake-vlm";
    o.api_key = "k";
    o.timeout_s = timeout_s;
    o.video = "clip.mp4";
    return o;
  }
  // Nothing of an extraction may exist after a failure.
  void ExpectNoOutputs(const fs::path& out) const {
    EXPECT_FALSE(fs::exists(out)) << out;
    EXPECT_FALSE(fs::exists(FramesDirFor(out))) << FramesDirFor(out);
    for (const auto& e : fs::directory_iterator(out_dir_))
      ADD_FAILURE() << "left behind: " << e.path();
  }
  static fs::path* dir_;
  static fs::path* video_;
  static std::vector<ScriptFrame>* frames_;
  fs::path out_dir_;
};
fs::path* VideoScriptTest::dir_ = nullptr;
fs::path* VideoScriptTest::video_ = nullptr;
std::vector<ScriptFrame>* VideoScriptTest::frames_ = nullptr;

TEST_F(VideoScriptTest, SamplesEvenlySpacedFramesAndSceneChanges) {
  ASSERT_EQ(frames_->size(), 4u);
  for (std::size_t i = 0; i < frames_->size(); ++i) {
    EXPECT_NEAR((*frames_)[i].time_s, 1.25 + 2.5 * i, 1e-6);
    EXPECT_EQ((*frames_)[i].path.filename(), fs::path(i == 0   ? "000.jpg"
                                                      : i == 1 ? "001.jpg"
                                                      : i == 2 ? "002.jpg"
                                                               : "003.jpg"));
  }
  io::FrameSamplingOptions scene;
  scene.mode = "scene";
  scene.count = 3;
  scene.width = 64;
  auto cuts = io::SampleVideoFrames(*video_, scene, out_dir_ / "scene");
  ASSERT_GE(cuts.size(), 1u);  // the first frame at least; the test pattern barely changes
  EXPECT_LE(cuts.size(), 3u);
  EXPECT_TRUE(fs::is_regular_file(cuts[0].path));
  EXPECT_FALSE(fs::exists(out_dir_ / "scene" / ".scene"));
  try {
    io::SampleVideoFrames(out_dir_ / "missing.mp4", scene, out_dir_ / "x");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.mp4"));
  }
}

TEST_F(VideoScriptTest, WellFormedAnswerWritesAValidScriptAndItsFrames) {
  FakeServer server({{ChatOk(std::string("```json\n") + kGoodAnswer + "\n```")}});
  fs::path out = out_dir_ / "tired_clip.json";
  VideoScriptResult r = ExtractVideoScript(*frames_, Options(server.url()), out);
  // The request: system prompt, then text + one image_url part per frame.
  std::vector<std::string> reqs = server.requests();
  ASSERT_EQ(reqs.size(), 1u);
  EXPECT_THAT(reqs[0], HasSubstr("POST /v1/chat/completions"));
  EXPECT_THAT(reqs[0], HasSubstr("Authorization: Bearer k"));
  nlohmann::json body = nlohmann::json::parse(reqs[0].substr(reqs[0].find("\r\n\r\n") + 4));
  EXPECT_EQ(body["model"], "fake-vlm");
  EXPECT_EQ(body["messages"][0]["role"], "system");
  const nlohmann::json& parts = body["messages"][1]["content"];
  ASSERT_EQ(parts.size(), 5u);
  EXPECT_EQ(parts[0]["type"], "text");
  EXPECT_THAT(parts[0]["text"].get<std::string>(), HasSubstr("1.2, 3.8, 6.2, 8.8"));
  EXPECT_EQ(parts[1]["type"], "image_url");
  EXPECT_EQ(parts[1]["image_url"]["url"].get<std::string>().rfind("data:image/jpeg;base64,/9j/", 0),
            0u);
  // The script: canonical names, transitions inserted, database grammar.
  EXPECT_EQ(r.script.emotion, "tired");
  EXPECT_EQ(r.script.id, "tired_clip");
  ShortScript loaded = LoadShortScript(out, GrammarMode::kStrict);
  EXPECT_EQ(KeyframeSignature(loaded.keyframes), KeyframeSignature(r.script.keyframes));
  std::vector<std::string> skills;
  for (const Keyframe& k : loaded.keyframes) skills.push_back(SkillName(k.skill));
  EXPECT_EQ(skills, (std::vector<std::string>{"walk", "sit", "getup", "walk", "lie"}));
  EXPECT_EQ(loaded.keyframes[1].furniture, "sofa");
  nlohmann::json j = ReadJson(out);
  EXPECT_EQ(j["provenance"]["method"], "video");
  EXPECT_EQ(j["provenance"]["video"], "clip.mp4");
  EXPECT_EQ(j["provenance"]["model"], "fake-vlm");
  ASSERT_EQ(j["provenance"]["frames"].size(), 4u);
  EXPECT_EQ(j["provenance"]["frames"][3]["file"], "tired_clip_frames/003.jpg");
  for (int i = 0; i < 4; ++i)
    EXPECT_TRUE(
        fs::is_regular_file(out_dir_ / "tired_clip_frames" / ("00" + std::to_string(i) + ".jpg")));
  // The folder works as an extra database.
  ScriptDatabase db = ScriptDatabase::LoadWithExtras({}, {out_dir_});
  EXPECT_EQ(db.size(), ScriptDatabase::Load().size() + 1);
  EXPECT_NE(db.Find("tired_clip"), nullptr);
}

TEST_F(VideoScriptTest, MalformedAnswersGiveOneClearErrorAndNoFile) {
  struct Case {
    std::string raw;
    std::string expect;
  };
  std::vector<Case> cases = {
      {ChatOk("The person looks tired and sits down."), "expected valid JSON"},
      {ChatOk("{'summary': 'x', 'keyframes': []}"), "single quotes"},
      {ChatOk(R"({"summary": "x", "emotion": "sad", "scene": "bedroom"})"),
       "field 'keyframes': expected a non-empty list"},
      {ChatOk(R"({"summary": "x", "emotion": "sad", "scene": "bedroom", "keyframes": [
          {"skill": "juggle", "caption": "juggles", "furniture": "bed"}]})"),
       "field 'keyframes[0].skill'"},
      {ChatOk(R"({"summary": "x", "emotion": "sad", "scene": "bedroom", "keyframes": [
          {"skill": "standup", "caption": "gets up"}, {"skill": "sit", "furniture": "bed"}]})"),
       "field 'keyframes[0].skill': expected get-up only after sit or lie"},
      {ChatOk(R"({"emotion": "sad", "scene": "bedroom", "keyframes": [
          {"skill": "sit", "caption": "sits", "furniture": "bed"}]})"),
       "field 'summary'"},
      {ChatOk(R"({"summary": "x", "emotion": "sad", "scene": "bedroom", "keyframes": [
          {"skill": "walk", "caption": "walks", "furniture": "floor"}]})"),
       "at least one sit, lie or reach keyframe"},
      {R"({"no": "choices"})", "connection closed before the HTTP headers ended"},
      {test_support::HttpOk(R"({"object": "error"})"), "choices[0].message.content"},
      {"HTTP/1.1 404 Not Found\r\nContent-Length: 9\r\n\r\nno model!", "HTTP 404"},
  };
  for (const Case& c : cases) {
    FakeServer server({{c.raw}});
    fs::path out = out_dir_ / "bad.json";
    try {
      ExtractVideoScript(*frames_, Options(server.url()), out);
      ADD_FAILURE() << "no error for " << c.expect;
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(server.url())) << c.expect;
      EXPECT_THAT(e.what(), HasSubstr(c.expect));
    }
    ExpectNoOutputs(out);
  }
}

TEST_F(VideoScriptTest, TimeOutGivesAClearErrorQuicklyAndNoFile) {
  FakeServer server({{ChatOk(kGoodAnswer), 2000}});
  fs::path out = out_dir_ / "slow.json";
  auto start = std::chrono::steady_clock::now();
  try {
    ExtractVideoScript(*frames_, Options(server.url(), 0.3), out);
    ADD_FAILURE() << "no error";
  } catch (const LlmError& e) {
    EXPECT_EQ(e.kind(), LlmError::Kind::kTimeout);
    EXPECT_THAT(e.what(), HasSubstr("VLM endpoint " + server.url()));
    EXPECT_THAT(e.what(), HasSubstr("timed out"));
  }
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(elapsed, 1.5);
  ExpectNoOutputs(out);
}

TEST_F(VideoScriptTest, UnknownFurnitureIsMappedOrRejected) {
  {
    FakeServer server({{ChatOk(kUnknownFurnitureAnswer)}});
    fs::path out = out_dir_ / "mapped.json";
    VideoScriptResult r = ExtractVideoScript(*frames_, Options(server.url()), out);
    EXPECT_EQ(r.script.scene, "living room");
    EXPECT_EQ(r.script.keyframes[1].skill, Skill::kSit);
    EXPECT_EQ(r.script.keyframes[1].furniture, "chair");
    EXPECT_EQ(r.script.keyframes.back().furniture, "bookshelf");
    EXPECT_EQ(r.script.keyframes.back().style, "right_high");
    std::string notes;
    for (const std::string& n : r.notes) notes += n + "\n";
    EXPECT_THAT(notes, HasSubstr("keyframes[0].furniture: 'wooden rocking chair' -> 'chair'"));
    EXPECT_THAT(notes, HasSubstr("'tall bookcases' -> 'bookshelf'"));
    EXPECT_THAT(notes, HasSubstr("keyframes[1].skill: 'sitting down' -> 'sit'"));
    EXPECT_EQ(ReadJson(out)["provenance"]["notes"].size(), r.notes.size());
    LoadShortScript(out, GrammarMode::kStrict);
  }
  {
    FakeServer server({{ChatOk(kUnknownFurnitureAnswer)}});
    VideoScriptOptions o = Options(server.url());
    o.unknown = UnknownTerms::kReject;
    fs::path out = out_dir_ / "rejected.json";
    fs::remove_all(out_dir_);
    fs::create_directories(out_dir_);
    try {
      ExtractVideoScript(*frames_, o, out);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("field 'scene'"));  // the first unknown term
    }
    ExpectNoOutputs(out);
  }
  {
    std::string answer = R"({"summary": "A person takes a bath.", "emotion": "relaxed",
        "scene": "bedroom", "keyframes": [{"skill": "lie", "caption": "lies in the bathtub",
        "furniture": "bathtub"}]})";
    FakeServer server({{ChatOk(answer)}});
    fs::path out = out_dir_ / "bath.json";
    try {
      ExtractVideoScript(*frames_, Options(server.url()), out);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("field 'keyframes[0].furniture'"));
      EXPECT_THAT(e.what(), HasSubstr("nothing close was found, got 'bathtub'"));
    }
    ExpectNoOutputs(out);
  }
}

TEST_F(VideoScriptTest, DryRunWritesTheRequestWithoutSending) {
  VideoScriptOptions o = Options("");
  fs::path out = out_dir_ / "request.json";
  VideoScriptResult r = WriteVideoScriptRequest(*frames_, o, out);
  nlohmann::json req = ReadJson(out);
  EXPECT_EQ(req["model"], "fake-vlm");
  EXPECT_EQ(req["response_format"]["type"], "json_object");
  EXPECT_THAT(req["messages"][0]["content"].get<std::string>(), HasSubstr("armchair"));
  EXPECT_EQ(req["messages"][1]["content"].size(), 5u);
  EXPECT_TRUE(fs::is_regular_file(r.frames_dir / "000.jpg"));
  // Without an endpoint a real extraction refuses before doing anything.
  EXPECT_THROW(ExtractVideoScript(*frames_, o, out_dir_ / "none.json"), Error);
  EXPECT_FALSE(fs::exists(out_dir_ / "none.json"));
}

TEST(VocabularyNearestTest, MapsFreeTextToTheVocabulary) {
  const Vocabulary& v = Vocabulary::Default();
  EXPECT_EQ(v.NearestFurniture("wooden rocking chairs")->canonical, "chair");
  EXPECT_EQ(v.NearestFurniture("armchiar")->canonical, "armchair");
  EXPECT_EQ(v.NearestFurniture("Living-room couch")->canonical, "sofa");
  EXPECT_EQ(v.NearestFurniture("benches")->canonical, "bench");
  EXPECT_FALSE(v.NearestFurniture("bathtub"));
  EXPECT_EQ(v.NearestSkill("sitting down")->canonical, "sit");
  EXPECT_EQ(v.NearestSkill("walked over")->canonical, "walk");
  EXPECT_EQ(v.NearestSkill("sat")->canonical, "sit");
  EXPECT_EQ(v.NearestSkill("stood up")->canonical, "getup");
  EXPECT_FALSE(v.NearestSkill("juggle"));
  EXPECT_EQ(v.NearestEmotion("very sleepy")->canonical, "tired");
  EXPECT_EQ(v.NearestRoomType("a cozy bedroom")->canonical, "bedroom");
}

TEST(Base64Test, MatchesRfc4648Vectors) {
  EXPECT_EQ(Base64Encode(""), "");
  EXPECT_EQ(Base64Encode("f"), "Zg==");
  EXPECT_EQ(Base64Encode("fo"), "Zm8=");
  EXPECT_EQ(Base64Encode("foo"), "Zm9v");
  EXPECT_EQ(Base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Base64Encode(std::string("\xff\xd8\xff", 3)), "/9j/");
}

}  // namespace
}  // namespace sims::planner
