// Procedural, clearly labelled synthetic motion clips (meta.synthetic = true, source
// "sims-synthetic"): the default training data until a user brings SAMP / 100STYLE / CIRCLE.
//
// Walks come from a footstep-driven gait: a root path (speed and turn-rate keys), footholds
// placed along it at mid-stance, feet planted while in support (heel strike and toe-off roll
// about the sole edges), swing arcs between footholds, a pelvis that bobs and sways as the
// legs allow, arms swinging opposite to the legs; leg IK puts the ankles on the feet. Sit,
// lie, reach and get-up clips are keyframed whole-body poses with IK for planted feet and
// reaching hands, placed relative to a seat or bed whose dimensions go into the metadata;
// get-ups from the floor (lying on the back or face down) rest on the floor in every frame.
// Every clip is lifted out of any floor/furniture penetration (MuJoCo collision on the real
// geometry) and stays within the joint limits.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/motion/motion_clip.h"
#include "sims/motion/motion_library.h"

namespace sims::motion {

/// Walking style parameters (angles in degrees, lengths in metres).
struct WalkStyle {
  double cadence_scale = 1.0;      ///< Step frequency multiplier.
  double stride_scale = 1.0;       ///< Step length multiplier at the same speed (lower cadence).
  double step_width = 0.095;       ///< Lateral ankle offset from the path.
  double toe_out_deg = 5;          ///< Foot yaw outward.
  double lift = 0.07;              ///< Swing clearance at full step length.
  double heel_strike_deg = 15;     ///< Toe-up pitch at heel strike.
  double toe_off_deg = 30;         ///< Toe-down pitch at toe-off.
  bool tiptoe = false;             ///< Heels stay up (stance on the toes).
  double tiptoe_deg = 28;          ///< Foot pitch when on tiptoe.
  double crouch = 0.0;             ///< Pelvis lowered below the straight-leg height.
  double bounce = 0.0;             ///< Extra vertical bob.
  double sway = 0.02;              ///< Lateral pelvis sway toward the stance foot.
  double pelvis_rot_deg = 4;       ///< Pelvis yaw oscillation.
  double pelvis_roll_deg = 3;      ///< Pelvis list toward the swing side.
  double lean_deg = 2;             ///< Forward trunk lean.
  double head_pitch_deg = 0;       ///< Head pitch (positive looks down).
  double arm_swing_deg = 22;       ///< Shoulder swing amplitude at 1 m/s.
  double arm_abduct_deg = 7;       ///< Shoulder abduction.
  double elbow_deg = 15;           ///< Elbow flexion.
  double elbow_swing_deg = 12;     ///< Extra elbow flexion as the arm swings forward.
  bool hands_behind_back = false;  ///< Arms folded behind the back.
  double drunk = 0.0;              ///< 0..1 irregular sway, wobble and step width.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(cadence_scale));
    a->Visit(SIMS_NVP(stride_scale));
    a->Visit(SIMS_NVP(step_width));
    a->Visit(SIMS_NVP(toe_out_deg));
    a->Visit(SIMS_NVP(lift));
    a->Visit(SIMS_NVP(heel_strike_deg));
    a->Visit(SIMS_NVP(toe_off_deg));
    a->Visit(SIMS_NVP(tiptoe));
    a->Visit(SIMS_NVP(tiptoe_deg));
    a->Visit(SIMS_NVP(crouch));
    a->Visit(SIMS_NVP(bounce));
    a->Visit(SIMS_NVP(sway));
    a->Visit(SIMS_NVP(pelvis_rot_deg));
    a->Visit(SIMS_NVP(pelvis_roll_deg));
    a->Visit(SIMS_NVP(lean_deg));
    a->Visit(SIMS_NVP(head_pitch_deg));
    a->Visit(SIMS_NVP(arm_swing_deg));
    a->Visit(SIMS_NVP(arm_abduct_deg));
    a->Visit(SIMS_NVP(elbow_deg));
    a->Visit(SIMS_NVP(elbow_swing_deg));
    a->Visit(SIMS_NVP(hands_behind_back));
    a->Visit(SIMS_NVP(drunk));
  }
};

