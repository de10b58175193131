#include "sims/humanoid/features.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sims::humanoid {
namespace {

TEST(FeaturesTest, TanNormOfIdentity) {
  float t[6];
  TanNorm(Eigen::Quaterniond::Identity(), t);
  const float expect[6] = {1, 0, 0, 0, 0, 1};
  for (int i = 0; i < 6; ++i) EXPECT_FLOAT_EQ(t[i], expect[i]);
}

TEST(FeaturesTest, HeadingIgnoresPitchAndRoll) {
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(HeadingAngle(yaw * tilt), 0.8, 1e-12);
  const Eigen::Quaterniond local = HeadingInverse(yaw * tilt) * (yaw * tilt);
  EXPECT_NEAR(HeadingAngle(local), 0.0, 1e-12);
}

TEST(FeaturesTest, HingeTripleComposesXYZ) {
  const Eigen::Quaterniond q = HingeTripleRotation(0.1, 0.2, 0.3);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                            Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()).toRotationMatrix() *
                            Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(q.toRotationMatrix().isApprox(r));
}

TEST(FeaturesTest, DofObservationOfZeroPoseIsIdentities) {
  float out[kDofObsDim];
  DofObservation(Eigen::Matrix<double, kNumDofs, 1>::Zero(), out);
  for (int j = 0; j < kNumJoints; ++j) {
    EXPECT_FLOAT_EQ(out[6 * j], 1.0f);
    EXPECT_FLOAT_EQ(out[6 * j + 5], 1.0f);
  }
}

TEST(FeaturesTest, ElbowRotatesAboutY) {
  Eigen::Matrix<double, kNumDofs, 1> q = Eigen::Matrix<double, kNumDofs, 1>::Zero();
  q[9] = M_PI / 2;  // right elbow, joint index 3
  float out[kDofObsDim];
  DofObservation(q, out);
  // R_y(90°)·x = (0, 0, −1), R_y(90°)·z = (1, 0, 0).
  EXPECT_NEAR(out[18 + 2], -1.0f, 1e-6);
  EXPECT_NEAR(out[18 + 3], 1.0f, 1e-6);
}

}  // namespace
}  // namespace sims::humanoid
