// The humanoid's kinematic tree read from the compiled MuJoCo model (body offsets, joint
// limits, foot boxes) with a fast Eigen forward kinematics and analytic limb IK, used by the
// retargeter, the BVH exporter and the synthetic clip generator. Tests check it against
// humanoid::ForwardKinematics.
#pragma once

#include <array>
#include <memory>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sims/humanoid/humanoid.h"

namespace sims::motion {

/// 28 hinge angles in humanoid::DofNames() order.
using DofVector = Eigen::Matrix<double, humanoid::kNumDofs, 1>;

/// Kinematic description of the AMP humanoid.
struct HumanoidSkeleton {
  std::array<int, humanoid::kNumBodies> parent{};            ///< Parent body (−1 for the pelvis).
  std::array<Eigen::Vector3d, humanoid::kNumBodies> offset;  ///< Body origin in the parent frame.
  std::array<Eigen::Quaterniond, humanoid::kNumBodies> rest;  ///< Body frame in the parent frame.
  std::array<int, humanoid::kNumBodies> joint{};  ///< Joint index moving the body, or −1.
  DofVector lower = DofVector::Zero();            ///< Joint lower limits (rad).
  DofVector upper = DofVector::Zero();            ///< Joint upper limits (rad).
  std::array<Eigen::Vector3d, 2>
      foot_box_center;  ///< Foot box centre in the foot frame (right, left).
  std::array<Eigen::Vector3d, 2> foot_box_half;  ///< Foot box half extents (right, left).

  /// Reads the layout from a humanoid model.
  static HumanoidSkeleton FromHumanoid(const humanoid::Humanoid& humanoid);
  /// The skeleton of the default humanoid asset (built once, thread-safe).
  static const HumanoidSkeleton& Default();
  /// The default humanoid itself (shared, built once).
  static std::shared_ptr<const humanoid::Humanoid> DefaultHumanoid();

  /// Hip→knee length of a leg (m).
  double thigh_length() const { return offset[humanoid::kRightShin].norm(); }
  /// Knee→ankle length (m).
  double shin_length() const { return offset[humanoid::kRightFoot].norm(); }
  /// Shoulder→elbow length (m).
  double upper_arm_length() const { return offset[humanoid::kRightLowerArm].norm(); }
  /// Elbow→hand length (m).
  double lower_arm_length() const { return offset[humanoid::kRightHand].norm(); }
  /// Ankle height above the sole when the foot is flat (m).
  double ankle_height() const { return foot_box_half[0].z() - foot_box_center[0].z(); }
  /// Pelvis height of the straight-legged zero pose with soles on the floor (m).
  double standing_root_height() const;
};

/// World poses of the 15 bodies.
struct SkeletonPose {
  std::array<Eigen::Vector3d, humanoid::kNumBodies> pos;     ///< p_WB.
  std::array<Eigen::Quaterniond, humanoid::kNumBodies> rot;  ///< R_WB.
};

/// Local rotation of joint `j` from its hinge angles (Rx·Ry·Rz, or Ry for 1-DoF joints).
Eigen::Quaterniond JointRotation(int j, const DofVector& dofs);

/// Forward kinematics of a root pose and hinge angles.
void SkeletonForwardKinematics(const HumanoidSkeleton& skel, const Eigen::Vector3d& root_pos,
                               const Eigen::Quaterniond& root_rot, const DofVector& dofs,
                               SkeletonPose* pose);

/// The eight corners of a foot box in world coordinates (`left` picks the foot).
std::array<Eigen::Vector3d, 8> FootBoxCorners(const HumanoidSkeleton& skel,
                                              const SkeletonPose& pose, bool left);

/// Lowest world z of a foot box (the sole when the foot is flat).
double SoleHeight(const HumanoidSkeleton& skel, const SkeletonPose& pose, bool left);

/// Result of a limb IK solve.
struct LimbIkResult {
  double position_error = 0;  ///< Distance between reached and requested end point (m).
  bool clamped = false;       ///< Some angle hit a joint limit.
};

/// Leg IK: writes hip (3), knee and ankle (3) angles of one leg so the ankle reaches
/// `p_W_ankle` with foot orientation `R_W_foot`, the knee pointing along `knee_dir_W`
/// (projected), given the pelvis pose. Angles are clamped to the joint limits.
LimbIkResult SolveLegIk(const HumanoidSkeleton& skel, bool left, const Eigen::Vector3d& root_pos,
                        const Eigen::Quaterniond& root_rot, const Eigen::Vector3d& p_W_ankle,
                        const Eigen::Quaterniond& R_W_foot, const Eigen::Vector3d& knee_dir_W,
                        DofVector* dofs);

/// Arm IK: writes shoulder (3) and elbow angles so the hand origin reaches `p_W_hand` with
/// the elbow pointing along `elbow_dir_W` (projected), given the torso's world pose (which
/// the caller obtains from the pelvis and abdomen angles).
LimbIkResult SolveArmIk(const HumanoidSkeleton& skel, bool left, const Eigen::Vector3d& p_W_torso,
                        const Eigen::Quaterniond& R_W_torso, const Eigen::Vector3d& p_W_hand,
                        const Eigen::Vector3d& elbow_dir_W, DofVector* dofs);

/// Clamps angles to the limits; returns the largest excess (rad) and, per DoF, the excess.
double ClampToLimits(const HumanoidSkeleton& skel, DofVector* dofs, DofVector* excess = nullptr);

}  // namespace sims::motion
