// The synthetic motion catalogue as data (configs/motion/synthetic_catalog.json): which clips
// exist, their labels and captions and the numbers that set them apart. The shapes they share
// (key timing of a sit-down or a reach, how a seat is placed, the named poses) stay in the
// generator code; a recipe picks them by name or parameter.
//
// Sections are generated in a fixed order (walk, idle, seat, sit_idle, bed, lie_idle, reach,
// floor_getup) from one random stream, so reordering recipes changes later clips' variants.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/motion/synthetic.h"

namespace sims::motion {

/// Labels of one generated clip (variants add "_v<i>" to the name).
struct SyntheticLabels {
  std::string name;                    ///< Clip name (file stem).
  std::string emotion = "neutral";     ///< Emotion label.
  std::string style;                   ///< Style label.
  std::vector<std::string> captions;   ///< Text descriptions (at least one).
  std::vector<std::string> furniture;  ///< Objects the clip fits (empty = the section's).

  /// Lists the label fields (called by the recipes' Serialize).
  template <class A>
  void SerializeLabels(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(emotion));
    a->Visit(SIMS_NVP(style));
    a->Visit(SIMS_NVP(captions));
    a->Visit(SIMS_NVP(furniture));
  }
  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    SerializeLabels(a);
  }
  /// Checks that the name, emotion and captions are given.
  void ValidateLabels() const;
  /// Same as ValidateLabels (run by the loader).
  void Validate() const { ValidateLabels(); }
};

/// A closed range [lo, hi] that variants draw from.
using SyntheticRange = std::array<double, 2>;

/// Turn on the spot by `degrees` (+ = left) over `turn_time` s, then walk off and stop.
struct TurnInPlace {
  double degrees = 90;     ///< Signed turn angle.
  double turn_time = 1.6;  ///< Seconds of turning.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(degrees));
    a->Visit(SIMS_NVP(turn_time));
  }
  /// Checks ranges.
  void Validate() const;
};

/// One walk recipe: labels, speed/turn profile and gait.
struct WalkRecipe : SyntheticLabels {
  double duration = 8.0;                     ///< Seconds (ignored with turn_in_place).
  std::vector<WalkKey> keys;                 ///< Speed/turn profile (unless turn_in_place).
  std::optional<TurnInPlace> turn_in_place;  ///< Keys generated for a turn on the spot.
  WalkStyle gait;                            ///< Gait style (absent fields keep defaults).
  uint64_t seed = 0;                         ///< Irregularity seed (drunk styles).
  bool drift = true;                         ///< Later variants add a slight constant turn.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    SerializeLabels(a);
    a->Visit(SIMS_NVP(duration));
    a->Visit(SIMS_NVP(keys));
    a->Visit(SIMS_NVP(turn_in_place));
    a->Visit(SIMS_NVP(gait));
    a->Visit(SIMS_NVP(seed));
    a->Visit(SIMS_NVP(drift));
  }
  /// Checks labels, keys and duration.
  void Validate() const;
};

/// Walk clips and how their variants vary.
struct WalkSection {
  std::vector<std::string> furniture = {"floor"};  ///< Default furniture labels.
  SyntheticRange speed_scale = {0.88, 1.12};       ///< Variant speed factor.
  SyntheticRange turn_scale = {0.85, 1.15};        ///< Variant turn-rate factor.
  SyntheticRange drift = {-0.15, 0.15};            ///< Variant added turn rate (rad/s).
  std::vector<WalkRecipe> recipes;                 ///< Walk recipes.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(speed_scale));
    a->Visit(SIMS_NVP(turn_scale));
    a->Visit(SIMS_NVP(drift));
    a->Visit(SIMS_NVP(recipes));
  }
  /// Checks the ranges.
  void Validate() const;
};

/// Procedural motion on top of a held pose (angles in degrees).
struct SyntheticNoise {
  double breathing = 1.0;   ///< Abdomen pitch amplitude scale.
  double look_deg = 0.0;    ///< Head yaw amplitude.
  double sway = 0.0;        ///< Pelvis lateral sway (m).
  double fidget_deg = 0.0;  ///< Arm/shoulder jitter amplitude.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(breathing));
    a->Visit(SIMS_NVP(look_deg));
    a->Visit(SIMS_NVP(sway));
    a->Visit(SIMS_NVP(fidget_deg));
  }
  /// Checks that amplitudes are non-negative.
  void Validate() const;
};

