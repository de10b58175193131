#include "sims/motion/retarget.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "motion/motion_test_util.h"
#include "sims/core/paths.h"
#include "sims/core/rng.h"
#include "sims/motion/rotation.h"

namespace sims::motion {
namespace {

const char kCmu[] = "/usr/share/assimp/models/BVH/01_01.bvh";

class CmuRetarget : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!std::filesystem::exists(kCmu)) return;
    clip_ = new MotionClip(RetargetBvh(ReadBvh(kCmu),
                                       LoadRetargetConfig(ConfigPath("retarget/cmu.json")),
                                       HumanoidSkeleton::Default(), &report_, kCmu));
  }
  static void TearDownTestSuite() { delete clip_; }
  void SetUp() override {
    if (!clip_) GTEST_SKIP() << "assimp-testmodels not installed";
  }
  static MotionClip* clip_;
  static RetargetReport report_;
};
MotionClip* CmuRetarget::clip_ = nullptr;
RetargetReport CmuRetarget::report_;

TEST_F(CmuRetarget, ResampledTo30FpsWithCmuScale) {
  EXPECT_EQ(clip_->fps(), 30.0);
  EXPECT_EQ(clip_->num_frames(), 688);  // 2752 frames at 120 Hz, every 4th
  EXPECT_NEAR(clip_->duration(), 2751.0 / 120.0, 0.05);
  // CMU units are 1/0.45 inch; the leg-length scale lands close to 0.0564 m per unit.
  EXPECT_NEAR(report_.scale, 0.0564, 0.006);
  EXPECT_EQ(report_.source_frames, 2752);
}

TEST_F(CmuRetarget, FeetOnTheFloorInStanceAndLimitsRespected) {
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  SkeletonPose prev, cur;
  int stance = 0, near_floor = 0;
  double lowest = 1e9;
  for (int f = 0; f < clip_->num_frames(); ++f) {
    const MotionFrame& fr = clip_->frame(f);
    for (int i = 0; i < humanoid::kNumDofs; ++i) {
      EXPECT_GE(fr.dof_pos[i], s.lower[i] - 1e-9);
      EXPECT_LE(fr.dof_pos[i], s.upper[i] + 1e-9);
    }
    SkeletonForwardKinematics(s, fr.root_pos, fr.root_rot, fr.dof_pos, &cur);
    for (bool left : {false, true}) {
      const double h = SoleHeight(s, cur, left);
      lowest = std::min(lowest, h);
      if (f == 0) continue;
      const int foot = left ? humanoid::kLeftFoot : humanoid::kRightFoot;
      const Eigen::Vector3d v = (cur.pos[foot] - prev.pos[foot]) * clip_->fps();
      if (v.head<2>().norm() < 0.1 && std::abs(v.z()) < 0.1) {  // the foot is planted
        ++stance;
        near_floor += h < 0.06;
      }
    }
    prev = cur;
  }
  EXPECT_GT(lowest, -0.03);  // percentile ground fix: a few landings dip slightly
  EXPECT_GT(stance, 200);
  EXPECT_GT(near_floor, 0.9 * stance) << near_floor << " of " << stance;
  // Few clamps: the map and rest alignment fit the CMU skeleton.
  int clamped = 0;
  for (const auto& [dof, cs] : report_.clamped) clamped += cs.frames;
  EXPECT_LT(clamped, 0.05 * report_.source_frames * humanoid::kNumDofs);
}

TEST_F(CmuRetarget, SegmentLengthsOfTheHumanoidArePreserved) {
  const auto h = HumanoidSkeleton::DefaultHumanoid();
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  const std::vector<humanoid::BodyStates> states = ClipBodyStates(*clip_, *h);
  for (int f = 0; f < clip_->num_frames(); f += 7)
    for (int b = 1; b < humanoid::kNumBodies; ++b)
      EXPECT_NEAR((states[f].pos[b] - states[f].pos[s.parent[b]]).norm(), s.offset[b].norm(), 1e-9);
  // Standing/walking root height of a 0.89 m humanoid.
  int plausible = 0;
  for (const auto& st : states) plausible += st.pos[0].z() > 0.6 && st.pos[0].z() < 1.3;
  EXPECT_GT(plausible, 0.9 * clip_->num_frames());
}

