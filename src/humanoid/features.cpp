#include "sims/humanoid/features.h"

#include <cmath>

namespace sims::humanoid {

namespace {
inline void Put3(const Eigen::Vector3d& v, float* out) {
  out[0] = static_cast<float>(v.x());
  out[1] = static_cast<float>(v.y());
  out[2] = static_cast<float>(v.z());
}
}  // namespace

double HeadingAngle(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d x = q * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

Eigen::Quaterniond HeadingInverse(const Eigen::Quaterniond& q) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(-HeadingAngle(q), Eigen::Vector3d::UnitZ()));
}

void TanNorm(const Eigen::Quaterniond& q, float* out6) {
  const Eigen::Matrix3d r = q.toRotationMatrix();
  Put3(r.col(0), out6);
  Put3(r.col(2), out6 + 3);
}

Eigen::Quaterniond HingeTripleRotation(double ax, double ay, double az) {
  return Eigen::AngleAxisd(ax, Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(ay, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(az, Eigen::Vector3d::UnitZ());
}

void DofObservation(const Eigen::Matrix<double, kNumDofs, 1>& dof_pos, float* out72) {
  int k = 0;
  for (const JointSpec& js : Joints()) {
    const int o = js.dof_offset;
    const Eigen::Quaterniond q =
        js.dof_count == 3
            ? HingeTripleRotation(dof_pos[o], dof_pos[o + 1], dof_pos[o + 2])
            : Eigen::Quaterniond(Eigen::AngleAxisd(dof_pos[o], Eigen::Vector3d::UnitY()));
    TanNorm(q, out72 + 6 * k);
    ++k;
  }
}

void ComputeSelfObservation(const BodyStates& bodies, const ObsOptions& options, float* out) {
  const Eigen::Quaterniond root_rot = bodies.rot[kPelvis];
  const Eigen::Quaterniond h_inv = HeadingInverse(root_rot);
  const Eigen::Vector3d root_pos = bodies.pos[kPelvis];
  float* o = out;
  *o++ = options.root_height ? static_cast<float>(root_pos.z()) : 0.0f;
  for (int b = 1; b < kNumBodies; ++b, o += 3) Put3(h_inv * (bodies.pos[b] - root_pos), o);
  for (int b = 0; b < kNumBodies; ++b, o += 6) {
    if (b == kPelvis && !options.local_root_rot)
      TanNorm(root_rot, o);
    else
      TanNorm(h_inv * bodies.rot[b], o);
  }
  for (int b = 0; b < kNumBodies; ++b, o += 3) Put3(h_inv * bodies.lin_vel[b], o);
  for (int b = 0; b < kNumBodies; ++b, o += 3) Put3(h_inv * bodies.ang_vel[b], o);
}

void ComputeAmpObservation(const HumanoidPose& pose, const BodyStates& bodies,
                           const ObsOptions& options, float* out) {
  const Eigen::Quaterniond h_inv = HeadingInverse(pose.root_rot);
  float* o = out;
  *o++ = options.root_height ? static_cast<float>(pose.root_pos.z()) : 0.0f;
  TanNorm(options.local_root_rot ? h_inv * pose.root_rot : pose.root_rot, o);
  o += 6;
  Put3(h_inv * pose.root_lin_vel, o);
  o += 3;
  Put3(h_inv * pose.root_ang_vel, o);
  o += 3;
  DofObservation(pose.dof_pos, o);
  o += kDofObsDim;
  for (int i = 0; i < kNumDofs; ++i) *o++ = static_cast<float>(pose.dof_vel[i]);
  for (int k : KeyBodies()) {
    Put3(h_inv * (bodies.pos[k] - pose.root_pos), o);
    o += 3;
  }
}

}  // namespace sims::humanoid
