#include "sims/humanoid/humanoid.h"

#include <algorithm>
#include <cmath>

#include "sims/core/error.h"

namespace sims::humanoid {

const std::array<const char*, kNumBodies>& BodyNames() {
  static const std::array<const char*, kNumBodies> names = {
      "pelvis",     "torso",          "head",           "right_upper_arm", "right_lower_arm",
      "right_hand", "left_upper_arm", "left_lower_arm", "left_hand",       "right_thigh",
      "right_shin", "right_foot",     "left_thigh",     "left_shin",       "left_foot"};
  return names;
}

const std::array<JointSpec, kNumJoints>& Joints() {
  static const std::array<JointSpec, kNumJoints> joints = {{
      {"abdomen", kTorso, 0, 3},
      {"neck", kHead, 3, 3},
      {"right_shoulder", kRightUpperArm, 6, 3},
      {"right_elbow", kRightLowerArm, 9, 1},
      {"left_shoulder", kLeftUpperArm, 10, 3},
      {"left_elbow", kLeftLowerArm, 13, 1},
      {"right_hip", kRightThigh, 14, 3},
      {"right_knee", kRightShin, 17, 1},
      {"right_ankle", kRightFoot, 18, 3},
      {"left_hip", kLeftThigh, 21, 3},
      {"left_knee", kLeftShin, 24, 1},
      {"left_ankle", kLeftFoot, 25, 3},
  }};
  return joints;
}

const std::array<const char*, kNumDofs>& DofNames() {
  static const std::array<const char*, kNumDofs> names = {
      "abdomen_x",        "abdomen_y",    "abdomen_z",        "neck_x",
      "neck_y",           "neck_z",       "right_shoulder_x", "right_shoulder_y",
      "right_shoulder_z", "right_elbow",  "left_shoulder_x",  "left_shoulder_y",
      "left_shoulder_z",  "left_elbow",   "right_hip_x",      "right_hip_y",
      "right_hip_z",      "right_knee",   "right_ankle_x",    "right_ankle_y",
      "right_ankle_z",    "left_hip_x",   "left_hip_y",       "left_hip_z",
      "left_knee",        "left_ankle_x", "left_ankle_y",     "left_ankle_z"};
  return names;
}

const std::array<const char*, kNumContactJoints>& ContactJointNames() {
  static const std::array<const char*, kNumContactJoints> names = {
      "pelvis",     "left_hip",   "left_knee",      "left_foot",   "right_hip",
      "right_knee", "right_foot", "torso",          "head",        "left_shoulder",
      "left_elbow", "left_hand",  "right_shoulder", "right_elbow", "right_hand"};
  return names;
}

const std::array<int, kNumContactJoints>& ContactJointBodies() {
  static const std::array<int, kNumContactJoints> bodies = {
      kPelvis,       kLeftThigh, kLeftShin,      kLeftFoot,      kRightThigh,
      kRightShin,    kRightFoot, kPelvis,        kTorso,         kLeftUpperArm,
      kLeftLowerArm, kLeftHand,  kRightUpperArm, kRightLowerArm, kRightHand};
  return bodies;
}

Eigen::Vector3d ContactJointOffset(int contact_joint) {
  if (contact_joint == kCjTorso) return {0, 0, 0.386151};
  if (contact_joint == kCjHead) return {0, 0, 0.373894};
  return Eigen::Vector3d::Zero();
}

const std::array<int, kNumKeyBodies>& KeyBodies() {
  static const std::array<int, kNumKeyBodies> keys = {kRightHand, kLeftHand, kRightFoot, kLeftFoot};
  return keys;
}

namespace {
template <std::size_t N>
int IndexByName(const std::array<const char*, N>& names, const std::string& name,
                const char* what) {
  for (std::size_t i = 0; i < N; ++i)
    if (name == names[i]) return static_cast<int>(i);
  std::string list;
  for (auto* n : names) list += (list.empty() ? "" : ", ") + std::string(n);
  ThrowInputError(what, "", "one of: " + list, "'" + name + "'");
}
}  // namespace

int ContactJointByName(const std::string& name) {
  return IndexByName(ContactJointNames(), name, "contact joint name");
}

int BodyByName(const std::string& name) { return IndexByName(BodyNames(), name, "body name"); }

Humanoid::Humanoid(MjModelPtr model) : model_(std::move(model)) {
  const mjModel* m = model_.get();
  SIMS_CHECK(m != nullptr);
  const std::string src = "humanoid model";
  for (int b = 0; b < kNumBodies; ++b) {
    body_ids_[b] = mj_name2id(m, mjOBJ_BODY, BodyNames()[b]);
    if (body_ids_[b] < 0) ThrowInputError(src, BodyNames()[b], "a body with this name", "missing");
  }
  const int root_joint = m->body_jntadr[body_ids_[kPelvis]];
  if (root_joint < 0 || m->jnt_type[root_joint] != mjJNT_FREE)
    ThrowInputError(src, "pelvis", "a free root joint", "none");
  root_qpos_adr_ = m->jnt_qposadr[root_joint];
  root_qvel_adr_ = m->jnt_dofadr[root_joint];
  for (int i = 0; i < kNumDofs; ++i) {
    const int j = mj_name2id(m, mjOBJ_JOINT, DofNames()[i]);
    if (j < 0 || m->jnt_type[j] != mjJNT_HINGE)
      ThrowInputError(src, DofNames()[i], "a hinge joint with this name", "missing");
    dof_qpos_adr_[i] = m->jnt_qposadr[j];
    dof_qvel_adr_[i] = m->jnt_dofadr[j];
    actuator_ids_[i] = -1;
    for (int a = 0; a < m->nu; ++a)
      if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == j)
        actuator_ids_[i] = a;
    if (actuator_ids_[i] < 0)
      ThrowInputError(src, DofNames()[i], "an actuator driving this joint", "none");
    const int a = actuator_ids_[i];
    lower_[i] = m->jnt_range[2 * j];
    upper_[i] = m->jnt_range[2 * j + 1];
    kp_[i] = m->actuator_gainprm[a * mjNGAIN];
    kd_[i] = m->dof_damping[dof_qvel_adr_[i]];
    torque_limit_[i] = m->actuator_forcerange[2 * a + 1];
  }
  // PD target mapping (ASE _build_pd_action_offset_scale).
  for (const JointSpec& js : Joints()) {
    if (js.dof_count == 3) {
      double max_abs = 0;
      for (int k = 0; k < 3; ++k)
        max_abs = std::max(
            {max_abs, std::abs(lower_[js.dof_offset + k]), std::abs(upper_[js.dof_offset + k])});
      const double scale = std::min(1.2 * max_abs, M_PI);
      for (int k = 0; k < 3; ++k) {
        pd_offset_[js.dof_offset + k] = 0.0;
        pd_scale_[js.dof_offset + k] = scale;
      }
    } else {
      const int i = js.dof_offset;
      pd_offset_[i] = 0.5 * (upper_[i] + lower_[i]);
      pd_scale_[i] = 0.7 * (upper_[i] - lower_[i]);
    }
  }
  geom_body_.assign(m->ngeom, -1);
  for (int g = 0; g < m->ngeom; ++g)
    for (int b = 0; b < kNumBodies; ++b)
      if (m->geom_bodyid[g] == body_ids_[b]) geom_body_[g] = b;
  for (int b = 0; b < kNumBodies; ++b) total_mass_ += m->body_mass[body_ids_[b]];
}

void Humanoid::ActionToTargets(const float* action, double* targets) const {
  for (int i = 0; i < kNumDofs; ++i) {
    const double a = std::clamp(static_cast<double>(action[i]), -1.0, 1.0);
    targets[i] = pd_offset_[i] + pd_scale_[i] * a;
  }
}

void Humanoid::TargetsToAction(const double* targets, float* action) const {
  for (int i = 0; i < kNumDofs; ++i)
    action[i] = static_cast<float>((targets[i] - pd_offset_[i]) / pd_scale_[i]);
}

}  // namespace sims::humanoid
