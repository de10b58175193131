#include "sims/motion/skeleton.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "sims/core/error.h"
#include "sims/humanoid/features.h"
#include "sims/humanoid/model_builder.h"
#include "sims/motion/rotation.h"

namespace sims::motion {

namespace {

// Bodies whose offsets the analytic limb IK assumes to lie along the parent's −z axis.
constexpr int kStraightBodies[] = {
    humanoid::kRightShin,     humanoid::kRightFoot, humanoid::kLeftShin,     humanoid::kLeftFoot,
    humanoid::kRightLowerArm, humanoid::kRightHand, humanoid::kLeftLowerArm, humanoid::kLeftHand};

Eigen::Vector3d Perpendicular(const Eigen::Vector3d& v, const Eigen::Vector3d& axis,
                              const Eigen::Vector3d& fallback) {
  Eigen::Vector3d p = v - v.dot(axis) * axis;
  if (p.norm() < 1e-6) p = fallback - fallback.dot(axis) * axis;
  if (p.norm() < 1e-9) p = axis.unitOrthogonal();
  return p.normalized();
}

// Rotation taking frame (a, b) to frame (a2, b2); a ⟂ b and a2 ⟂ b2 are unit vectors.
Eigen::Matrix3d AlignFrames(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& a2, const Eigen::Vector3d& b2) {
  Eigen::Matrix3d src, dst;
  src << a, b, a.cross(b);
  dst << a2, b2, a2.cross(b2);
  return dst * src.transpose();
}

int ClampDof(const HumanoidSkeleton& skel, int i, double* v) {
  const double c = std::clamp(*v, skel.lower[i], skel.upper[i]);
  const int clamped = std::abs(c - *v) > 1e-9 ? 1 : 0;
  *v = c;
  return clamped;
}

}  // namespace

HumanoidSkeleton HumanoidSkeleton::FromHumanoid(const humanoid::Humanoid& humanoid) {
  const mjModel* m = humanoid.model();
  HumanoidSkeleton s;
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    const int id = humanoid.body_id(b);
    const int pid = m->body_parentid[id];
    s.parent[b] = -1;
    for (int p = 0; p < humanoid::kNumBodies; ++p)
      if (humanoid.body_id(p) == pid) s.parent[b] = p;
    SIMS_CHECK_MSG(b == humanoid::kPelvis || s.parent[b] >= 0,
                   "AMP body parent outside the humanoid");
    const double* p = m->body_pos + 3 * id;
    const double* q = m->body_quat + 4 * id;
    s.offset[b] = Eigen::Vector3d(p[0], p[1], p[2]);
    s.rest[b] = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
    s.joint[b] = -1;
  }
  for (int j = 0; j < humanoid::kNumJoints; ++j) s.joint[humanoid::Joints()[j].body] = j;
  s.lower = humanoid.dof_lower();
  s.upper = humanoid.dof_upper();
  for (int b : kStraightBodies) {
    SIMS_CHECK_MSG(std::abs(s.offset[b].x()) < 1e-9 && std::abs(s.offset[b].y()) < 1e-9 &&
                       s.offset[b].z() < 0 &&
                       s.rest[b].angularDistance(Eigen::Quaterniond::Identity()) < 1e-9,
                   std::string("limb IK expects body ") + humanoid::BodyNames()[b] +
                       " straight below its parent");
  }
  for (int side = 0; side < 2; ++side) {
    const int foot = humanoid.body_id(side == 0 ? humanoid::kRightFoot : humanoid::kLeftFoot);
    bool found = false;
    for (int g = 0; g < m->ngeom && !found; ++g) {
      if (m->geom_bodyid[g] != foot || m->geom_type[g] != mjGEOM_BOX) continue;
      s.foot_box_center[side] =
          Eigen::Vector3d(m->geom_pos[3 * g], m->geom_pos[3 * g + 1], m->geom_pos[3 * g + 2]);
      s.foot_box_half[side] =
          Eigen::Vector3d(m->geom_size[3 * g], m->geom_size[3 * g + 1], m->geom_size[3 * g + 2]);
      found = true;
    }
    if (!found) throw Error("humanoid model: foot bodies need a box geom (the sole)");
  }
  return s;
}

