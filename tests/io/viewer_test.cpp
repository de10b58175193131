// The web viewer end to end: story outputs served on 127.0.0.1, loaded in headless Chromium.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "common/test_util.h"
#include "io/cdp_client.h"
#include "io/io_test_util.h"
#include "sims/core/error.h"
#include "sims/io/http_server.h"
#include "sims/io/story_outputs.h"
#include "sims/io/subprocess.h"

namespace sims::io {
namespace {

using nlohmann::json;

std::string Fetch(const std::string& url, std::string* headers = nullptr) {
  // A raw request through bash's /dev/tcp keeps the test free of HTTP client libraries.
  const auto colon = url.find(':', 7);
  const auto slash = url.find('/', colon);
  const std::string host = url.substr(7, colon - 7),
                    port = url.substr(colon + 1, slash - colon - 1);
  const std::string path = url.substr(slash);
  std::string out;
  RunCommand({"bash", "-c",
              "exec 5<>/dev/tcp/" + host + "/" + port + "; printf 'GET " + path +
                  " HTTP/1.1\\r\\nHost: x\\r\\nConnection: close\\r\\n\\r\\n' >&5; cat <&5"},
             &out);
  const auto sep = out.find("\r\n\r\n");
  if (headers) *headers = out.substr(0, sep);
  return sep == std::string::npos ? "" : out.substr(sep + 4);
}

TEST(HttpServerTest, ServesFilesWithTypesAndStaysInsideRoot) {
  const auto dir = sims::testing::TempDir("io_http");
  std::filesystem::create_directories(dir / "sub");
  std::ofstream(dir / "index.html") << "<p>hi</p>";
  std::ofstream(dir / "sub" / "a.js") << "export const a = 1;";
  std::ofstream(dir.parent_path() / "io_http_secret.txt") << "secret";
  StaticHttpServer server(dir);
  EXPECT_GT(server.port(), 0);
  std::string h;
  EXPECT_EQ(Fetch(server.url(), &h), "<p>hi</p>");
  EXPECT_NE(h.find("200 OK"), std::string::npos) << h;
  EXPECT_NE(h.find("text/html"), std::string::npos) << h;
  EXPECT_EQ(Fetch(server.url() + "sub/a.js?v=1", &h), "export const a = 1;");
  EXPECT_NE(h.find("text/javascript"), std::string::npos) << h;
  Fetch(server.url() + "nope.txt", &h);
  EXPECT_NE(h.find("404"), std::string::npos) << h;
  Fetch(server.url() + "../io_http_secret.txt", &h);
  EXPECT_NE(h.find("404"), std::string::npos) << h;
  Fetch(server.url() + "sub/%2e%2e/%2e%2e/io_http_secret.txt", &h);
  EXPECT_NE(h.find("404"), std::string::npos) << h;
  EXPECT_GE(server.requests(), 5);
  EXPECT_EQ(ContentTypeFor("x.glb"), "model/gltf-binary");
}

TEST(StoryOutputsTest, WritesEveryFileAndNoTemporaries) {
  const auto dir = sims::testing::TempDir("io_outputs");
  const MotionRecord rec = testing::TestRecord(0.5);
  const StoryOutputs out = WriteStoryOutputs(dir, rec, testing::TestScene());
  for (const char* f :
       {"motion.json", "motion.bvh", "scene.glb", "index.html", "viewer.js",
        "three/build/three.module.min.js", "three/examples/jsm/loaders/GLTFLoader.js",
        "three/examples/jsm/utils/BufferGeometryUtils.js",
        "three/examples/jsm/controls/OrbitControls.js", "three/LICENSE"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  EXPECT_EQ(out.files.size(), 4u);
  EXPECT_FALSE(out.video.has_value());
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  // The BVH is the motion module's humanoid export, with the glTF's skeleton names.
  const motion::BvhMotion bvh = motion::ReadBvh(dir / "motion.bvh");
  EXPECT_EQ(bvh.num_frames, rec.num_frames());
  EXPECT_EQ(bvh.joints[0].name, "pelvis");
  // Writing again over an existing folder works (three/ is kept when up to date).
  EXPECT_NO_THROW(WriteStoryOutputs(dir, rec, testing::TestScene()));
}

TEST(StoryOutputsTest, FailedVideoLeavesEarlierOutputsAndNoPartialFile) {
  const auto dir = sims::testing::TempDir("io_outputs_fail");
  StoryOutputOptions opt;
  opt.viewer = false;
  opt.video = true;
  opt.video_options.ffmpeg = "false";  // exists, exits 1 at once
  opt.video_options.progress = false;
  opt.video_options.width = 32;
  opt.video_options.height = 32;
  EXPECT_THROW(WriteStoryOutputs(dir, testing::TestRecord(0.2), testing::TestScene(), opt), Error);
  EXPECT_TRUE(std::filesystem::exists(dir / "motion.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "scene.glb"));
  EXPECT_FALSE(std::filesystem::exists(dir / "story.mp4"));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(ViewerTest, PlaysInHeadlessChromium) {
  if (testing::ChromiumPath().empty())
    GTEST_SKIP() << "Chromium is not installed (/usr/bin/chromium; cmake/setup.sh installs it)";
  const auto dir = sims::testing::TempDir("io_viewer");
  const MotionRecord rec = testing::TestRecord(2.0);
  ASSERT_EQ(rec.keyframes[1].start_frame, 30);
  WriteStoryOutputs(dir / "story", rec, testing::TestScene());
  StaticHttpServer server(dir / "story");
  testing::CdpBrowser browser(dir / "profile", 1000, 700);
  browser.Navigate(server.url());
  const bool ready = browser.WaitFor("window.simsViewer && window.simsViewer.ready", 30);
  std::string errors;
  for (const auto& e : browser.errors()) errors += e + "\n";
  ASSERT_TRUE(ready) << "viewer never became ready; page errors:\n"
                     << errors
                     << "notice: " << browser.Eval("document.getElementById('notice').textContent")
                     << "\nchromium log:\n"
                     << browser.Log();
  EXPECT_NEAR(browser.Eval("simsViewer.duration").get<double>(), rec.duration(), 1e-9);
  EXPECT_EQ(browser.Eval("document.querySelectorAll('.kf').length"), 2);
  EXPECT_NE(browser.Eval("document.querySelector('.kf[data-index=\"0\"]').textContent")
                .get<std::string>()
                .find("success"),
            std::string::npos);
  EXPECT_NE(browser.Eval("document.querySelector('.kf[data-index=\"1\"]').textContent")
                .get<std::string>()
                .find("failed"),
            std::string::npos);

  // The character is drawn: hiding it changes many pixels, and the screenshots differ.
  const int changed = browser.Eval("simsViewer.characterPixels()").get<int>();
  EXPECT_GT(changed, 1000) << "character covers too few pixels";
  const std::string with = browser.Screenshot();
  browser.Eval("simsViewer.setCharacterVisible(false)");
  const std::string without = browser.Screenshot();
  browser.Eval("simsViewer.setCharacterVisible(true)");
  EXPECT_NE(with, without);

  // Clicking the second keyframe in the list moves the time to its start.
  const json rect = browser.Eval(
      "(() => { const r = document.querySelector('.kf[data-index=\"1\"]').getBoundingClientRect();"
      " return {x: r.x + r.width / 2, y: r.y + r.height / 2}; })()");
  browser.Click(rect["x"].get<double>(), rect["y"].get<double>());
  EXPECT_NEAR(browser.Eval("simsViewer.time").get<double>(), 30 / 30.0, 1e-9);
  EXPECT_EQ(browser.Eval("simsViewer.currentKeyframe"), 1);
  EXPECT_EQ(browser.Eval("document.querySelector('.kf.current').dataset.index"), "1");
  EXPECT_NE(browser.Eval("document.getElementById('caption').textContent")
                .get<std::string>()
                .find("sits down"),
            std::string::npos);

  // The scrub bar sets the time; play advances it; pause stops it.
  browser.Eval(
      "(() => { const s = document.getElementById('scrub'); s.value = 0.25;"
      " s.dispatchEvent(new Event('input')); })()");
  EXPECT_NEAR(browser.Eval("simsViewer.time").get<double>(), 0.25, 1.0 / 30);
  EXPECT_EQ(browser.Eval("simsViewer.currentKeyframe"), 0);
  const json play = browser.Eval(
      "(() => { const r = document.getElementById('play').getBoundingClientRect();"
      " return {x: r.x + r.width / 2, y: r.y + r.height / 2}; })()");
  browser.Click(play["x"].get<double>(), play["y"].get<double>());
  EXPECT_TRUE(browser.WaitFor("simsViewer.time > 0.5", 10)) << browser.Eval("simsViewer.time");
  browser.Click(play["x"].get<double>(), play["y"].get<double>());
  EXPECT_EQ(browser.Eval("simsViewer.playing"), false);

  errors.clear();
  for (const auto& e : browser.errors()) errors += e + "\n";
  EXPECT_TRUE(browser.errors().empty()) << errors;
}

}  // namespace
}  // namespace sims::io
