#include "sims/motion/motion_clip.h"

#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "motion/motion_test_util.h"
#include "sims/core/error.h"
#include "sims/humanoid/features.h"
#include "sims/humanoid/model_builder.h"

namespace sims::motion {
namespace {

using testing_util::WigglyClip;

std::string ErrorOf(const std::filesystem::path& p) {
  return sims::testing::ErrorOf([&] { LoadClip(p); });
}

TEST(MotionClipTest, SaveLoadRoundTrip) {
  const MotionClip clip = WigglyClip(50, 1);
  const auto dir = testing::TempDir("clip");
  SaveClip(clip, dir / "a.json");
  EXPECT_TRUE(std::filesystem::exists(dir / "a.bin"));
  EXPECT_EQ(std::filesystem::file_size(dir / "a.bin"), 16u + 50u * 35u * 4u);
  const MotionClip back = LoadClip(dir / "a.json");
  ASSERT_EQ(back.num_frames(), 50);
  EXPECT_EQ(back.fps(), 30.0);
  for (int f = 0; f < 50; ++f) {
    EXPECT_LT((back.frame(f).root_pos - clip.frame(f).root_pos).norm(), 1e-6);
    EXPECT_LT(back.frame(f).root_rot.angularDistance(clip.frame(f).root_rot), 1e-6);
    EXPECT_LT((back.frame(f).dof_pos - clip.frame(f).dof_pos).cwiseAbs().maxCoeff(), 1e-6);
  }
  EXPECT_EQ(back.meta().name, clip.meta().name);
  EXPECT_EQ(back.meta().captions, clip.meta().captions);
  EXPECT_EQ(back.meta().emotion, "happy");
  EXPECT_EQ(back.meta().params, clip.meta().params);
}

TEST(MotionClipTest, LoadErrorsNameFileAndField) {
  const MotionClip clip = WigglyClip(10, 2);
  const auto dir = testing::TempDir("clip_err");
  SaveClip(clip, dir / "a.json");
  // Truncated frame file.
  std::filesystem::resize_file(dir / "a.bin", 16 + 35 * 4 * 5);
  std::string e = ErrorOf(dir / "a.json");
  EXPECT_NE(e.find("a.bin"), std::string::npos) << e;
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  // Unknown emotion label.
  SaveClip(clip, dir / "b.json");
  nlohmann::json j = ReadJsonFile(dir / "b.json");
  j["meta"]["emotion"] = "gleeful";
  WriteJsonFile(dir / "b.json", j);
  e = ErrorOf(dir / "b.json");
  EXPECT_NE(e.find("b.json"), std::string::npos) << e;
  EXPECT_NE(e.find("emotion"), std::string::npos) << e;
  EXPECT_NE(e.find("drunk"), std::string::npos) << e;
  // Missing file, wrong format tag.
  EXPECT_NE(ErrorOf(dir / "none.json").find("none.json"), std::string::npos);
  WriteJsonFile(dir / "c.json", nlohmann::json{{"format", "other"}});
  EXPECT_NE(ErrorOf(dir / "c.json").find("format"), std::string::npos);
  // Inline frames of the wrong width.
  WriteJsonFile(
      dir / "d.json",
      nlohmann::json{
          {"format", "sims-motion-clip"}, {"version", 1}, {"fps", 30}, {"frames", {{1, 2, 3}}}});
  e = ErrorOf(dir / "d.json");
  EXPECT_NE(e.find("frames[0]"), std::string::npos) << e;
}

TEST(MotionClipTest, SamplingAndVelocities) {
  // Constant linear/angular/hinge velocities: the estimates are exact.
  std::vector<MotionFrame> fr(31);
  const Eigen::Vector3d v(0.8, -0.3, 0.1);
  const double w = 0.9;
  DofVector rate = DofVector::Constant(0.2);
  for (int f = 0; f < 31; ++f) {
    const double t = f / 30.0;
    fr[f].root_pos = Eigen::Vector3d(0, 0, 0.9) + v * t;
    fr[f].root_rot = Eigen::AngleAxisd(w * t, Eigen::Vector3d::UnitZ());
    fr[f].dof_pos = rate * t;
  }
  const MotionClip clip(30.0, fr);
  EXPECT_NEAR(clip.duration(), 1.0, 1e-12);
  for (double t : {0.0, 0.31, 0.5, 0.99, 1.0, 2.0}) {
    const humanoid::HumanoidPose p = clip.SamplePose(t);
    const double tc = std::min(t, 1.0);
    EXPECT_LT((p.root_pos - (Eigen::Vector3d(0, 0, 0.9) + v * tc)).norm(), 1e-9) << t;
    EXPECT_NEAR(humanoid::HeadingAngle(p.root_rot), w * tc, 1e-9);
    EXPECT_LT((p.root_lin_vel - v).norm(), 1e-9) << t;
    EXPECT_LT((p.root_ang_vel - Eigen::Vector3d(0, 0, w)).norm(), 1e-9) << t;
    EXPECT_LT((p.dof_vel - rate).norm(), 1e-9) << t;
    EXPECT_LT((p.dof_pos - rate * tc).norm(), 1e-9) << t;
  }
  // Resampling keeps the motion.
  const MotionClip up = clip.Resampled(120.0);
  EXPECT_EQ(up.num_frames(), 121);
  EXPECT_LT((up.SamplePose(0.37).root_pos - clip.SamplePose(0.37).root_pos).norm(), 1e-9);
  EXPECT_EQ(clip.Slice(5, 10).num_frames(), 5);
  EXPECT_THROW(MotionClip(0.0, fr), Error);
  EXPECT_THROW(MotionClip(30.0, {}), Error);
}

// FK of clip frames (humanoid::ForwardKinematics) equals MuJoCo's full mj_forward replay.
TEST(MotionClipTest, ForwardKinematicsMatchesMujocoReplay) {
  const MotionClip clip = WigglyClip(30, 4);
  const auto h = HumanoidSkeleton::DefaultHumanoid();
  const std::vector<humanoid::BodyStates> fk = ClipBodyStates(clip, *h);
  humanoid::MjDataPtr d = humanoid::MakeData(h->model());
  for (int f = 0; f < clip.num_frames(); ++f) {
    const humanoid::HumanoidPose p = clip.FramePose(f);
    // Replay through raw qpos/qvel.
    double* q = d->qpos + h->root_qpos_adr();
    q[0] = p.root_pos.x(), q[1] = p.root_pos.y(), q[2] = p.root_pos.z();
    q[3] = p.root_rot.w(), q[4] = p.root_rot.x(), q[5] = p.root_rot.y(), q[6] = p.root_rot.z();
    const Eigen::Vector3d wl = p.root_rot.conjugate() * p.root_ang_vel;
    for (int k = 0; k < 3; ++k) {
      d->qvel[h->root_qvel_adr() + k] = p.root_lin_vel[k];
      d->qvel[h->root_qvel_adr() + 3 + k] = wl[k];
    }
    for (int i = 0; i < humanoid::kNumDofs; ++i) {
      d->qpos[h->dof_qpos_adr(i)] = p.dof_pos[i];
      d->qvel[h->dof_qvel_adr(i)] = p.dof_vel[i];
    }
    {
      testing::ScopedAllowMujocoWarnings allow;  // wiggly poses may self-intersect
      mj_forward(h->model(), d.get());
    }
    humanoid::BodyStates replay;
    humanoid::ReadBodyStates(*h, d.get(), &replay);
    for (int b = 0; b < humanoid::kNumBodies; ++b) {
      EXPECT_LT((fk[f].pos[b] - replay.pos[b]).norm(), 1e-9);
      EXPECT_LT(fk[f].rot[b].angularDistance(replay.rot[b]), 1e-9);
      EXPECT_LT((fk[f].lin_vel[b] - replay.lin_vel[b]).norm(), 1e-9);
      EXPECT_LT((fk[f].ang_vel[b] - replay.ang_vel[b]).norm(), 1e-9);
    }
  }
}

}  // namespace
}  // namespace sims::motion