std::shared_ptr<const humanoid::Humanoid> HumanoidSkeleton::DefaultHumanoid() {
  static std::once_flag once;
  static std::shared_ptr<const humanoid::Humanoid> h;
  std::call_once(once,
                 [] { h = std::make_shared<const humanoid::Humanoid>(humanoid::BuildModel()); });
  return h;
}

const HumanoidSkeleton& HumanoidSkeleton::Default() {
  static const HumanoidSkeleton s = FromHumanoid(*DefaultHumanoid());
  return s;
}

double HumanoidSkeleton::standing_root_height() const {
  return -(offset[humanoid::kRightThigh].z() + offset[humanoid::kRightShin].z() +
           offset[humanoid::kRightFoot].z()) +
         ankle_height();
}

Eigen::Quaterniond JointRotation(int j, const DofVector& dofs) {
  const humanoid::JointSpec& js = humanoid::Joints()[j];
  const int o = js.dof_offset;
  if (js.dof_count == 3) return humanoid::HingeTripleRotation(dofs[o], dofs[o + 1], dofs[o + 2]);
  return Eigen::Quaterniond(Eigen::AngleAxisd(dofs[o], Eigen::Vector3d::UnitY()));
}

void SkeletonForwardKinematics(const HumanoidSkeleton& skel, const Eigen::Vector3d& root_pos,
                               const Eigen::Quaterniond& root_rot, const DofVector& dofs,
                               SkeletonPose* pose) {
  pose->pos[0] = root_pos;
  pose->rot[0] = root_rot.normalized();
  // AMP order lists every parent before its children.
  for (int b = 1; b < humanoid::kNumBodies; ++b) {
    const int p = skel.parent[b];
    pose->pos[b] = pose->pos[p] + pose->rot[p] * skel.offset[b];
    Eigen::Quaterniond r = pose->rot[p] * skel.rest[b];
    if (skel.joint[b] >= 0) r = r * JointRotation(skel.joint[b], dofs);
    pose->rot[b] = r;
  }
}

