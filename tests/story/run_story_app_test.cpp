// The run_story app end to end: the real binary with the bundled policies on a tiny scene.
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/config.h"
#include "sims/core/paths.h"
#include "sims/io/motion_record.h"
#include "sims/motion/bvh.h"

namespace sims::story {
namespace {

int RunStory(const std::string& args) {
  const std::string cmd = std::string(SIMS_RUN_STORY_BIN) + " " + args + " --log-level warn";
  return std::system(cmd.c_str());
}

std::string ReadText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(RunStoryAppTest, BundledPoliciesWriteEveryOutputWithValidContent) {
  const auto dir = sims::testing::TempDir("run_story_app");
  const auto out = dir / "out";
  ASSERT_EQ(
      RunStory("--instruction 'walk to the chair' --scene chair --seed 3 --out " + out.string()),
      0);
  const auto result = ReadJsonFile(out / "result.json");
  ASSERT_EQ(result["keyframes"].size(), 1u);
  EXPECT_EQ(result["keyframes"][0]["skill"], "walk");
  EXPECT_TRUE(std::filesystem::equivalent(result["policies"].get<std::string>(),
                                          AssetPath("policies/policies.json")));
  const double duration = result["duration_s"].get<double>();
  EXPECT_GT(duration, 0.5);
  // The bundled walk policy really walked there: a character that stood still, fell or
  // wandered off would fail the success test (pelvis within 0.5 m of the chair's approach
  // point) and would not have covered the metre and a half from the start.
  const auto& kf = result["keyframes"][0];
  EXPECT_TRUE(kf["success"].get<bool>()) << kf.dump();
  EXPECT_LT(kf["contact_error"].get<double>(), 0.5) << kf.dump();
  EXPECT_EQ(kf["falls"], 0);
  EXPECT_EQ(result["success_rate"], 1.0);
  // Per keyframe: the caption, the emotion of the clip its z (bundled motion-text model) is
  // nearest to, and the style measured in the motion ("" when under 3 s, as here it may be).
  ASSERT_EQ(result["keyframe_styles"].size(), 1u);
  const auto& ks = result["keyframe_styles"][0];
  EXPECT_EQ(ks["caption"], kf["caption"]);
  EXPECT_EQ(ks["skill"], "walk");
  EXPECT_FALSE(ks["z_nearest_clip"].get<std::string>().empty()) << ks.dump();
  EXPECT_FALSE(ks["z_emotion"].get<std::string>().empty()) << ks.dump();
  EXPECT_TRUE(ks.contains("measured_style"));

  const auto motion = io::LoadMotionRecord(out / "motion.json");  // validates frames/keyframes
  EXPECT_DOUBLE_EQ(motion.fps, 30.0);
  EXPECT_NEAR(motion.duration(), duration, 1.0 / 30.0 + 1e-9);
  ASSERT_EQ(motion.keyframes.size(), 1u);
  EXPECT_TRUE(motion.keyframes[0].success);
  ASSERT_GE(motion.num_frames(), 2);
  const double walked =
      (motion.frames.back().root_pos - motion.frames.front().root_pos).head<2>().norm();
  EXPECT_GT(walked, 1.0) << "pelvis moved " << walked << " m";
  const auto bvh = motion::ReadBvh(out / "motion.bvh");
  EXPECT_EQ(bvh.num_frames, motion.num_frames());
  EXPECT_EQ(ReadText(out / "scene.glb").substr(0, 4), "glTF");
  EXPECT_NE(ReadText(out / "index.html").find("motion.json"), std::string::npos);
  EXPECT_NE(ReadText(out / "story.txt").find("chair"), std::string::npos);
  EXPECT_TRUE(ReadJsonFile(out / "config.json").contains("options"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.partial"));
}

TEST(RunStoryAppTest, BadInputExitsNonZeroAndLeavesNoOutput) {
  const auto dir = sims::testing::TempDir("run_story_app_bad");
  std::ofstream(dir / "single_quotes.json") << "{'keyframes': []}";
  EXPECT_NE(RunStory((dir / "single_quotes.json").string() + " --out " + (dir / "a").string()), 0);
  std::ofstream(dir / "spaceship.json")
      << R"({"keyframes": [{"skill": "sit", "furniture": "spaceship"}]})";
  EXPECT_NE(RunStory((dir / "spaceship.json").string() + " --out " + (dir / "b").string()), 0);
  EXPECT_NE(RunStory("--instruction 'walk to the chair' --scene chair --policies " +
                     (dir / "none.json").string() + " --out " + (dir / "c").string()),
            0);
  for (const char* d : {"a", "b", "c"}) {
    EXPECT_FALSE(std::filesystem::exists(dir / d)) << d;
    EXPECT_FALSE(std::filesystem::exists(dir / (std::string(d) + ".partial"))) << d;
  }
}

}  // namespace
}  // namespace sims::story
