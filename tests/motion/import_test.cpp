#include "sims/motion/import.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "motion/motion_test_util.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/motion/retarget.h"

namespace sims::motion {
namespace {

namespace fs = std::filesystem;
const char kCmu[] = "/usr/share/assimp/models/BVH/01_01.bvh";

TEST(ImportTest, CmuClip) {
  if (!fs::exists(kCmu)) GTEST_SKIP() << "assimp-testmodels not installed";
  const auto dir = testing::TempDir("import");
  ImportOptions o;
  o.map = ConfigPath("retarget/cmu.json");
  o.captions = {"a person jumps forward and turns around"};
  o.skill = "other";
  const ImportSummary s = ImportBvhFile(kCmu, dir, o);
  EXPECT_EQ(s.name, "01_01");
  EXPECT_EQ(s.frames, 688);
  EXPECT_EQ(s.fps, 30.0);
  EXPECT_NEAR(s.duration, 22.9, 0.05);
  EXPECT_NE(s.Line().find("01_01: 688 frames @ 30 fps, 22.90 s"), std::string::npos) << s.Line();
  const MotionClip c = LoadClip(dir / "01_01.json");
  EXPECT_EQ(c.meta().captions, o.captions);
  EXPECT_GT(c.meta().params.at("retarget_scale"), 0.04);
  const MotionManifest m = LoadManifest(dir / "manifest.json");
  ASSERT_EQ(m.clips.size(), 1u);
  EXPECT_EQ(m.clips[0].file, "01_01.json");
  // Importing again replaces the manifest entry instead of duplicating it.
  ImportBvhFile(kCmu, dir, o);
  EXPECT_EQ(LoadManifest(dir / "manifest.json").clips.size(), 1u);
}

TEST(ImportTest, MalformedBvhFailsClearlyAndWritesNothing) {
  const auto dir = testing::TempDir("import_bad");
  ImportOptions o;
  o.map = ConfigPath("retarget/cmu.json");
  for (const char* f : {"truncated.bvh", "bad_channel_count.bvh", "zero_frames.bvh"}) {
    try {
      ImportBvhFile(testing::TestData(std::string("motion/") + f), dir, o);
      ADD_FAILURE() << f;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_empty(dir));

  // A readable clip (not the optional assimp-testmodels one, whose absence would throw "file
  // not found" first) with a bad label: the label is the error, and nothing is written.
  const auto src = testing::TempDir("import_bad_src");
  WriteHumanoidBvh(testing_util::WigglyClip(20, 1, 0.1, true), src / "clip.bvh");
  RetargetConfig map = HumanoidBvhRetargetConfig();
  map.target_fps = 30;
  map.ground = "clip_min";
  SaveConfig(src / "map.json", map);
  o.map = src / "map.json";
  o.emotion = "gleeful";
  std::string e = testing::ErrorOf([&] { ImportBvhFile(src / "clip.bvh", dir, o); });
  EXPECT_NE(e.find("clip.bvh"), std::string::npos) << e;
  EXPECT_NE(e.find("emotion"), std::string::npos) << e;
  EXPECT_NE(e.find("neutral"), std::string::npos) << e;  // lists the labels
  EXPECT_TRUE(fs::is_empty(dir));
  o.emotion = "neutral";
  o.map = src / "no_map.json";
  e = testing::ErrorOf([&] { ImportBvhFile(src / "clip.bvh", dir, o); });
  EXPECT_NE(e.find("no_map.json"), std::string::npos) << e;
  EXPECT_TRUE(fs::is_empty(dir));
  // The same clip with good labels imports: the errors above came from the labels and the map.
  o.map = src / "map.json";
  EXPECT_EQ(ImportBvhFile(src / "clip.bvh", dir, o).frames, 20);
}

TEST(ImportTest, DatasetRulesLabelFiles) {
  for (const char* name : {"100style", "samp"})
    EXPECT_NO_THROW(
        LoadConfig<DatasetConfig>(ConfigPath(std::string("datasets/") + name + ".json")));
  const DatasetConfig style = LoadConfig<DatasetConfig>(ConfigPath("datasets/100style.json"));
  bool skip = false;
  ImportOptions o = DatasetFileOptions(style, "Angry/Angry_FW.bvh", &skip);
  EXPECT_FALSE(skip);
  EXPECT_EQ(o.emotion, "angry");
  EXPECT_EQ(o.skill, "walk");
  EXPECT_EQ(o.captions[0], "a person walks forward in the angry style");
  EXPECT_EQ(o.name, "100style_angry_angry_fw");
  o = DatasetFileOptions(style, "ArmsAboveHead/ArmsAboveHead_ID.bvh", &skip);
  EXPECT_EQ(o.skill, "idle");
  EXPECT_EQ(o.emotion, "neutral");
  EXPECT_EQ(o.captions[0], "a person stands in place in the arms above head style");
  const DatasetConfig samp = LoadConfig<DatasetConfig>(ConfigPath("datasets/samp.json"));
  o = DatasetFileOptions(samp, "lie_down_3.bvh", &skip);
  EXPECT_EQ(o.skill, "lie");
  EXPECT_EQ(o.captions[0], "a person lies down on the bed");
  EXPECT_EQ(ToWords("ArmsBehindBack_FW"), "arms behind back fw");
}

// A whole (tiny) dataset: humanoid BVH exports in style folders plus one broken file.
TEST(ImportTest, DatasetFolder) {
  const auto root = testing::TempDir("dataset");
  const auto out = testing::TempDir("dataset_out");
  fs::create_directories(root / "Angry");
  fs::create_directories(root / "Happy");
  WriteHumanoidBvh(testing_util::WigglyClip(20, 1, 0.1, true), root / "Angry" / "Angry_FW.bvh");
  WriteHumanoidBvh(testing_util::WigglyClip(25, 2, 0.1, true), root / "Happy" / "Happy_ID.bvh");
  fs::copy_file(testing::TestData("motion/truncated.bvh"), root / "Happy" / "Happy_BW.bvh");
  const auto map_path = out / "map.json";
  RetargetConfig map = HumanoidBvhRetargetConfig();
  map.target_fps = 30;
  map.ground = "clip_min";
  SaveConfig(map_path, map);
  DatasetConfig cfg = LoadConfig<DatasetConfig>(ConfigPath("datasets/100style.json"));
  cfg.retarget = map_path.string();
  cfg.source_fps = 30;
  const auto cfg_path = out / "dataset.json";
  SaveConfig(cfg_path, cfg);
  const auto clips_dir = out / "clips";
  EXPECT_THROW(ImportDataset(cfg_path, root, clips_dir, false), Error);
  int failures = 0;
  const auto summaries = ImportDataset(cfg_path, root, clips_dir, true, &failures);
  EXPECT_EQ(failures, 1);
  ASSERT_EQ(summaries.size(), 3u);
  const MotionLibrary lib = MotionLibrary::Load(clips_dir / "manifest.json", nullptr);
  ASSERT_EQ(lib.num_clips(), 2);
  EXPECT_EQ(lib.Find("walk", "angry").size(), 1u);
  EXPECT_EQ(lib.Find("idle", "happy").size(), 1u);
  EXPECT_THROW(ImportDataset(cfg_path, root / "missing", clips_dir, true), Error);
}

}  // namespace
}  // namespace sims::motion