// A second real skeleton: Z-X-Y channel order, 100 fps, centimetres, other joint names
// (the 100STYLE-style map fits it), resampled to 30 fps at a non-integer ratio.
TEST(RetargetTest, BoxingClipWithAnotherHierarchy) {
  const char kBoxing[] = "/usr/share/assimp/models/BVH/Boxing_Toes.bvh";
  if (!std::filesystem::exists(kBoxing)) GTEST_SKIP() << "assimp-testmodels not installed";
  const BvhMotion bvh = ReadBvh(kBoxing);
  EXPECT_NEAR(bvh.fps(), 100.0, 1e-6);
  RetargetReport report;
  const MotionClip clip = RetargetBvh(bvh, LoadRetargetConfig(ConfigPath("retarget/100style.json")),
                                      HumanoidSkeleton::Default(), &report, kBoxing);
  EXPECT_EQ(clip.fps(), 30.0);
  EXPECT_NEAR(clip.duration(), (bvh.num_frames - 1) / 100.0, 1.0 / 30);
  EXPECT_NEAR(report.scale, 0.01, 0.003);  // centimetres
  // Standing in a boxing stance at the start: both soles on the floor, root at hip height.
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  SkeletonPose sp;
  const MotionFrame& f = clip.frame(0);
  SkeletonForwardKinematics(s, f.root_pos, f.root_rot, f.dof_pos, &sp);
  EXPECT_LT(SoleHeight(s, sp, false), 0.05);
  EXPECT_LT(SoleHeight(s, sp, true), 0.05);
  EXPECT_GT(f.root_pos.z(), 0.7);
}

// Humanoid clip → BVH (Y-up and Z-up) → retarget back gives the same clip.
TEST(RetargetTest, HumanoidBvhRoundTrip) {
  const MotionClip clip = testing_util::WigglyClip(40, 3);
  const auto dir = testing::TempDir("retarget");
  for (bool y_up : {true, false}) {
    HumanoidBvhOptions o;
    o.y_up = y_up;
    WriteBvh(HumanoidClipToBvh(clip, HumanoidSkeleton::Default(), o), dir / "h.bvh");
    const BvhMotion bvh = ReadBvh(dir / "h.bvh");
    EXPECT_EQ(bvh.joints.size(), 15u);
    RetargetReport report;
    const MotionClip back =
        RetargetBvh(bvh, HumanoidBvhRetargetConfig(o), HumanoidSkeleton::Default(), &report);
    ASSERT_EQ(back.num_frames(), clip.num_frames());
    EXPECT_NEAR(back.fps(), 30.0, 1e-6);
    EXPECT_TRUE(report.warnings.empty());
    for (int f = 0; f < clip.num_frames(); ++f) {
      EXPECT_LT((back.frame(f).root_pos - clip.frame(f).root_pos).norm(), 1e-6) << y_up;
      EXPECT_LT(back.frame(f).root_rot.angularDistance(clip.frame(f).root_rot), 1e-6) << y_up;
      EXPECT_LT((back.frame(f).dof_pos - clip.frame(f).dof_pos).cwiseAbs().maxCoeff(), 1e-6)
          << y_up;
    }
  }
}

TEST(RetargetTest, ConfigErrorsNameTheField) {
  RetargetConfig c = LoadRetargetConfig(ConfigPath("retarget/cmu.json"));
  c.up_axis = "w";
  try {
    ValidateConfig(c, "cmu.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("up_axis"), std::string::npos);
  }
  c = LoadRetargetConfig(ConfigPath("retarget/cmu.json"));
  c.joints.erase("left_foot");
  EXPECT_THROW(ValidateConfig(c, "cmu.json"), Error);
  // A map naming joints the file lacks.
  c = LoadRetargetConfig(ConfigPath("retarget/cmu.json"));
  const BvhMotion tiny = ReadBvh(testing::TestData("motion/tiny_zxy.bvh"));
  try {
    RetargetBvh(tiny, c, HumanoidSkeleton::Default(), nullptr, "tiny.bvh");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tiny.bvh"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("Hips"), std::string::npos);
  }
  for (const char* name : {"cmu", "100style", "samp"})
    EXPECT_NO_THROW(LoadRetargetConfig(ConfigPath(std::string("retarget/") + name + ".json")));
}

}  // namespace
}  // namespace sims::motion