/// Changes to a base pose (standing, seated or supine), applied in field order; `pose` names
/// a generator pose applied last: hands_behind_back, hands_mid_thigh, hands_on_knees,
/// legs_crossed, on_side, knees_up, or one of the whole-body floor poses (on the floor
/// whatever the furniture, resting on it): floor_supine, floor_prone, hands_and_knees,
/// kneeling, one_knee (or empty).
struct PoseEdit {
  std::array<double, 3> pelvis_offset = {0, 0, 0};  ///< Added to the pelvis position (m).
  std::optional<double> pitch_deg;                  ///< Pelvis pitch (replaces the base).
  std::map<std::string, double> dofs_deg;           ///< Joint angles by DoF name (replace).
  std::string pose;                                 ///< Named generator pose.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(pelvis_offset));
    a->Visit(SIMS_NVP(pitch_deg));
    a->Visit(SIMS_NVP(dofs_deg));
    a->Visit(SIMS_NVP(pose));
  }
  /// Checks DoF and pose names.
  void Validate() const;
};

/// A held pose with idle noise (standing, sitting or lying idles).
struct IdleRecipe : SyntheticLabels {
  PoseEdit key;          ///< Changes to the section's base pose.
  SyntheticNoise noise;  ///< Idle noise.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    SerializeLabels(a);
    a->Visit(SIMS_NVP(key));
    a->Visit(SIMS_NVP(noise));
  }
  /// Checks labels.
  void Validate() const { ValidateLabels(); }
};

/// Standing idles.
struct IdleSection {
  std::vector<std::string> furniture = {"floor"};  ///< Default furniture labels.
  double duration = 6.0;                           ///< Seconds.
  double foot_width = 0.1;                         ///< Feet apart (m) in the first variant.
  double foot_width_step = 0.02;                   ///< Added per later variant.
  std::vector<IdleRecipe> recipes;                 ///< Idle recipes.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(duration));
    a->Visit(SIMS_NVP(foot_width));
    a->Visit(SIMS_NVP(foot_width_step));
    a->Visit(SIMS_NVP(recipes));
  }
  /// Checks ranges.
  void Validate() const;
};

/// A sit-down (or, played backwards, a get-up) onto a seat.
struct SitMotion : SyntheticLabels {
  double lean = 1.0;      ///< Forward trunk lean scale.
  double sit_time = 2.2;  ///< Seconds from standing to seated.
  double hold = 1.5;      ///< Seconds held seated.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    SerializeLabels(a);
    a->Visit(SIMS_NVP(lean));
    a->Visit(SIMS_NVP(sit_time));
    a->Visit(SIMS_NVP(hold));
  }
  /// Checks labels and times.
  void Validate() const;
};

/// A seat box; later variants change the height by a draw from `height_jitter`.
struct SeatSpec {
  double height = 0.44;                          ///< Seat height (m).
  double depth = 0.45;                           ///< Extent along x (m).
  double width = 0.5;                            ///< Extent along y (m).
  SyntheticRange height_jitter = {-0.03, 0.02};  ///< Added to the height in later variants.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(height));
    a->Visit(SIMS_NVP(depth));
    a->Visit(SIMS_NVP(width));
    a->Visit(SIMS_NVP(height_jitter));
  }
  /// Checks sizes.
  void Validate() const;
};

/// One seat with its sit-down and get-up clips.
struct SeatRecipe {
  SeatSpec seat;    ///< The seat.
  SitMotion sit;    ///< Sit-down clip (skill sit).
  SitMotion getup;  ///< Get-up clip (skill getup: a sit-down played backwards).
  /// Further seat heights (m) with one sit-down and one get-up clip each (names end in _h<cm>),
  /// so that reference starts find a clip of the seat's own kind near any seat's height.
  std::vector<double> extra_heights;

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(seat));
    a->Visit(SIMS_NVP(sit));
    a->Visit(SIMS_NVP(getup));
    a->Visit(SIMS_NVP(extra_heights));
  }
  /// Checks the extra heights.
  void Validate() const;
};

/// Seated idles on one seat.
struct SitIdleSection {
  std::vector<std::string> furniture;  ///< Default furniture labels.
  double duration = 6.0;               ///< Seconds.
  SeatSpec seat;                       ///< The seat.
  std::vector<IdleRecipe> recipes;     ///< Seated idle recipes.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(duration));
    a->Visit(SIMS_NVP(seat));
    a->Visit(SIMS_NVP(recipes));
  }
  /// Checks ranges.
  void Validate() const;
};

