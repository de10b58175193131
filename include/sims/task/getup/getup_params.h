// Get-up's own settings (part of task::SkillConfig, bound flat like walk_params.h).
#pragma once

#include <string>
#include <vector>

#include "sims/core/config.h"

namespace sims::task {

/// Get-up options (see getup.h).
struct GetUpParams {
  /// Precomputed fall states (ASE: random root orientation and random actions, then the fall);
  /// generated once per process for each count, deterministically.
  int fall_states = 1000;
  /// Falls do not terminate during this many control steps after a fall-state start (ASE 60).
  int fall_grace_steps = 60;
  /// Share of reference starts taken from floor get-up clips (lying on the floor) when the
  /// library has any; the rest start seated or lying on the env's furniture.
  double floor_clip_share = 0.3;
  /// Standing: the head at least this high (m; standing head origin ≈ 1.35 m) ...
  double standing_head_height = 1.2;
  /// ... and the pelvis at least this high (m; standing ≈ 0.89 m).
  double standing_pelvis_height = 0.8;
  /// A bed may be up to this much higher than a bed get-up clip's bed (m) for a bed start: the
  /// first quarter of such a clip lies on the mattress, so the clip is lifted with it. Lower beds
  /// keep the 5 cm of every furniture clip (kMaxClipHeightMismatch).
  double bed_raise = 0.15;
  /// Reference starts draw their clip time from the first this fraction of a get-up clip. The
  /// first quarter is still seated or lying (what evaluation uses, GetUpSkillInfo's
  /// configure_eval); training may reach further into the rise, so the policy also practises
  /// finishing a rise from leaning, half-risen states (reference state init, DeepMimic). Lifted
  /// bed starts keep the first quarter: later in such a clip the character stands beside the
  /// bed, above the floor.
  double reference_max_fraction = 0.25;
  /// Backplay, a reverse curriculum over the reference start time (Salimans & Chen 2018,
  /// learning from a demonstration's end backwards): when > 0, reference starts draw their clip
  /// time from [(1 − b)·e, e] instead, e this fraction of the clip (nearly risen) and b the
  /// env's backplay level in [0, 1], which starts at 0 and moves with the env's reference
  /// episodes (backplay_step); floor clips keep a level of their own, since rising from the
  /// floor is learnt far later than rising from a seat. At b = 1 the window runs from seated or
  /// lying to e. Lifted bed starts use the same window: a risen state stands on the floor beside
  /// the bed, the bed's lift fading out as the pelvis rises (FurnitureShare). 0 = off (evaluation
  /// turns it off).
  double backplay_end = 0;
  /// Backplay level change after a reference-start episode: + this when it succeeded, − half
  /// of it when it did not, so the level settles where a third of the starts succeed (as the
  /// object skills' spawn curriculum).
  double backplay_step = 0.05;
  /// k of the rise phase's stand-point term S = exp(−k·‖s − x_pelvis‖²) when s is the object's
  /// free floor point (a start lying on a bed or sofa; seated starts with the feet down use the
  /// feet, floor starts where they lie, both with k = 2). Held-out bed get-ups that stood without
  /// counting stood ~0.3 m short of it with a shin against the frame, where k = 2 still pays
  /// 84 % of the term.
  double furniture_stand_sharpness = 2.0;

  /// Lists the fields for JSON binding (keys as in the skill config).
  template <class A>
  void Serialize(A* a) {
    a->Visit(MakeNameValue("getup_fall_states", &fall_states));
    a->Visit(MakeNameValue("getup_fall_grace_steps", &fall_grace_steps));
    a->Visit(MakeNameValue("getup_floor_clip_share", &floor_clip_share));
    a->Visit(MakeNameValue("getup_standing_head_height", &standing_head_height));
    a->Visit(MakeNameValue("getup_standing_pelvis_height", &standing_pelvis_height));
    a->Visit(MakeNameValue("getup_bed_raise", &bed_raise));
    a->Visit(MakeNameValue("getup_reference_max_fraction", &reference_max_fraction));
    a->Visit(MakeNameValue("getup_backplay_end", &backplay_end));
    a->Visit(MakeNameValue("getup_backplay_step", &backplay_step));
    a->Visit(MakeNameValue("getup_furniture_stand_sharpness", &furniture_stand_sharpness));
  }
  /// Checks ranges.
  void Validate() const;
};

}  // namespace sims::task
