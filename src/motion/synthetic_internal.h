// Shared pieces of the synthetic clip generator (not part of the public API).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sims/humanoid/model_builder.h"
#include "sims/motion/motion_clip.h"
#include "sims/motion/synthetic.h"

namespace sims::motion::synth {

/// DoF indices (humanoid::DofNames() order).
enum Dof : int {
  kAbdX = 0,
  kAbdY,
  kAbdZ,
  kNeckX,
  kNeckY,
  kNeckZ,
  kRShX,
  kRShY,
  kRShZ,
  kRElbow,
  kLShX,
  kLShY,
  kLShZ,
  kLElbow,
  kRHipX,
  kRHipY,
  kRHipZ,
  kRKnee,
  kRAnkX,
  kRAnkY,
  kRAnkZ,
  kLHipX,
  kLHipY,
  kLHipZ,
  kLKnee,
  kLAnkX,
  kLAnkY,
  kLAnkZ,
};

/// Degrees to radians.
inline double Deg(double d) { return d * M_PI / 180.0; }
/// 3x² − 2x³ on [0, 1] (clamped).
inline double SmoothStep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}
/// Minimum-jerk profile 10x³ − 15x⁴ + 6x⁵ on [0, 1] (clamped).
inline double MinJerk(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * x * (10 + x * (-15 + 6 * x));
}
/// Pelvis orientation from yaw (about z), then pitch (about the new y), then roll (new x).
inline Eigen::Quaterniond YawPitchRoll(double yaw, double pitch, double roll) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

/// Sole pivot points of a foot in its own frame (heel-bottom and toe-bottom edge centres).
struct FootGeometry {
  Eigen::Vector3d heel, toe;   ///< Pivot points.
  double ankle_height = 0.05;  ///< Ankle above the sole when flat.
};
/// Foot geometry of the skeleton (right and left feet are identical in the asset).
FootGeometry FootOf(const HumanoidSkeleton& skel);

/// Ankle position of a foot resting on its heel (pitch < 0) or toe (pitch > 0) edge, or flat,
/// given the flat ankle position `flat` (ankle xy, z = ankle height) and yaw.
Eigen::Vector3d PivotAnkle(const FootGeometry& g, const Eigen::Vector3d& flat, double yaw,
                           double pitch);
/// Foot orientation: yaw about z, then pitch about the foot's y (positive = toe down).
inline Eigen::Quaterniond FootRotation(double yaw, double pitch) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY());
}

/// Static boxes (seat, bed) the humanoid must stay above, as MuJoCo geometry.
humanoid::StaticGeometry FurnitureGeometry(const std::vector<FurnitureSpec>& boxes);

/// Deepest penetrations of a pose: humanoid vs world (floor, furniture) and humanoid vs itself.
struct Penetration {
  double world = 0;  ///< Humanoid–floor/furniture (m).
  double self = 0;   ///< Between humanoid geoms (m).
};
/// Measures a frame with `h`'s model (which includes the furniture) using scratch data `d`.
Penetration MeasurePenetration(const humanoid::Humanoid& h, mjData* d, const MotionFrame& f);

/// Height above the floor (z = 0) of the lowest point of the humanoid's geoms in a frame
/// (negative: below the floor), from `h`'s model with scratch data `d`. Geoms of the bodies
/// whose bit (1 << humanoid::Body) is set in `skip` are left out.
double LowestPoint(const humanoid::Humanoid& h, mjData* d, const MotionFrame& f, uint32_t skip = 0);

/// Labels of a synthetic clip.
MotionMeta SyntheticMeta(const std::string& name, const std::string& skill,
                         const std::string& emotion, const std::string& style,
                         std::vector<std::string> captions,
                         std::vector<std::string> furniture = {});