/// Lying down on a bed and getting up from it.
struct BedSection {
  std::vector<std::string> furniture = {"bed"};  ///< Default furniture labels.
  double height = 0.48;                          ///< Bed height (m) in the first variant.
  SyntheticRange variant_height = {0.42, 0.52};  ///< Bed height range of later variants.
  /// Further bed heights (m) with one lie-down and one get-up clip each (names end in _h<cm>),
  /// so that reference starts find a clip near any bed's height, held-out beds included.
  std::vector<double> extra_heights;
  double lie_hold = 1.5;     ///< Seconds held lying after lying down.
  SyntheticLabels lie_down;  ///< Lie-down clip (skill lie).
  SyntheticLabels getup;     ///< Get-up clip (skill getup).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(height));
    a->Visit(SIMS_NVP(variant_height));
    a->Visit(SIMS_NVP(extra_heights));
    a->Visit(SIMS_NVP(lie_hold));
    a->Visit(SIMS_NVP(lie_down));
    a->Visit(SIMS_NVP(getup));
  }
  /// Checks ranges and labels.
  void Validate() const;
};

/// Lying down on a sofa: the bed's lie-down (sit on the front edge, lean back, swing the legs up)
/// on a seat whose long axis is y, the pelvis over the seat's middle and the head toward an arm.
/// Stories lie on sofas, and without such clips the lie skill's sofa episodes had no reference
/// starts and no demonstrations of it.
struct SofaLieSection {
  std::vector<std::string> furniture = {"sofa"};  ///< Furniture labels.
  /// Seat heights (m), one clip each (names end in _h<cm>); reference starts take a clip within
  /// 0.05 m of a sofa's seat. Below 0.42 m the lie-down's legs cross the trunk by more than
  /// the 3 cm the clip checks allow (0.050 m at 0.36 m).
  std::vector<double> heights = {0.42, 0.48};
  double depth = 0.7;   ///< Seat depth from the front edge to the back (m).
  double width = 1.68;  ///< Seat width between the arms (m).
  /// How far the pelvis lies from the seat's middle toward the arm the head rests by (m; the
  /// lie skill's sofa target: 0.13 on a 1.68 m seat).
  double pelvis_offset = 0.13;
  double lie_hold = 1.5;     ///< Seconds held lying after lying down.
  SyntheticLabels lie_down;  ///< Clip labels (skill lie); an empty name writes no clips.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(heights));
    a->Visit(SIMS_NVP(depth));
    a->Visit(SIMS_NVP(width));
    a->Visit(SIMS_NVP(pelvis_offset));
    a->Visit(SIMS_NVP(lie_hold));
    a->Visit(SIMS_NVP(lie_down));
  }
  /// Checks ranges and labels.
  void Validate() const;
};

/// Lying idles on the bed of BedSection.
struct LieIdleSection {
  std::vector<std::string> furniture = {"bed"};  ///< Default furniture labels.
  double duration = 6.0;                         ///< Seconds.
  std::vector<IdleRecipe> recipes;               ///< Lying idle recipes.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(duration));
    a->Visit(SIMS_NVP(recipes));
  }
  /// Checks ranges.
  void Validate() const;
};

/// One reach: stand, reach one hand to a target, hold, return. Lateral values (target y,
/// hint y) are mirrored to the hand's side.
struct ReachRecipe : SyntheticLabels {
  std::string side = "right";                        ///< Hand: right or left.
  std::array<double, 3> target = {0.5, 0.25, 1.05};  ///< Hand target: x, lateral, z (m).
  std::optional<double> pelvis_x;                    ///< Pelvis x while reaching.
  std::optional<double> pelvis_drop;          ///< Pelvis below standing height while reaching.
  std::optional<double> pitch_deg;            ///< Pelvis pitch while reaching.
  std::map<std::string, double> dofs_deg;     ///< Joint angles while reaching.
  std::optional<std::array<double, 3>> hint;  ///< Elbow direction while reaching.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    SerializeLabels(a);
    a->Visit(SIMS_NVP(side));
    a->Visit(SIMS_NVP(target));
    a->Visit(SIMS_NVP(pelvis_x));
    a->Visit(SIMS_NVP(pelvis_drop));
    a->Visit(SIMS_NVP(pitch_deg));
    a->Visit(SIMS_NVP(dofs_deg));
    a->Visit(SIMS_NVP(hint));
  }
  /// Checks labels, side and DoF names.
  void Validate() const;
};

