// The AMP humanoid: its fixed layout (15 bodies, 12 joints, 28 DoF, 15 contact joints) and a
// wrapper that resolves the layout against a compiled mjModel (humanoid alone or in a scene).
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "sims/humanoid/model_builder.h"

namespace sims::humanoid {

inline constexpr int kNumBodies = 15;         ///< AMP bodies (pelvis first).
inline constexpr int kNumJoints = 12;         ///< AMP joints (3-DoF or 1-DoF each).
inline constexpr int kNumDofs = 28;           ///< Actuated hinge DoF.
inline constexpr int kNumContactJoints = 15;  ///< UniHSI/SIMS contact-goal joints.
inline constexpr int kNumKeyBodies = 4;       ///< Hands and feet for the AMP observation.
inline constexpr int kRootQposSize = 7;       ///< Free joint: position + quaternion (w x y z).
inline constexpr int kRootQvelSize = 6;       ///< Free joint: linear (world) + angular (local).
inline constexpr double kDefaultRootHeight = 0.89;  ///< Standing pelvis height (AMP default).

/// AMP body indices (the order of amp_humanoid.xml).
enum Body : int {
  kPelvis = 0,
  kTorso,
  kHead,
  kRightUpperArm,
  kRightLowerArm,
  kRightHand,
  kLeftUpperArm,
  kLeftLowerArm,
  kLeftHand,
  kRightThigh,
  kRightShin,
  kRightFoot,
  kLeftThigh,
  kLeftShin,
  kLeftFoot,
};

/// UniHSI contact-joint indices (the order of UniHSI's strikeBodyNames).
enum ContactJoint : int {
  kCjPelvis = 0,
  kCjLeftHip,
  kCjLeftKnee,
  kCjLeftFoot,
  kCjRightHip,
  kCjRightKnee,
  kCjRightFoot,
  kCjTorso,
  kCjHead,
  kCjLeftShoulder,
  kCjLeftElbow,
  kCjLeftHand,
  kCjRightShoulder,
  kCjRightElbow,
  kCjRightHand,
};

/// One AMP joint: the body it moves and its slice of the 28 DoF.
struct JointSpec {
  const char* name;  ///< Joint group name ("abdomen", "right_elbow", ...).
  int body;          ///< AMP body index the joint rotates.
  int dof_offset;    ///< First DoF index.
  int dof_count;     ///< 3 (hinges x, y, z composing as Rx*Ry*Rz) or 1 (hinge about y).
};

/// Body names in AMP order.
const std::array<const char*, kNumBodies>& BodyNames();
/// The 12 joints in DoF order.
const std::array<JointSpec, kNumJoints>& Joints();
/// The 28 hinge names in DoF order.
const std::array<const char*, kNumDofs>& DofNames();
/// Contact-joint names in UniHSI order ("pelvis", "left_hip", ..., "right_hand").
const std::array<const char*, kNumContactJoints>& ContactJointNames();
/// Body carrying each contact joint (torso/head use an offset point, see ContactJointOffset).
const std::array<int, kNumContactJoints>& ContactJointBodies();
/// Offset of a contact joint in its body's frame (UniHSI: torso 0.386 above the pelvis, head
/// 0.374 above the torso; zero for the others).
Eigen::Vector3d ContactJointOffset(int contact_joint);
/// Hands and feet (right hand, left hand, right foot, left foot).
const std::array<int, kNumKeyBodies>& KeyBodies();
/// Contact-joint index by name; throws sims::Error listing the valid names.
int ContactJointByName(const std::string& name);
/// AMP body index by name; throws sims::Error listing the valid names.
int BodyByName(const std::string& name);

/// The humanoid inside a compiled model: index tables, PD gains and the action mapping.
/// Immutable after construction; shared read-only by all environments.
class Humanoid {
 public:
  /// Resolves the layout by name; throws sims::Error if the model lacks it.
  explicit Humanoid(MjModelPtr model);

  /// The compiled model.
  const mjModel* model() const { return model_.get(); }
  /// Shared ownership of the model.
  const MjModelPtr& model_ptr() const { return model_; }
  /// mjModel body id of an AMP body.
  int body_id(int body) const { return body_ids_[body]; }
  /// qpos address of the root free joint.
  int root_qpos_adr() const { return root_qpos_adr_; }
  /// qvel address of the root free joint.
  int root_qvel_adr() const { return root_qvel_adr_; }
  /// qpos address of DoF i.
  int dof_qpos_adr(int i) const { return dof_qpos_adr_[i]; }
  /// qvel address of DoF i.
  int dof_qvel_adr(int i) const { return dof_qvel_adr_[i]; }
  /// Actuator id driving DoF i.
  int actuator_id(int i) const { return actuator_ids_[i]; }
  /// True if geom g belongs to the humanoid.
  bool is_humanoid_geom(int g) const { return geom_body_[g] >= 0; }
  /// AMP body of geom g, or -1 for scene/floor geoms.
  int geom_body(int g) const { return geom_body_[g]; }
  /// Lower joint limits (rad).
  const Eigen::Matrix<double, kNumDofs, 1>& dof_lower() const { return lower_; }
  /// Upper joint limits (rad).
  const Eigen::Matrix<double, kNumDofs, 1>& dof_upper() const { return upper_; }
  /// Position gains.
  const Eigen::Matrix<double, kNumDofs, 1>& kp() const { return kp_; }
  /// Damping gains.
  const Eigen::Matrix<double, kNumDofs, 1>& kd() const { return kd_; }
  /// Torque limits (N·m).
  const Eigen::Matrix<double, kNumDofs, 1>& torque_limit() const { return torque_limit_; }
  /// PD target offset: 0 for 3-DoF joints, mid-range for 1-DoF joints.
  const Eigen::Matrix<double, kNumDofs, 1>& pd_offset() const { return pd_offset_; }
  /// PD target scale: min(1.2·max|limit|, π) for 3-DoF joints, 0.7·range for 1-DoF joints.
  const Eigen::Matrix<double, kNumDofs, 1>& pd_scale() const { return pd_scale_; }
  /// targets = offset + scale · clamp(action, −1, 1) for 28 actions.
  void ActionToTargets(const float* action, double* targets) const;
  /// Inverse of ActionToTargets (unclamped), e.g. to hold a pose.
  void TargetsToAction(const double* targets, float* action) const;
  /// Total mass of the humanoid bodies (kg).
  double total_mass() const { return total_mass_; }

 private:
  MjModelPtr model_;
  std::array<int, kNumBodies> body_ids_{};
  std::array<int, kNumDofs> dof_qpos_adr_{}, dof_qvel_adr_{}, actuator_ids_{};
  std::vector<int> geom_body_;
  int root_qpos_adr_ = 0, root_qvel_adr_ = 0;
  Eigen::Matrix<double, kNumDofs, 1> lower_, upper_, kp_, kd_, torque_limit_, pd_offset_, pd_scale_;
  double total_mass_ = 0;
};

}  // namespace sims::humanoid
