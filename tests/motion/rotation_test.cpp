#include "sims/motion/rotation.h"

#include <gtest/gtest.h>

#include "sims/core/rng.h"
#include "sims/humanoid/features.h"

namespace sims::motion {
namespace {

TEST(RotationTest, EulerRoundTripAllOrders) {
  const AxisOrder orders[] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  Rng rng(1);
  for (const auto& o : orders) {
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d a(rng.Uniform(-3, 3), rng.Uniform(-1.5, 1.5), rng.Uniform(-3, 3));
      const Eigen::Matrix3d r = EulerToMatrix(o, a);
      const Eigen::Vector3d b = MatrixToEuler(o, r);
      EXPECT_LT((EulerToMatrix(o, b) - r).norm(), 1e-9);
      EXPECT_LT((b - a).norm(), 1e-8) << o[0] << o[1] << o[2];
      EXPECT_LT((EulerToMatrix(o, AlternateEuler(b)) - r).norm(), 1e-9);
    }
    // Gimbal lock still reproduces the rotation.
    const Eigen::Matrix3d r = EulerToMatrix(o, Eigen::Vector3d(0.3, M_PI / 2, -0.7));
    EXPECT_LT((EulerToMatrix(o, MatrixToEuler(o, r)) - r).norm(), 1e-9);
  }
}

TEST(RotationTest, HingeTripleMatchesSimAndPrefersLimits) {
  const Eigen::Vector3d a(0.2, -0.4, 0.9);
  const Eigen::Quaterniond q = humanoid::HingeTripleRotation(a[0], a[1], a[2]);
  const Eigen::Vector3d lo(-1, -1, -1), hi(1, 1, 1);
  EXPECT_LT((DecomposeHingeTriple(q, lo, hi) - a).norm(), 1e-9);
  // A shoulder raised overhead (y = −170°) lies outside asin's range: the limits pick it.
  const Eigen::Vector3d b(0.1, -170 * M_PI / 180, 0.2);
  const Eigen::Quaterniond qb = humanoid::HingeTripleRotation(b[0], b[1], b[2]);
  const Eigen::Vector3d got = DecomposeHingeTriple(qb, Eigen::Vector3d(-M_PI, -M_PI, -M_PI / 2),
                                                   Eigen::Vector3d(M_PI / 4, M_PI / 3, M_PI / 2));
  EXPECT_LT((got - b).norm(), 1e-9);
}

TEST(RotationTest, YHingeProjectionAndRotationVectors) {
  const Eigen::Vector3d bone(0, 0, -1);
  for (double t : {-2.5, -1.0, 0.0, 0.7, 2.0}) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(t, Eigen::Vector3d::UnitY()));
    EXPECT_NEAR(ProjectToYHinge(q, bone), t, 1e-12);
  }
  const Eigen::Vector3d v(0.3, -1.2, 0.5);
  EXPECT_LT((QuatToRotationVector(RotationVectorToQuat(v)) - v).norm(), 1e-12);
  EXPECT_NEAR(WrapAngle(3 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(WrapAngle(-0.5), -0.5, 1e-15);
}

}  // namespace
}  // namespace sims::motion
