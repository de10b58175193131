// Walk's own settings. They are part of task::SkillConfig (the one config a training run and a
// policy file carry), bound flat: the JSON keys sit beside the shared ones.
#pragma once

#include "sims/core/config.h"

namespace sims::task {

/// Walk targets and success (see walk.h).
struct WalkParams {
  double target_min_distance = 0.5;        ///< Walk targets at least this far (m).
  double target_max_distance = 5.0;        ///< ... and at most this far (m).
  double success_radius = 0.5;             ///< Reached when within this (m, xy).
  bool resample_target_on_success = true;  ///< New walk target after a held success.
  /// Style-conditioned training: the speed term asks for the pace of the episode's style clip
  /// (its "speed" parameter, clamped to [style_speed_min, style_speed_max]) instead of
  /// target_speed, so the task reward agrees with the style the discriminator asks for.
  bool speed_from_style = false;
  double style_speed_min = 0.7;  ///< m/s (a 5 m evaluation target stays reachable in 10 s).
  double style_speed_max = 1.5;  ///< m/s.
  /// Style-conditioned training: share of the task reward paid for the style clip's posture,
  /// r = (1 − w)·r_walk + w·exp(−style_pose_scale·mean_j (q̃_j − q̄_j)²), q̄ the clip's mean
  /// joint angles and q̃ the character's joint angles averaged over the last ~style_pose_time
  /// seconds (an average, so the gait's swing is not punished). It gives the policy a dense
  /// signal for the posture a style asks for (head bowed, arms tight) where a saturated
  /// discriminator pays every agent motion about the same. 0 = off.
  double style_pose_weight = 0.0;
  double style_pose_scale = 50.0;  ///< 1/rad²: mean squared error 0.02 rad² pays e⁻¹.
  double style_pose_time = 1.0;    ///< Time constant of the posture average (s).
  /// Walks among furniture: 0 trains on open floor; n > 0 builds n random furnished rooms
  /// (scene::RandomRooms) and gives each env a room, starts on its free floor, targets on free
  /// floor of the same room reachable by A* (scene::FreeSpaceGrid), a pelvis goal that chases
  /// a point path_lookahead ahead on the path (as the story FSM does), and ends the episode
  /// as a failure when the character touches furniture or a wall. The furniture has held-out
  /// dimensions when held_out_objects is set (evaluation).
  int rooms = 0;
  double path_lookahead = 1.0;  ///< m ahead on the A* path (the FSM's lookahead).
  /// Share of the task reward paid for feet that do not slide: r = (1 − w − w_pose)·r_walk +
  /// w_pose·r_pose + w·exp(−foot_slide_scale·Σ_f ‖v_f,xy‖²) over the feet whose origin is below
  /// foot_contact_height. The walk policies shuffle (foot origin median 5.5 cm, 0.5 cm above
  /// a flat sole; 0.41 m/s of sliding on flat ground against 0.05 m/s in the demo clips) and
  /// a saturated discriminator does not tell them otherwise. 0 = off.
  double foot_slide_weight = 0.0;
  double foot_slide_scale = 5.0;      ///< s²/m²: a foot sliding at 0.45 m/s pays e⁻¹.
  double foot_contact_height = 0.08;  ///< m, foot body origin (eval's foot-sliding metric).
  /// Among furniture (rooms > 0): share of starts standing just in front of a piece of
  /// furniture of the room, facing it, the pelvis furniture_start_min..max m from one of its
  /// sides, the way sit, reach and lie leave the character in a story. The walk that follows
  /// must turn away without touching it; free-floor starts never teach that (the main story's
  /// walk from the bookshelf after a reach fell in 8 of 10 seeds). 0 = off.
  double furniture_start_share = 0.0;
  double furniture_start_min = 0.25;  ///< m from the furniture's side to the pelvis.
  double furniture_start_max = 0.5;   ///< m.

  /// Lists the fields for JSON binding (keys as in the skill config).
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(target_min_distance));
    a->Visit(SIMS_NVP(target_max_distance));
    a->Visit(MakeNameValue("walk_success_radius", &success_radius));
    a->Visit(SIMS_NVP(resample_target_on_success));
    a->Visit(SIMS_NVP(speed_from_style));
    a->Visit(SIMS_NVP(style_speed_min));
    a->Visit(SIMS_NVP(style_speed_max));
    a->Visit(SIMS_NVP(style_pose_weight));
    a->Visit(SIMS_NVP(style_pose_scale));
    a->Visit(SIMS_NVP(style_pose_time));
    a->Visit(MakeNameValue("walk_rooms", &rooms));
    a->Visit(MakeNameValue("walk_path_lookahead", &path_lookahead));
    a->Visit(SIMS_NVP(foot_slide_weight));
    a->Visit(SIMS_NVP(foot_slide_scale));
    a->Visit(SIMS_NVP(foot_contact_height));
    a->Visit(MakeNameValue("walk_furniture_start_share", &furniture_start_share));
    a->Visit(MakeNameValue("walk_furniture_start_min", &furniture_start_min));
    a->Visit(MakeNameValue("walk_furniture_start_max", &furniture_start_max));
  }
  /// Checks ranges.
  void Validate() const;
};

}  // namespace sims::task