std::array<Eigen::Vector3d, 8> FootBoxCorners(const HumanoidSkeleton& skel,
                                              const SkeletonPose& pose, bool left) {
  const int side = left ? 1 : 0;
  const int b = left ? humanoid::kLeftFoot : humanoid::kRightFoot;
  std::array<Eigen::Vector3d, 8> out;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d sgn((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    const Eigen::Vector3d local =
        skel.foot_box_center[side] + sgn.cwiseProduct(skel.foot_box_half[side]);
    out[k] = pose.pos[b] + pose.rot[b] * local;
  }
  return out;
}

double SoleHeight(const HumanoidSkeleton& skel, const SkeletonPose& pose, bool left) {
  double z = 1e9;
  for (const auto& c : FootBoxCorners(skel, pose, left)) z = std::min(z, c.z());
  return z;
}

double ClampToLimits(const HumanoidSkeleton& skel, DofVector* dofs, DofVector* excess) {
  double worst = 0;
  for (int i = 0; i < humanoid::kNumDofs; ++i) {
    const double v = (*dofs)[i];
    const double c = std::clamp(v, skel.lower[i], skel.upper[i]);
    if (excess) (*excess)[i] = std::abs(v - c);
    worst = std::max(worst, std::abs(v - c));
    (*dofs)[i] = c;
  }
  return worst;
}

namespace {

double Excess(const HumanoidSkeleton& skel, int dof, const Eigen::Ref<const Eigen::VectorXd>& v) {
  double e = 0;
  for (int k = 0; k < v.size(); ++k)
    e += std::max({0.0, skel.lower[dof + k] - v[k], v[k] - skel.upper[dof + k]});
  return e;
}

// Swivel candidates (rad) around the hint, tried in order when the hint hits a joint limit.
const std::vector<double>& SwivelCandidates() {
  static const std::vector<double> c = [] {
    std::vector<double> v = {0.0};
    for (int k = 1; k <= 18; ++k) v.push_back(k * M_PI / 36), v.push_back(-k * M_PI / 36);
    return v;
  }();
  return c;
}

// Damped least squares on a limb's DoFs (within the limits) towards an end-body position and,
// optionally, orientation. Used when the analytic solution had to be clamped: near 90° of
// hip flexion the x and z hinges nearly align and clamping one of them alone moves the foot.
// Returns the final residual norm (the position miss when there is no orientation target).
double RefineLimb(const HumanoidSkeleton& skel, const Eigen::Vector3d& root_pos,
                  const Eigen::Quaterniond& root_rot, int end_body, int first_dof, int num_dofs,
                  const Eigen::Vector3d& p_target, const Eigen::Quaterniond* R_target,
                  DofVector* dofs) {
  constexpr double kRotWeight = 0.1;  // metres per radian
  const int m = R_target ? 6 : 3;
  auto residual = [&](const DofVector& d, Eigen::VectorXd* r) {
    SkeletonPose sp;
    SkeletonForwardKinematics(skel, root_pos, root_rot, d, &sp);
    r->resize(m);
    r->head<3>() = sp.pos[end_body] - p_target;
    if (R_target)
      r->tail<3>() = kRotWeight * QuatToRotationVector(R_target->conjugate() * sp.rot[end_body]);
  };
  Eigen::VectorXd r, r2;
  residual(*dofs, &r);
  double err = r.norm();
  double lambda = 1e-3;
  for (int it = 0; it < 60 && err > 1e-6; ++it) {
    Eigen::MatrixXd J(m, num_dofs);
    for (int k = 0; k < num_dofs; ++k) {
      DofVector d = *dofs;
      d[first_dof + k] += 1e-6;
      residual(d, &r2);
      J.col(k) = (r2 - r) / 1e-6;
    }
    const Eigen::MatrixXd A =
        J.transpose() * J + lambda * Eigen::MatrixXd::Identity(num_dofs, num_dofs);
    const Eigen::VectorXd step = A.ldlt().solve(-J.transpose() * r);
    DofVector d = *dofs;
    for (int k = 0; k < num_dofs; ++k)
      d[first_dof + k] = std::clamp(d[first_dof + k] + step[k], skel.lower[first_dof + k],
                                    skel.upper[first_dof + k]);
    residual(d, &r2);
    if (r2.norm() < err) {
      *dofs = d, r = r2, err = r2.norm();
      lambda = std::max(lambda * 0.3, 1e-7);
    } else {
      lambda *= 10;
      if (lambda > 1e3) break;
    }
  }
  return err;
}

}  // namespace

LimbIkResult SolveLegIk(const HumanoidSkeleton& skel, bool left, const Eigen::Vector3d& root_pos,
                        const Eigen::Quaterniond& root_rot, const Eigen::Vector3d& p_W_ankle,
                        const Eigen::Quaterniond& R_W_foot, const Eigen::Vector3d& knee_dir_W,
                        DofVector* dofs) {
  const int thigh = left ? humanoid::kLeftThigh : humanoid::kRightThigh;
  const int shin = left ? humanoid::kLeftShin : humanoid::kRightShin;
  const int foot = left ? humanoid::kLeftFoot : humanoid::kRightFoot;
  const int hip_dof = humanoid::Joints()[skel.joint[thigh]].dof_offset;
  const int knee_dof = humanoid::Joints()[skel.joint[shin]].dof_offset;
  const int ankle_dof = humanoid::Joints()[skel.joint[foot]].dof_offset;
  const double l1 = skel.offset[shin].norm(), l2 = skel.offset[foot].norm();

  const Eigen::Quaterniond R_WPf = root_rot.normalized() * skel.rest[thigh];  // hip parent frame
  const Eigen::Vector3d p_hip = root_pos + root_rot * skel.offset[thigh];
  const Eigen::Vector3d t = R_WPf.conjugate() * (p_W_ankle - p_hip);
  const double d = std::clamp(t.norm(), std::abs(l1 - l2) + 1e-6, (l1 + l2) * (1 - 1e-9));
  const double knee = std::acos(std::clamp((d * d - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1.0, 1.0));
  const Eigen::Vector3d u(-l2 * std::sin(knee), 0, -l1 - l2 * std::cos(knee));
  const Eigen::Vector3d a = u.normalized();
  // The knee cap points along the thigh's +x when the shin folds back (positive knee angle).
  const Eigen::Vector3d b = Perpendicular(Eigen::Vector3d::UnitX(), a, Eigen::Vector3d::UnitY());
  const Eigen::Vector3d a2 = t.norm() > 1e-9 ? t.normalized() : Eigen::Vector3d(0, 0, -1);
  const Eigen::Vector3d b2 =
      Perpendicular(R_WPf.conjugate() * knee_dir_W, a2, Eigen::Vector3d::UnitX());
  const Eigen::Vector3d prev_hip = dofs->segment<3>(hip_dof);
  const Eigen::Vector3d prev_ankle = dofs->segment<3>(ankle_dof);
  const double kv = std::clamp(knee, skel.lower[knee_dof], skel.upper[knee_dof]);

  // Hip and ankle angles for a knee swivel φ about the hip–ankle line; near hip flexion of
  // 90° the x and z hinges nearly align, so the swivel is searched to respect the limits.
  Eigen::Vector3d hip, ankle;
  double best = 1e18;
  for (double phi : SwivelCandidates()) {
    const Eigen::Vector3d b2s = Eigen::AngleAxisd(phi, a2) * b2;
    const Eigen::Quaterniond r_hip(AlignFrames(a, b, a2, b2s));
    const Eigen::Vector3d h = DecomposeHingeTriple(r_hip, skel.lower.segment<3>(hip_dof),
                                                   skel.upper.segment<3>(hip_dof), &prev_hip);
    const Eigen::Quaterniond R_shin =
        R_WPf * humanoid::HingeTripleRotation(h[0], h[1], h[2]) *
        Eigen::Quaterniond(Eigen::AngleAxisd(kv, Eigen::Vector3d::UnitY()));
    const Eigen::Vector3d an = DecomposeHingeTriple(R_shin.conjugate() * R_W_foot.normalized(),
                                                    skel.lower.segment<3>(ankle_dof),
                                                    skel.upper.segment<3>(ankle_dof), &prev_ankle);
    const double score =
        Excess(skel, hip_dof, h) + Excess(skel, ankle_dof, an) + 1e-3 * std::abs(phi);
    if (score < best) best = score, hip = h, ankle = an;
    if (score < 1e-9) break;  // the hint itself is within the limits
  }
  int clamped = 0;
  for (int k = 0; k < 3; ++k) clamped += ClampDof(skel, hip_dof + k, &hip[k]);
  for (int k = 0; k < 3; ++k) clamped += ClampDof(skel, ankle_dof + k, &ankle[k]);
  clamped += kv != knee;
  dofs->segment<3>(hip_dof) = hip;
  (*dofs)[knee_dof] = kv;
  dofs->segment<3>(ankle_dof) = ankle;

  const Eigen::Quaterniond R_thigh = R_WPf * humanoid::HingeTripleRotation(hip[0], hip[1], hip[2]);
  const Eigen::Quaterniond R_shin =
      R_thigh * Eigen::Quaterniond(Eigen::AngleAxisd(kv, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d p_knee = p_hip + R_thigh * skel.offset[shin];
  const Eigen::Vector3d p_ankle = p_knee + R_shin * skel.offset[foot];
  LimbIkResult result;
  result.position_error = (p_ankle - p_W_ankle).norm();
  result.clamped = clamped > 0;
  if (clamped > 0 && t.norm() < (l1 + l2) * (1 - 1e-6)) {
    const Eigen::Quaterniond R_foot = R_W_foot.normalized();
    RefineLimb(skel, root_pos, root_rot, foot, hip_dof, 7, p_W_ankle, &R_foot, dofs);
    // RefineLimb's error includes the foot orientation; report the ankle position miss alone.
    SkeletonPose sp;
    SkeletonForwardKinematics(skel, root_pos, root_rot, *dofs, &sp);
    result.position_error = (sp.pos[foot] - p_W_ankle).norm();
  }
  return result;
}

LimbIkResult SolveArmIk(const HumanoidSkeleton& skel, bool left, const Eigen::Vector3d& p_W_torso,
                        const Eigen::Quaterniond& R_W_torso, const Eigen::Vector3d& p_W_hand,
                        const Eigen::Vector3d& elbow_dir_W, DofVector* dofs) {
  const int upper = left ? humanoid::kLeftUpperArm : humanoid::kRightUpperArm;
  const int lower = left ? humanoid::kLeftLowerArm : humanoid::kRightLowerArm;
  const int hand = left ? humanoid::kLeftHand : humanoid::kRightHand;
  const int sh_dof = humanoid::Joints()[skel.joint[upper]].dof_offset;
  const int el_dof = humanoid::Joints()[skel.joint[lower]].dof_offset;
  const double l1 = skel.offset[lower].norm(), l2 = skel.offset[hand].norm();

  const Eigen::Quaterniond R_WPf = R_W_torso.normalized() * skel.rest[upper];
  const Eigen::Vector3d p_sh = p_W_torso + R_W_torso * skel.offset[upper];
  const Eigen::Vector3d t = R_WPf.conjugate() * (p_W_hand - p_sh);
  const double d = std::clamp(t.norm(), std::abs(l1 - l2) + 1e-6, (l1 + l2) * (1 - 1e-9));
  const double bend = std::acos(std::clamp((d * d - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1.0, 1.0));
  const double elbow = -bend;  // the forearm folds forward (negative y rotation)
  const Eigen::Vector3d u(-l2 * std::sin(elbow), 0, -l1 - l2 * std::cos(elbow));
  const Eigen::Vector3d a = u.normalized();
  // The elbow tip points along the upper arm's −x when the forearm folds forward.
  const Eigen::Vector3d b = Perpendicular(-Eigen::Vector3d::UnitX(), a, Eigen::Vector3d::UnitY());
  const Eigen::Vector3d a2 = t.norm() > 1e-9 ? t.normalized() : Eigen::Vector3d(0, 0, -1);
  const Eigen::Vector3d b2 =
      Perpendicular(R_WPf.conjugate() * elbow_dir_W, a2, -Eigen::Vector3d::UnitX());
  const Eigen::Vector3d prev = dofs->segment<3>(sh_dof);
  Eigen::Vector3d sh;
  double best = 1e18;
  for (double phi : SwivelCandidates()) {
    const Eigen::Quaterniond r_sh(AlignFrames(a, b, a2, Eigen::AngleAxisd(phi, a2) * b2));
    const Eigen::Vector3d s = DecomposeHingeTriple(r_sh, skel.lower.segment<3>(sh_dof),
                                                   skel.upper.segment<3>(sh_dof), &prev);
    const double score = Excess(skel, sh_dof, s) + 1e-3 * std::abs(phi);
    if (score < best) best = score, sh = s;
    if (score < 1e-9) break;
  }
  double ev = elbow;
  int clamped = 0;
  for (int k = 0; k < 3; ++k) clamped += ClampDof(skel, sh_dof + k, &sh[k]);
  clamped += ClampDof(skel, el_dof, &ev);
  dofs->segment<3>(sh_dof) = sh;
  (*dofs)[el_dof] = ev;

  const Eigen::Quaterniond R_up = R_WPf * humanoid::HingeTripleRotation(sh[0], sh[1], sh[2]);
  const Eigen::Quaterniond R_low =
      R_up * Eigen::Quaterniond(Eigen::AngleAxisd(ev, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d p_hand = p_sh + R_up * skel.offset[lower] + R_low * skel.offset[hand];
  LimbIkResult result;
  result.position_error = (p_hand - p_W_hand).norm();
  result.clamped = clamped > 0;
  if (clamped > 0 && result.position_error > 1e-4) {
    // Refine with a pelvis placed so that the torso lands at (p_W_torso, R_W_torso).
    const DofVector& d = *dofs;
    const Eigen::Quaterniond R_t0 = humanoid::HingeTripleRotation(d[0], d[1], d[2]);
    const Eigen::Quaterniond R_root = R_W_torso * (skel.rest[humanoid::kTorso] * R_t0).conjugate();
    const Eigen::Vector3d p_root = p_W_torso - R_root * skel.offset[humanoid::kTorso];
    // Position-only refinement: its residual is exactly the hand miss.
    result.position_error =
        RefineLimb(skel, p_root, R_root, hand, sh_dof, 4, p_W_hand, nullptr, dofs);
  }
  return result;
}

}  // namespace sims::motion
