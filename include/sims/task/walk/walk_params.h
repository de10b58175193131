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

  /// Lists the fields for JSON binding (keys as in the skill config).
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(target_min_distance));
    a->Visit(SIMS_NVP(target_max_distance));
    a->Visit(MakeNameValue("walk_success_radius", &success_radius));
    a->Visit(SIMS_NVP(resample_target_on_success));
  }
  /// Checks ranges.
  void Validate() const;
};

}  // namespace sims::task
