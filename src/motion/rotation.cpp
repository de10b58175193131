#include "sims/motion/rotation.h"

#include <cmath>

#include "sims/core/error.h"

namespace sims::motion {

namespace {

Eigen::Matrix3d AxisRotation(int axis, double angle) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  a[axis] = 1.0;
  return Eigen::AngleAxisd(angle, a).toRotationMatrix();
}

// Even permutations of (x, y, z) are the cyclic ones.
bool IsEven(const AxisOrder& o) { return (o[1] - o[0] + 3) % 3 == 1; }

double Excess(double v, double lo, double hi) {
  if (v < lo) return lo - v;
  if (v > hi) return v - hi;
  return 0.0;
}

}  // namespace

Eigen::Matrix3d EulerToMatrix(const AxisOrder& order, const Eigen::Vector3d& angles) {
  return AxisRotation(order[0], angles[0]) * AxisRotation(order[1], angles[1]) *
         AxisRotation(order[2], angles[2]);
}

Eigen::Vector3d MatrixToEuler(const AxisOrder& order, const Eigen::Matrix3d& r) {
  SIMS_CHECK(order[0] != order[1] && order[1] != order[2] && order[0] != order[2]);
  const int i = order[0], j = order[1], k = order[2];
  // For R = Ri(a)·Rj(b)·Rk(c): R(i,k) = ±sin b, and a, c follow from the row/column of k, i.
  const double s = IsEven(order) ? 1.0 : -1.0;
  const double sb = std::clamp(s * r(i, k), -1.0, 1.0);
  const double b = std::asin(sb);
  double a, c;
  if (std::abs(sb) < 1.0 - 1e-10) {
    a = std::atan2(-s * r(j, k), r(k, k));
    c = std::atan2(-s * r(i, j), r(i, i));
  } else {
    // Gimbal lock: only a ± c is defined; put it all in a.
    c = 0.0;
    a = std::atan2(s * r(k, j), r(j, j));
  }
  return {a, b, c};
}

double WrapAngle(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a <= 0) a += 2.0 * M_PI;
  return a - M_PI;
}

Eigen::Vector3d AlternateEuler(const Eigen::Vector3d& angles) {
  return {WrapAngle(angles[0] + M_PI), WrapAngle(M_PI - angles[1]), WrapAngle(angles[2] + M_PI)};
}

Eigen::Vector3d DecomposeHingeTriple(const Eigen::Quaterniond& q, const Eigen::Vector3d& lower,
                                     const Eigen::Vector3d& upper,
                                     const Eigen::Vector3d* previous) {
  const Eigen::Vector3d a = MatrixToEuler({0, 1, 2}, q.normalized().toRotationMatrix());
  const Eigen::Vector3d b = AlternateEuler(a);
  double ea = 0, eb = 0;
  for (int k = 0; k < 3; ++k) {
    ea += Excess(a[k], lower[k], upper[k]);
    eb += Excess(b[k], lower[k], upper[k]);
  }
  if (std::abs(ea - eb) > 1e-9) return ea < eb ? a : b;
  if (previous) return (a - *previous).squaredNorm() <= (b - *previous).squaredNorm() ? a : b;
  return a;
}

double ProjectToYHinge(const Eigen::Quaterniond& q, const Eigen::Vector3d& bone) {
  // Ry(θ) maps the bone (bx, 0, bz) to (bx cosθ + bz sinθ, ·, −bx sinθ + bz cosθ); match the
  // angle of the rotated bone in the x–z plane.
  const Eigen::Vector3d v = q * bone;
  return WrapAngle(std::atan2(v.x(), v.z()) - std::atan2(bone.x(), bone.z()));
}

Eigen::Vector3d QuatToRotationVector(const Eigen::Quaterniond& q_in) {
  Eigen::Quaterniond q = q_in.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  const double angle = 2.0 * std::atan2(s, q.w());
  return v * (angle / s);
}

Eigen::Quaterniond RotationVectorToQuat(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-12)
    return Eigen::Quaterniond(1.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

Eigen::Quaterniond YawQuat(double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
}

}  // namespace sims::motion
