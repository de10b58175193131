// Retargeting BVH skeletons onto the humanoid by joint-name maps kept in configs/retarget/,
// and the reverse path (humanoid clip → BVH) for export.
//
// Each humanoid body takes the global rotation of its mapped BVH joint, converted to the
// humanoid's axes (z up, x forward, y left) and composed with a rest-pose correction that
// aligns the BVH rest pose with the humanoid's zero pose (automatic for limbs from bone
// directions, plus an optional configured rotation). Local joint rotations are then
// decomposed into the hinge angles (Rx·Ry·Rz for 3-DoF joints, projected onto y for elbows
// and knees), clamped to the limits (reported as warnings), the root follows the hip
// midpoint scaled by the leg-length ratio, the clip is resampled and lifted onto the floor.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/motion/bvh.h"
#include "sims/motion/motion_clip.h"

namespace sims::motion {

/// How one humanoid body is driven.
struct RetargetJoint {
  std::vector<std::string> bvh;  ///< Candidate BVH joint names; the first present is used.
  std::array<double, 3> rest_correction_deg = {
      0, 0,
      0};  ///< Extra XYZ rotation (degrees, humanoid axes) applied after the automatic alignment.
  bool auto_align = true;  ///< Align the humanoid bone with the BVH rest bone (limbs only).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(bvh));
    a->Visit(SIMS_NVP(rest_correction_deg));
    a->Visit(SIMS_NVP(auto_align));
  }
  /// Requires at least one name.
  void Validate() const;
};

/// A retarget map (configs/retarget/<dataset>.json).
struct RetargetConfig {
  std::string name;                ///< Map name ("cmu").
  std::string up_axis = "y";       ///< BVH up axis: x, y, z, -x, -y, -z.
  std::string forward_axis = "z";  ///< BVH axis the character faces in its rest pose.
  double scale = 0.0;        ///< Metres per BVH unit; 0 = humanoid leg length / BVH leg length.
  double target_fps = 30.0;  ///< Output frame rate (0 keeps the source rate).
  /// Ground fix from the foot soles: percentile (the ground_percentile-th lowest per-frame
  /// sole height → 0; robust to falls and proportion mismatches), clip_min (lowest sole over
  /// the clip → 0), per_frame (every frame's lowest sole → 0), none.
  std::string ground = "percentile";
  double ground_percentile = 1.0;               ///< Percentile for ground = percentile (0..100).
  double ground_offset = 0.0;                   ///< Height added after the ground fix (m).
  double clamp_warning_deg = 2.0;               ///< Report joints clamped by more than this.
  std::map<std::string, RetargetJoint> joints;  ///< Humanoid body name → BVH joint(s).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(up_axis));
    a->Visit(SIMS_NVP(forward_axis));
    a->Visit(SIMS_NVP(scale));
    a->Visit(SIMS_NVP(target_fps));
    a->Visit(SIMS_NVP(ground));
    a->Visit(SIMS_NVP(ground_percentile));
    a->Visit(SIMS_NVP(ground_offset));
    a->Visit(SIMS_NVP(clamp_warning_deg));
    a->Visit(SIMS_NVP(joints));
  }
  /// Checks axes, ground mode, body names and the required bodies (pelvis, thighs, shins, feet).
  void Validate() const;
};

/// Loads and validates a retarget map.
RetargetConfig LoadRetargetConfig(const std::filesystem::path& path);

/// Per-DoF clamp statistics.
struct ClampStat {
  int frames = 0;        ///< Frames clamped by more than the warning threshold.
  double max_deg = 0.0;  ///< Largest excess (degrees).
};

/// What happened during a retarget.
struct RetargetReport {
  double scale = 0;                          ///< Metres per BVH unit used.
  double source_fps = 0;                     ///< BVH frame rate.
  int source_frames = 0;                     ///< BVH frames.
  double ground_shift = 0;                   ///< Height added by the ground fix (m).
  std::map<std::string, ClampStat> clamped;  ///< DoF name → clamp statistics.
  std::vector<std::string> warnings;         ///< Human-readable warnings.
};

/// Retargets a BVH motion; `source` names the file in errors. Throws sims::Error when a
/// required mapped joint is missing from the BVH.
MotionClip RetargetBvh(const BvhMotion& bvh, const RetargetConfig& config,
                       const HumanoidSkeleton& skel, RetargetReport* report = nullptr,
                       const std::string& source = "BVH");

/// Options of the humanoid → BVH export.
struct HumanoidBvhOptions {
  bool y_up = true;      ///< Write Y-up (x left, z forward) as most tools expect; else Z-up.
  double scale = 100.0;  ///< BVH units per metre (100 = centimetres).
};

/// The humanoid as a BVH hierarchy (one joint per body, offsets from the model) carrying the
/// clip's motion; joint names are the humanoid body names.
BvhMotion HumanoidClipToBvh(const MotionClip& clip, const HumanoidSkeleton& skel,
                            const HumanoidBvhOptions& options = {});

/// Writes a clip as BVH (HumanoidClipToBvh + WriteBvh), using the default humanoid.
void WriteHumanoidBvh(const MotionClip& clip, const std::filesystem::path& path,
                      const HumanoidBvhOptions& options = {});

/// The retarget map that reads HumanoidClipToBvh output back (identity names and rests).
RetargetConfig HumanoidBvhRetargetConfig(const HumanoidBvhOptions& options = {});

}  // namespace sims::motion
