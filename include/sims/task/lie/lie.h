// Lie: the pelvis on a bed's mattress and the head on a pillow. A surface skill
// (surface_skill.h: reward, success, reference init) whose pelvis part is the "mattress" and
// whose head goes to the nearest of the bed's pillows; success when both joints are within
// contact_success_threshold (0.30 m for lie) of their parts. Reference init places lie clips
// on the env's bed by the clip's stored bed height, edge and head end.
#pragma once

#include "sims/task/surface_skill.h"

namespace sims::task {

/// The lie skill.
class LieSkill : public SurfaceSkill {
 public:
  /// Uses the scene's objects with a mattress.
  LieSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "lie"; }
};

/// Registry entry for lie.
SkillInfo LieSkillInfo();

}  // namespace sims::task
