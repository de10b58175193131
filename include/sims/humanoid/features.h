// Observations shared by the environment and the motion library: the policy's AMP
// self-observation (223) and the discriminator's per-step AMP observation (125), both in the
// heading frame (yaw removed) so they are invariant to rotations of the world about z.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sims/humanoid/state.h"

namespace sims::humanoid {

inline constexpr int kSelfObsDim = 223;     ///< 1 + 14·3 + 15·6 + 15·3 + 15·3.
inline constexpr int kAmpObsStepDim = 125;  ///< 1 + 6 + 3 + 3 + 72 + 28 + 12.
inline constexpr int kDofObsDim = 72;       ///< 12 joints × tan-norm 6-d.

/// Observation options (ASE rootHeightObs / localRootObs).
struct ObsOptions {
  bool root_height = true;     ///< Include the root height (else zero).
  bool local_root_rot = true;  ///< Root rotation heading-local (InterScene) vs global (ASE AMP).
};

/// Heading angle: atan2 of the y and x components of R·(1,0,0).
double HeadingAngle(const Eigen::Quaterniond& q);

/// Rotation by −heading about +z.
Eigen::Quaterniond HeadingInverse(const Eigen::Quaterniond& q);

/// Tan-norm 6-d: [R·(1,0,0), R·(0,0,1)].
void TanNorm(const Eigen::Quaterniond& q, float* out6);

/// Rotation of a 3-DoF hinge triple (x, y, z hinges: Rx·Ry·Rz).
Eigen::Quaterniond HingeTripleRotation(double ax, double ay, double az);

/// Joint rotations as 12 × tan-norm (72 values); 1-DoF joints rotate about y.
void DofObservation(const Eigen::Matrix<double, kNumDofs, 1>& dof_pos, float* out72);

/// The 223-d self observation (ASE compute_humanoid_observations_max order).
void ComputeSelfObservation(const BodyStates& bodies, const ObsOptions& options, float* out);

/// The 125-d AMP observation of one step (ASE build_amp_observations order).
void ComputeAmpObservation(const HumanoidPose& pose, const BodyStates& bodies,
                           const ObsOptions& options, float* out);

}  // namespace sims::humanoid
