// Sit: the pelvis on a seat surface (chair, armchair, sofa, stool), optionally the torso
// against the back rest (SitParams::back_contact). A surface skill (surface_skill.h: reward,
// success, reference init) whose pelvis part is the "seat surface": success when the pelvis
// is within contact_success_threshold (0.20 m) of the seat. Reference init places sit clips
// on the env's seat by the clip's stored seat height and front edge (motion/synthetic.h).
#pragma once

#include "sims/task/surface_skill.h"

namespace sims::task {

/// Categories with a "seat surface" the sit skill trains on by default.
std::vector<std::string> SeatCategories();

/// The sit skill.
class SitSkill : public SurfaceSkill {
 public:
  /// Uses the scene's objects with a seat surface.
  SitSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "sit"; }
};

/// Registry entry for sit.
SkillInfo SitSkillInfo();

}  // namespace sims::task