/// Keyframed whole-body motion: per key a pelvis pose, base joint angles and, per limb
/// (0 right arm, 1 left arm, 2 right leg, 3 left leg), an IK weight and target. Keys are
/// interpolated with cubic Hermite splines (Catmull–Rom tangents, zero at holds and ends),
/// then every frame is solved: limbs with weight w blend joint angles and IK (1 = IK).
struct LimbKey {
  double weight = 0;                                 ///< 0 joint angles, 1 IK.
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< Ankle or hand position (world).
  double yaw = 0, pitch = 0;                         ///< Foot orientation (legs).
  Eigen::Vector3d hint = Eigen::Vector3d::UnitX();   ///< Knee/elbow direction (world).
};
/// One key of a keyframed clip.
struct BodyKey {
  double t = 0;                                      ///< Time (s).
  bool hold = false;                                 ///< Zero velocity at this key.
  Eigen::Vector3d pelvis = Eigen::Vector3d::Zero();  ///< Pelvis position.
  double yaw = 0, pitch = 0, roll = 0;               ///< Pelvis orientation (rad).
  DofVector dofs = DofVector::Zero();                ///< Base joint angles.
  std::array<LimbKey, 4> limbs;                      ///< Limb targets.
  /// The pelvis turns from this key's orientation to the next key's along the shortest
  /// rotation (slerp, timed like the other channels) instead of through interpolated
  /// yaw/pitch/roll; for turns that are not about one axis (rolling over, lying to upright).
  bool slerp = false;
  /// Velocities at this key are limited so that no channel overshoots (Fritsch–Carlson):
  /// zero where a channel holds still on either side or turns back, so a hand or foot
  /// planted across keys stays put.
  bool monotone = false;
};
/// Additive procedural motion on top of the keys (breathing, looking around, weight shift).
struct IdleNoise {
  double breathing = 1.0;  ///< Abdomen pitch amplitude scale.
  double look = 0.0;       ///< Head yaw amplitude (rad).
  double sway = 0.0;       ///< Pelvis lateral sway amplitude (m).
  double fidget = 0.0;     ///< Arm/shoulder jitter amplitude (rad).
  uint64_t seed = 0;       ///< Phase seed.
};
/// Largest IK misses of a solve (limbs with full IK weight).
struct SolveStats {
  double leg_error = 0;  ///< Ankle miss (m).
  double arm_error = 0;  ///< Hand miss (m).
  double max_lift = 0;   ///< Largest root lift out of penetration (m).
};
/// Solves keys into frames at `fps` over [0, keys.back().t]. With `furniture` (may be
/// empty: floor only) the pelvis of each frame is raised until no humanoid geom penetrates
/// the floor or the boxes, and the limbs are re-solved (planted feet stay planted). With
/// `rest_on_floor` (floor only: `furniture` empty) the pelvis of each frame is also lowered
/// where the body floats, so that its lowest point touches the floor in every frame (clips
/// that lie, kneel or crawl on the floor).
std::vector<MotionFrame> SolveKeys(const std::vector<BodyKey>& keys, double fps,
                                   const IdleNoise& noise = {},
                                   const std::vector<FurnitureSpec>* furniture = nullptr,
                                   SolveStats* stats = nullptr, bool rest_on_floor = false);

/// Arms folded behind the back: hand IK to points behind the sacrum (pelvis frame), for the
/// pelvis pose and the spine angles already in `dofs`.
void HandsBehindBack(const Eigen::Vector3d& root_pos, const Eigen::Quaterniond& root_rot,
                     DofVector* dofs);
/// World targets and elbow hints of HandsBehindBack (right, left).
void HandsBehindBackTargets(const Eigen::Vector3d& root_pos, const Eigen::Quaterniond& root_rot,
                            std::array<Eigen::Vector3d, 2>* targets,
                            std::array<Eigen::Vector3d, 2>* hints);

/// Standing key: feet planted at (0, ±width) flat, arms relaxed, pelvis at standing height.
BodyKey StandingKey(double t, double foot_width = 0.1);

}  // namespace sims::motion::synth
