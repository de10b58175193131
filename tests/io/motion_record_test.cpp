#include "sims/io/motion_record.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "common/test_util.h"
#include "io/io_test_util.h"
#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/motion/skeleton.h"

namespace sims::io {
namespace {

using sims::testing::ErrorOf;

TEST(MotionRecordTest, BuilderComputesBodiesAndKeyframeRanges) {
  const MotionRecord rec = testing::TestRecord(1.0);
  ASSERT_EQ(rec.num_frames(), 31);
  EXPECT_NEAR(rec.duration(), 1.0, 1e-12);
  ASSERT_EQ(rec.keyframes.size(), 2u);
  EXPECT_EQ(rec.keyframes[0].start_frame, 0);
  EXPECT_EQ(rec.keyframes[0].end_frame, 14);
  EXPECT_TRUE(rec.keyframes[0].success);
  EXPECT_EQ(rec.keyframes[1].start_frame, 15);
  EXPECT_EQ(rec.keyframes[1].end_frame, 30);
  EXPECT_FALSE(rec.keyframes[1].success);
  EXPECT_EQ(rec.keyframes[1].detail, "timed out");
  EXPECT_EQ(rec.KeyframeAt(0), 0);
  EXPECT_EQ(rec.KeyframeAt(14), 0);
  EXPECT_EQ(rec.KeyframeAt(15), 1);
  // Body poses agree with the skeleton's own forward kinematics.
  const auto& skel = motion::HumanoidSkeleton::Default();
  for (int f : {0, 17, 30}) {
    const RecordFrame& fr = rec.frames[f];
    motion::SkeletonPose pose;
    motion::SkeletonForwardKinematics(skel, fr.root_pos, fr.root_rot, fr.dof_pos, &pose);
    EXPECT_NEAR(fr.time, f / 30.0, 1e-12);
    EXPECT_TRUE(fr.body_pos[humanoid::kPelvis].isApprox(fr.root_pos, 1e-12));
    for (int b = 0; b < humanoid::kNumBodies; ++b) {
      EXPECT_LT((fr.body_pos[b] - pose.pos[b]).norm(), 1e-9) << b;
      EXPECT_LT(fr.body_rot[b].angularDistance(pose.rot[b]), 1e-9) << b;
    }
  }
}

TEST(MotionRecordTest, UnreachedAndUnfinishedKeyframes) {
  MotionRecordBuilder b;
  KeyframeAnnotation a;
  a.skill = "walk";
  b.BeginKeyframe(a);
  b.AddFrame(humanoid::HumanoidPose{});
  b.AddFrame(humanoid::HumanoidPose{});
  a.index = 1;
  a.skill = "sit";
  b.BeginKeyframe(a);            // closes "walk" as failed
  b.EndKeyframe(false, "fell");  // no frame while open: never reached
  a.index = 2;
  a.skill = "lie";
  b.AddKeyframe(a);  // never reached (-1, -1)
  a.index = 3;
  b.BeginKeyframe(a);
  b.AddFrame(humanoid::HumanoidPose{});
  const MotionRecord rec = b.Finish();  // closes keyframe 3 as unfinished
  ASSERT_EQ(rec.keyframes.size(), 4u);
  EXPECT_EQ(rec.keyframes[0].end_frame, 1);
  EXPECT_FALSE(rec.keyframes[0].success);
  EXPECT_FALSE(rec.keyframes[1].reached());
  EXPECT_FALSE(rec.keyframes[2].reached());
  EXPECT_EQ(rec.keyframes[3].start_frame, 2);
  EXPECT_EQ(rec.keyframes[3].end_frame, 2);
  EXPECT_EQ(rec.keyframes[3].detail, "unfinished");
  EXPECT_EQ(b.num_frames(), 0);
}

TEST(MotionRecordTest, JsonRoundTrip) {
  const MotionRecord rec = testing::TestRecord(0.5);
  const auto dir = sims::testing::TempDir("io_record");
  SaveMotionRecord(rec, dir / "motion.json");
  const MotionRecord back = LoadMotionRecord(dir / "motion.json");
  ASSERT_EQ(back.num_frames(), rec.num_frames());
  EXPECT_EQ(back.title, rec.title);
  EXPECT_EQ(back.scene.name, "chair");
  EXPECT_EQ(back.scene.source, "chair");
  EXPECT_EQ(back.fps, 30.0);
  ASSERT_EQ(back.keyframes.size(), rec.keyframes.size());
  for (std::size_t k = 0; k < rec.keyframes.size(); ++k) {
    EXPECT_EQ(back.keyframes[k].skill, rec.keyframes[k].skill);
    EXPECT_EQ(back.keyframes[k].caption, rec.keyframes[k].caption);
    EXPECT_EQ(back.keyframes[k].emotion, rec.keyframes[k].emotion);
    EXPECT_EQ(back.keyframes[k].furniture, rec.keyframes[k].furniture);
    EXPECT_EQ(back.keyframes[k].start_frame, rec.keyframes[k].start_frame);
    EXPECT_EQ(back.keyframes[k].end_frame, rec.keyframes[k].end_frame);
    EXPECT_EQ(back.keyframes[k].success, rec.keyframes[k].success);
  }
  for (int f = 0; f < rec.num_frames(); ++f) {
    EXPECT_LT((back.frames[f].root_pos - rec.frames[f].root_pos).norm(), 2e-6);
    EXPECT_LT((back.frames[f].dof_pos - rec.frames[f].dof_pos).cwiseAbs().maxCoeff(), 1e-6);
    for (int b = 0; b < humanoid::kNumBodies; ++b) {
      EXPECT_LT((back.frames[f].body_pos[b] - rec.frames[f].body_pos[b]).norm(), 2e-6);
      EXPECT_LT(back.frames[f].body_rot[b].angularDistance(rec.frames[f].body_rot[b]), 1e-5);
    }
  }
  // The file documents its layout.
  const nlohmann::json j = ReadJsonFile(dir / "motion.json");
  EXPECT_EQ(j["format"], kMotionRecordFormat);
  EXPECT_EQ(j["skeleton"]["bodies"][0], "pelvis");
  EXPECT_EQ(j["skeleton"]["dofs"].size(), static_cast<std::size_t>(humanoid::kNumDofs));
  EXPECT_EQ(j["num_frames"], rec.num_frames());
}

TEST(MotionRecordTest, MalformedFilesNameFileAndField) {
  const auto dir = sims::testing::TempDir("io_record_bad");
  const MotionRecord rec = testing::TestRecord(0.2);
  const nlohmann::json good = MotionRecordToJson(rec);
  auto write = [&](const nlohmann::json& j) {
    const auto p = dir / "bad.json";
    std::ofstream(p) << j.dump();
    return p;
  };
  struct Case {
    std::function<void(nlohmann::json&)> edit;
    std::string field;
  };
  const std::vector<Case> cases = {
      {[](nlohmann::json& j) { j["format"] = "something"; }, "format"},
      {[](nlohmann::json& j) { j["frames"][2]["body_rot"].erase(3); }, "frames[2].body_rot"},
      {[](nlohmann::json& j) { j["frames"][1]["root_pos"][1] = "x"; }, "frames[1].root_pos[1]"},
      {[](nlohmann::json& j) { j["frames"][0]["dof_pos"].push_back(0); }, "frames[0].dof_pos"},
      {[](nlohmann::json& j) { j["frames"][3]["t"] = 9.0; }, "frames[3].t"},
      {[](nlohmann::json& j) { j["keyframes"][1]["end_frame"] = 999; }, "keyframes[1]"},
      {[](nlohmann::json& j) { j["keyframes"][0].erase("success"); }, "keyframes[0].success"},
      {[](nlohmann::json& j) { j["num_frames"] = 3; }, "num_frames"},
      {[](nlohmann::json& j) { j["skeleton"]["bodies"][1] = "chest"; }, "skeleton.bodies"},
      {[](nlohmann::json& j) { j["fps"] = -30; }, "fps"},
  };
  for (const Case& c : cases) {
    nlohmann::json j = good;
    c.edit(j);
    const auto path = write(j);
    const std::string msg = ErrorOf([&] { LoadMotionRecord(path); });
    EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.field), std::string::npos) << "want field " << c.field << " in: " << msg;
  }
  EXPECT_NE(ErrorOf([&] { LoadMotionRecord(dir / "missing.json"); }).find("no such file"),
            std::string::npos);
  std::ofstream(dir / "broken.json") << "{\"format\": ";
  EXPECT_NE(ErrorOf([&] { LoadMotionRecord(dir / "broken.json"); }).find("broken.json"),
            std::string::npos);
}

TEST(MotionRecordTest, ClipsConvertBothWays) {
  const MotionRecord rec = testing::TestRecord(0.5);
  const motion::MotionClip clip = RecordToClip(rec);
  EXPECT_EQ(clip.num_frames(), rec.num_frames());
  EXPECT_NEAR(clip.duration(), rec.duration(), 1e-12);
  const auto dir = sims::testing::TempDir("io_record_clip");
  motion::SaveClip(clip, dir / "clip.json");
  const MotionRecord back = LoadMotionRecordOrClip(dir / "clip.json");
  ASSERT_EQ(back.num_frames(), rec.num_frames());
  ASSERT_EQ(back.keyframes.size(), 1u);
  EXPECT_EQ(back.keyframes[0].end_frame, rec.num_frames() - 1);
  EXPECT_LT(
      (back.frames.back().body_pos[humanoid::kHead] - rec.frames.back().body_pos[humanoid::kHead])
          .norm(),
      1e-5);
}

}  // namespace
}  // namespace sims::io
