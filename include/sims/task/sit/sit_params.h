// Sit's own settings (part of task::SkillConfig, bound flat like walk_params.h).
#pragma once

#include "sims/core/config.h"

namespace sims::task {

/// Sit options (see sit.h).
struct SitParams {
  bool back_contact = false;  ///< Also reward the torso touching the back rest.

  /// Lists the fields for JSON binding (keys as in the skill config).
  template <class A>
  void Serialize(A* a) {
    a->Visit(MakeNameValue("sit_back_contact", &back_contact));
  }
};

}  // namespace sims::task
