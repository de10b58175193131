// Rotation helpers shared by BVH I/O, retargeting, mirroring and the synthetic generator:
// Euler angles in any Tait–Bryan axis order, the humanoid's hinge-triple decomposition
// (Rx·Ry·Rz) with joint limits, and rotation-vector conversions.
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sims::motion {

/// Three distinct axes (0 = x, 1 = y, 2 = z); {2, 0, 1} means R = Rz(a0)·Rx(a1)·Ry(a2).
using AxisOrder = std::array<int, 3>;

/// R = R_order[0](a[0]) · R_order[1](a[1]) · R_order[2](a[2]) (radians).
Eigen::Matrix3d EulerToMatrix(const AxisOrder& order, const Eigen::Vector3d& angles);

/// The Euler angles of R in `order` with the middle angle in [−π/2, π/2].
Eigen::Vector3d MatrixToEuler(const AxisOrder& order, const Eigen::Matrix3d& r);

/// The other solution (a0 + π, π − a1, a2 + π), wrapped to (−π, π]; same rotation.
Eigen::Vector3d AlternateEuler(const Eigen::Vector3d& angles);

/// Wraps an angle to (−π, π].
double WrapAngle(double a);

/// Hinge angles (x, y, z) of a 3-DoF joint rotation q = Rx·Ry·Rz. Of the two Euler solutions
/// it picks the one closest to [lower, upper] (summed excess), then the one nearest `previous`
/// when given, so decomposed sequences stay continuous.
Eigen::Vector3d DecomposeHingeTriple(const Eigen::Quaterniond& q, const Eigen::Vector3d& lower,
                                     const Eigen::Vector3d& upper,
                                     const Eigen::Vector3d* previous = nullptr);

/// Angle of a 1-DoF y hinge that best reproduces q's image of `bone` (a child bone direction
/// in the joint frame at zero angle): the swing of the bone projected on the x–z plane.
double ProjectToYHinge(const Eigen::Quaterniond& q, const Eigen::Vector3d& bone);

/// Rotation vector (axis · angle, angle in [0, π]) of q.
Eigen::Vector3d QuatToRotationVector(const Eigen::Quaterniond& q);

/// Quaternion of a rotation vector.
Eigen::Quaterniond RotationVectorToQuat(const Eigen::Vector3d& v);

/// Rotation about world z by `yaw`.
Eigen::Quaterniond YawQuat(double yaw);

}  // namespace sims::motion
