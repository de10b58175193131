// Settings of the skills that interact with furniture (object_skill.h: sit, lie, reach, get-up,
// unified), part of task::SkillConfig and bound flat like walk/walk_params.h.
#pragma once

#include <string>
#include <vector>

#include "sims/core/config.h"

namespace sims::task {

/// The training ground, spawn distances and the success/force thresholds of object skills.
struct ObjectParams {
  std::vector<std::string> object_categories;  ///< Procedural categories to train on.
  int num_objects = 16;                        ///< Objects in the training ground.
  bool held_out_objects = false;               ///< Held-out dimension ranges (evaluation).
  /// Training pieces scale each nominal dimension by a factor in [training_scale_min,
  /// training_scale_max] outside the held-out bands (scene::TrainingScale): sit 12175 succeeded
  /// in 64 of 100 standing starts on ±10 % training pieces but 43 on held-out ones.
  double training_scale_min = 0.9;
  double training_scale_max = 1.1;  ///< ...
  double spawn_min_distance = 1.0;  ///< Character spawn distance from the object (m).
  double spawn_max_distance = 4.0;  ///< ... (m).
  double spawn_arc_deg = 360;       ///< Default starts within ±arc/2 of the object's front (deg).
  /// Default starts widen from spawn_min_distance to spawn_max_distance as each env succeeds:
  /// its level rises by spawn_curriculum_step after a completed default-start episode and falls
  /// by half that after a failed one (evaluation turns it off: full range).
  bool spawn_curriculum = false;
  double spawn_curriculum_step = 0.1;  ///< Level change per episode (level in [0, 1]).
  /// With the curriculum on, this share of default starts is drawn over the full distance
  /// range whatever the level (and counts for the level like the others), so long approaches
  /// stay in practice: sit's levels stayed near 0 with standing-start success ~0.1, and its
  /// policy fell on 3–5 m walks in evaluation (33 % falls at 1–5 m, 5 % at 1–1.5 m).
  double spawn_full_range_share = 0;
  double contact_success_threshold = 0.2;  ///< Sit/reach 0.20 m, lie 0.30 m.
  /// Reference starts within this many seconds before the clip's contact (0 = anywhere before
  /// it): a short window starts most episodes mid-approach, where the contact is a few steps away.
  double reference_window = 0;
  double max_contact_force = 1e4;  ///< Net contact force (N) that ends an episode (0 = off).
  /// Share of r_near paid by the precise kernel exp(−100Σ) (NearReward): exp(−10Σ) pays 0.67
  /// at 0.2 m, so a sit policy perched on the seat's front edge, 0.2 m from its target, earned
  /// most of the near reward and never moved back (eval goal offsets); 0 = the papers' kernel.
  double precise_near_share = 0;
  /// Share of r_near paid by the wide kernel exp(−Σ), added to the skill's own (lie 0.5): reach
  /// policies left the hand 0.5–0.7 m below high targets, where exp(−10Σ) is ~0.01 and flat.
  double wide_near_share = 0;
  /// Share of r_near paid only as the pelvis faces the object's front (max(0, cos) between
  /// its heading and the anchor's direction from the target; for seats): sit policies stood
  /// astride narrow chairs and stools, the pelvis over the seat 0.35 m above its target, from
  /// where no motion leads down (eval poses); 0 = off, the papers' position-only r_near.
  double near_facing_share = 0;
  /// Hand-off state files (task/handoff.h: where another skill's policy left the character on
  /// furniture, recorded by `eval_policy --end-states`), e.g. get-up from where sit and lie
  /// end, lie from where sit ends; a relative path missing from the working directory is taken
  /// from the project root; [] = none.
  std::vector<std::string> handoff_states;
  /// Share of the reference starts taken from the hand-off states, placed on the env's object
  /// when one fits it (else a reference start as usual); labelled "handoff".
  double handoff_share = 0;
  /// Share of the training ground's pieces that get a table in front of them (a dining table,
  /// a desk or a coffee table, drawn alike), as the stories' rooms put one before most chairs
  /// and sofas: the sit policy trained on lone pieces squatted beside the rooms' chairs
  /// (sit/TRAINING.md); 0 = lone pieces. The tables are never targets: object_categories
  /// must name the targets and neither "table" nor "desk".
  double clutter_share = 0;
  /// Gap between the piece's front face and the table's near edge (m), drawn uniformly.
  double clutter_gap_min = 0.45;
  double clutter_gap_max = 1.0;  ///< ...

  /// Lists the fields for JSON binding (keys as in the skill config).
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(object_categories));
    a->Visit(SIMS_NVP(num_objects));
    a->Visit(SIMS_NVP(held_out_objects));
    a->Visit(SIMS_NVP(training_scale_min));
    a->Visit(SIMS_NVP(training_scale_max));
    a->Visit(SIMS_NVP(spawn_min_distance));
    a->Visit(SIMS_NVP(spawn_max_distance));
    a->Visit(SIMS_NVP(spawn_arc_deg));
    a->Visit(SIMS_NVP(spawn_curriculum));
    a->Visit(SIMS_NVP(spawn_curriculum_step));
    a->Visit(SIMS_NVP(spawn_full_range_share));
    a->Visit(SIMS_NVP(contact_success_threshold));
    a->Visit(SIMS_NVP(reference_window));
    a->Visit(SIMS_NVP(max_contact_force));
    a->Visit(SIMS_NVP(precise_near_share));
    a->Visit(SIMS_NVP(near_facing_share));
    a->Visit(SIMS_NVP(wide_near_share));
    a->Visit(SIMS_NVP(handoff_states));
    a->Visit(SIMS_NVP(handoff_share));
    a->Visit(SIMS_NVP(clutter_share));
    a->Visit(SIMS_NVP(clutter_gap_min));
    a->Visit(SIMS_NVP(clutter_gap_max));
    // Get-up's names from when only get-up had hand-off starts (its checkpoints and policies).
    a->VisitRenamed("getup_handoff_states", SIMS_NVP(handoff_states));
    a->VisitRenamed("getup_handoff_share", SIMS_NVP(handoff_share));
  }
  /// Checks ranges.
  void Validate() const;
};

}  // namespace sims::task
