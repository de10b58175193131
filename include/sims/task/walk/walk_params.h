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
  }
  /// Checks ranges.
  void Validate() const;
};

}  // namespace sims::task