/// Root speed (m/s) and turn rate (rad/s, + = left) at time t; smooth between keys.
struct WalkKey {
  double t = 0;         ///< Time (s).
  double speed = 0;     ///< Forward speed.
  double yaw_rate = 0;  ///< Turn rate.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(t));
    a->Visit(SIMS_NVP(speed));
    a->Visit(SIMS_NVP(yaw_rate));
  }
};

/// One walk clip.
struct WalkSpec {
  double duration = 8.0;      ///< Seconds.
  std::vector<WalkKey> keys;  ///< Speed/turn profile (at least one key).
  WalkStyle style;            ///< Gait style.
  double phase = 0.0;         ///< Gait phase at t = 0 (cycles).
  uint64_t seed = 0;          ///< Irregularity seed (drunk styles).
};

/// What a seat or bed looks like, relative to the character's start (facing +x, feet at
/// the origin).
struct FurnitureSpec {
  double height = 0.45;    ///< Top surface height (m).
  double depth = 0.45;     ///< Extent along x (m).
  double width = 0.5;      ///< Extent along y (m).
  double front_x = -0.12;  ///< x of the edge nearest the character (furniture at x < front_x).
  double center_y = 0.0;   ///< y of the centre.
};

/// Generates a walk; `meta` labels are copied (synthetic flags and params are added).
MotionClip GenerateWalk(const WalkSpec& spec, const MotionMeta& meta, double fps = 30.0);

/// `lead` placed so that its last frame stands where `clip`'s first frame does (xy and
/// heading; heights unchanged), followed by `clip` whose first `blend_seconds` crossfade from
/// that last frame. `clip`'s frames keep their coordinates, so its metadata (furniture
/// parameters, targets) still holds; the result takes `clip`'s metadata.
MotionClip ComposeAfter(const MotionClip& lead, const MotionClip& clip, double blend_seconds);

/// Generator settings (apps/make_synthetic_motions).
struct SyntheticOptions {
  uint64_t seed = 1;                ///< Seed of every random choice.
  double fps = 30.0;                ///< Output frame rate.
  int variants = 2;                 ///< Random variants per recipe (speeds, heights, targets).
  std::vector<std::string> skills;  ///< Skills to generate (empty = all).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(seed));
    a->Visit(SIMS_NVP(fps));
    a->Visit(SIMS_NVP(variants));
    a->Visit(SIMS_NVP(skills));
  }
  /// Checks ranges.
  void Validate() const;
};

/// The clips of the shipped catalogue (configs/motion/synthetic_catalog.json, see
/// synthetic_catalog.h; deterministic for a seed): walks in several styles, speeds and turns,
/// starts/stops and turns in place; standing idles; sit down / sit idle; lie down / lie idle;
/// reaches; get-ups from seats, beds and the floor.
std::vector<MotionClip> GenerateSyntheticClips(const SyntheticOptions& options);

/// Quality figures of a clip (used by tests and the generator's self-check).
struct ClipQuality {
  double min_sole_height = 0;        ///< Lowest foot-box point over the clip (m).
  double max_floor_penetration = 0;  ///< Deepest humanoid–floor penetration (m).
  double max_limit_excess = 0;       ///< Largest joint-limit violation (rad).
  double max_stance_slide = 0;       ///< Fastest horizontal motion of a grounded sole corner (m/s).
  double max_self_penetration =
      0;                     ///< Deepest penetration between non-adjacent humanoid geoms (m).
  double max_floor_gap = 0;  ///< Highest the body's lowest point gets above the floor (m).
};

/// Measures a clip with the default humanoid (FK + MuJoCo collision against the floor).
ClipQuality MeasureClipQuality(const MotionClip& clip);

/// Writes clips as `<dir>/<name>.json/.bin` plus `<dir>/manifest.json` (weights: walks 2,
/// others 1). Returns the manifest path.
std::filesystem::path WriteMotionDataset(const std::vector<MotionClip>& clips,
                                         const std::filesystem::path& dir,
                                         const std::string& description);

}  // namespace sims::motion
