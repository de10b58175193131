// Sit's own settings (part of task::SkillConfig, bound flat like walk_params.h).
#pragma once

#include "sims/core/config.h"

namespace sims::task {

/// Sit options (see sit.h).
struct SitParams {
  bool back_contact = false;  ///< Also reward the torso touching the back rest.
  /// The pelvis target: this far behind the seat's front edge (at most its centre) ...
  double target_behind_edge = 0.2;
  /// ... and this high above the seat top (the seated pelvis of the sit clips: 0.085 m).
  double pelvis_height = 0.085;

  /// Lists the fields for JSON binding (keys as in the skill config).
  template <class A>
  void Serialize(A* a) {
    a->Visit(MakeNameValue("sit_back_contact", &back_contact));
    a->Visit(MakeNameValue("sit_target_behind_edge", &target_behind_edge));
    a->Visit(MakeNameValue("sit_pelvis_height", &pelvis_height));
  }
};

}  // namespace sims::task
