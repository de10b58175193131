#include "sims/motion/mirror.h"

#include <gtest/gtest.h>

#include "motion/motion_test_util.h"
#include "sims/humanoid/features.h"

namespace sims::motion {
namespace {

TEST(MirrorTest, TwiceIsIdentity) {
  const MotionClip clip = testing_util::WigglyClip(20, 7);
  const MotionClip m = MirrorClip(clip);
  EXPECT_TRUE(m.meta().mirrored);
  EXPECT_EQ(m.meta().name, "wiggly_right_7_mirror");
  EXPECT_EQ(m.meta().captions[0], "a person wiggles the right arm");
  EXPECT_EQ(m.meta().captions[1], "wiggling to the left");
  EXPECT_EQ(m.meta().params.at("target_y"), -0.3);
  EXPECT_EQ(m.meta().params.at("turn_yaw"), -0.5);
  EXPECT_EQ(m.meta().params.at("seat_height"), 0.45);
  const MotionClip mm = MirrorClip(m);
  EXPECT_EQ(mm.meta().name, clip.meta().name);
  EXPECT_EQ(mm.meta().captions, clip.meta().captions);
  EXPECT_EQ(mm.meta().params, clip.meta().params);
  EXPECT_FALSE(mm.meta().mirrored);
  for (int f = 0; f < clip.num_frames(); ++f) {
    EXPECT_LT((mm.frame(f).root_pos - clip.frame(f).root_pos).norm(), 1e-15);
    EXPECT_LT(mm.frame(f).root_rot.angularDistance(clip.frame(f).root_rot), 1e-9);
    EXPECT_EQ(mm.frame(f).dof_pos, clip.frame(f).dof_pos);
  }
}

// The mirrored pose is the reflection y → −y of the original: every body lands on its
// partner's reflected position with the reflected orientation, and velocities reflect too.
TEST(MirrorTest, ReflectsBodiesAcrossTheSagittalPlane) {
  const MotionClip clip = testing_util::WigglyClip(15, 8);
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  const Eigen::Matrix3d S = Eigen::Vector3d(1, -1, 1).asDiagonal();
  const auto h = HumanoidSkeleton::DefaultHumanoid();
  const MotionClip m = MirrorClip(clip);
  const auto a = ClipBodyStates(clip, *h);
  const auto b = ClipBodyStates(m, *h);
  auto partner = [](int body) {
    std::string n = humanoid::BodyNames()[body];
    if (n.rfind("left_", 0) == 0)
      n = "right_" + n.substr(5);
    else if (n.rfind("right_", 0) == 0)
      n = "left_" + n.substr(6);
    return humanoid::BodyByName(n);
  };
  for (int f = 0; f < clip.num_frames(); ++f) {
    for (int body = 0; body < humanoid::kNumBodies; ++body) {
      const int p = partner(body);
      EXPECT_LT((b[f].pos[p] - S * a[f].pos[body]).norm(), 1e-9) << humanoid::BodyNames()[body];
      const Eigen::Matrix3d want = S * a[f].rot[body].toRotationMatrix() * S;
      EXPECT_LT((b[f].rot[p].toRotationMatrix() - want).norm(), 1e-9)
          << humanoid::BodyNames()[body];
      // Interior frames: velocities come from the mirrored frames and must reflect exactly
      // (angular velocity is a pseudo-vector: ω → −S·ω).
      EXPECT_LT((b[f].lin_vel[p] - S * a[f].lin_vel[body]).norm(), 1e-6);
      EXPECT_LT((b[f].ang_vel[p] + S * a[f].ang_vel[body]).norm(), 1e-6);
    }
    for (int i = 0; i < humanoid::kNumDofs; ++i) {
      EXPECT_GE(m.frame(f).dof_pos[i], s.lower[i] - 1e-12);
      EXPECT_LE(m.frame(f).dof_pos[i], s.upper[i] + 1e-12);
    }
  }
  // MirrorPose agrees with mirroring the frames.
  const humanoid::HumanoidPose p = MirrorPose(clip.SamplePose(0.2));
  const humanoid::HumanoidPose q = m.SamplePose(0.2);
  EXPECT_LT((p.root_ang_vel - q.root_ang_vel).norm(), 1e-9);
  EXPECT_LT((p.dof_vel - q.dof_vel).norm(), 1e-9);
}

TEST(MirrorTest, TextSwapsSides) {
  EXPECT_EQ(MirrorText("Turn Left, then RIGHT; left-handed"),
            "Turn Right, then LEFT; right-handed");
  EXPECT_EQ(MirrorText("walks leftward clockwise"), "walks rightward counterclockwise");
  EXPECT_EQ(MirrorText("leftover bright"), "leftover bright");
  EXPECT_EQ(MirrorText(MirrorText("reach with the right hand")), "reach with the right hand");
}

}  // namespace
}  // namespace sims::motion