/// Reaches.
struct ReachSection {
  double target_jitter = 0.05;                      ///< Per-axis target jitter of later variants.
  std::array<double, 3> rest_hint = {-0.2, 1, -1};  ///< Elbow direction at rest (lateral mirrored).
  std::map<std::string, double> side_dofs_deg;  ///< Joint angles while reaching, for a left hand
                                                ///< (negated for the right).
  std::vector<ReachRecipe> recipes;             ///< Reach recipes.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(target_jitter));
    a->Visit(SIMS_NVP(rest_hint));
    a->Visit(SIMS_NVP(side_dofs_deg));
    a->Visit(SIMS_NVP(recipes));
  }
  /// Checks ranges and DoF names.
  void Validate() const;
};

/// Getting up from lying on the floor: supine (roll onto the right side, then onto hands and
/// knees) or prone (push up onto hands and knees), then kneel up, step the left foot forward
/// onto one knee and stand up, ending standing at the origin facing +x. The key poses are
/// the generator's floor poses; a recipe sets the start and the timing.
struct FloorGetUpRecipe : SyntheticLabels {
  std::string start = "supine";  ///< Lying on the back ("supine") or face down ("prone").
  double tempo = 1.0;            ///< Time scale of the movement (> 1 slower).
  double pause = 0.0;            ///< Extra seconds resting on hands and knees.
  double hold = 0.5;             ///< Seconds standing still at the end.
  double slump_deg = 0.0;        ///< Extra trunk and head droop while kneeling and rising.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    SerializeLabels(a);
    a->Visit(SIMS_NVP(start));
    a->Visit(SIMS_NVP(tempo));
    a->Visit(SIMS_NVP(pause));
    a->Visit(SIMS_NVP(hold));
    a->Visit(SIMS_NVP(slump_deg));
  }
  /// Checks labels, start and times.
  void Validate() const;
};

/// Floor get-ups (skill getup). They carry no furniture_* parameters (nothing to place) and
/// the parameter floor = 1.
struct FloorGetUpSection {
  std::vector<std::string> furniture = {"floor"};  ///< Default furniture labels.
  SyntheticRange tempo_scale = {0.9, 1.12};        ///< Variant tempo factor.
  std::vector<FloorGetUpRecipe> recipes;           ///< Floor get-up recipes.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(tempo_scale));
    a->Visit(SIMS_NVP(recipes));
  }
  /// Checks the range.
  void Validate() const;
};

/// The whole catalogue.
struct SyntheticCatalog {
  WalkSection walk;               ///< Skill walk.
  IdleSection idle;               ///< Skill idle.
  std::vector<SeatRecipe> seats;  ///< Skills sit and getup.
  SitIdleSection sit_idle;        ///< Skill sit.
  BedSection bed;                 ///< Skills lie and getup.
  LieIdleSection lie_idle;        ///< Skill lie.
  ReachSection reach;             ///< Skill reach.
  FloorGetUpSection floor_getup;  ///< Skill getup (from the floor).
  SofaLieSection sofa_lie;        ///< Skill lie (on sofas).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(walk));
    a->Visit(SIMS_NVP(idle));
    a->Visit(SIMS_NVP(seats));
    a->Visit(SIMS_NVP(sit_idle));
    a->Visit(SIMS_NVP(bed));
    a->Visit(SIMS_NVP(lie_idle));
    a->Visit(SIMS_NVP(reach));
    a->Visit(SIMS_NVP(floor_getup));
    a->Visit(SIMS_NVP(sofa_lie));
  }
  /// Checks that clip names are unique.
  void Validate() const;
};

/// The shipped catalogue: ConfigPath("motion/synthetic_catalog.json").
std::filesystem::path DefaultSyntheticCatalogPath();

/// Loads and validates a catalogue; errors name the file, the field and the expectation.
SyntheticCatalog LoadSyntheticCatalog(const std::filesystem::path& path);

/// Generates the clips of `catalog` (deterministic for options.seed).
std::vector<MotionClip> GenerateSyntheticClips(const SyntheticCatalog& catalog,
                                               const SyntheticOptions& options);

}  // namespace sims::motion
