// Humanoid state in two forms: generalised coordinates (HumanoidPose) and per-body world
// states (BodyStates). Motion clips and the environment both go through these, so features
// computed from a clip and from the simulation use the same code.
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sims/humanoid/humanoid.h"

namespace sims::humanoid {

/// Generalised state. Velocities are world-frame (MuJoCo stores the root angular velocity in
/// the root's local frame; Read/WritePose convert).
struct HumanoidPose {
  Eigen::Vector3d root_pos = {0, 0, kDefaultRootHeight};         ///< p_WP (pelvis origin).
  Eigen::Quaterniond root_rot = Eigen::Quaterniond::Identity();  ///< R_WP.
  Eigen::Vector3d root_lin_vel = Eigen::Vector3d::Zero();        ///< v_WP in W.
  Eigen::Vector3d root_ang_vel = Eigen::Vector3d::Zero();        ///< ω_WP in W.
  Eigen::Matrix<double, kNumDofs, 1> dof_pos =
      Eigen::Matrix<double, kNumDofs, 1>::Zero();  ///< Hinge angles (rad).
  Eigen::Matrix<double, kNumDofs, 1> dof_vel =
      Eigen::Matrix<double, kNumDofs, 1>::Zero();  ///< Hinge rates (rad/s).
};

/// World-frame state of the 15 bodies (origin position, orientation, velocities at the origin).
struct BodyStates {
  std::array<Eigen::Vector3d, kNumBodies> pos;      ///< p_WB.
  std::array<Eigen::Quaterniond, kNumBodies> rot;   ///< R_WB.
  std::array<Eigen::Vector3d, kNumBodies> lin_vel;  ///< v_WB (body origin) in W.
  std::array<Eigen::Vector3d, kNumBodies> ang_vel;  ///< ω_WB in W.
};

/// Reads qpos/qvel into a pose.
void ReadPose(const Humanoid& h, const mjData* d, HumanoidPose* pose);

/// Writes a pose into qpos/qvel (does not run any MuJoCo stage).
void WritePose(const Humanoid& h, const HumanoidPose& pose, mjData* d);

/// Reads body states; needs positions and velocities computed (mj_forward, mj_step1, or
/// mj_kinematics + mj_comPos + mj_comVel).
void ReadBodyStates(const Humanoid& h, const mjData* d, BodyStates* bodies);

/// Forward kinematics of a pose using `scratch` (writes the pose, runs the position and
/// velocity stages without collision detection, reads body states).
void ForwardKinematics(const Humanoid& h, const HumanoidPose& pose, mjData* scratch,
                       BodyStates* bodies);

/// World position of a contact joint (UniHSI joint→body map with torso/head offsets).
Eigen::Vector3d ContactJointPosition(const BodyStates& bodies, int contact_joint);

}  // namespace sims::humanoid
