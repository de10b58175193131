// Sit: the pelvis on a seat surface (chair, armchair, sofa, stool), optionally the torso
// against the back rest (config.sit_back_contact). Contact reward (see
// contact_reward.h) with the anchor x* at the seat centre and g_j the seat's (back's) surface
// point nearest to joint j; success when the pelvis is within contact_success_threshold
// (0.20 m) of the seat; the episode ends without failure once success has held for
// success_hold_steps. Reference init places sit clips on the env's seat by the clip's stored
// seat height and front edge (motion/synthetic.h conventions).
#pragma once

#include "sims/task/object_skill.h"

namespace sims::task {

/// Categories with a "seat surface" the sit skill trains on by default.
std::vector<std::string> SeatCategories();

/// The sit skill.
class SitSkill : public ObjectSkill {
 public:
  /// Uses the scene's objects with a seat surface.
  SitSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "sit"; }
  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;

  /// Where env i's pelvis should go: the seat point nearest to `pelvis` (world).
  Eigen::Vector3d SeatTarget(int env_id, const Eigen::Vector3d& pelvis) const;
  /// Updates env i's goals for body states `b`; returns Σ‖g_j − x_j‖² and sets the pelvis
  /// distance to the seat.
  double UpdateGoals(int env_id, const sim::BodyStates& b, double* pelvis_distance);

 protected:
  bool Accepts(const ObjectGeometry& g) const override { return g.seat >= 0; }
  bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) override;
};

/// Registry entry for sit.
SkillInfo SitSkillInfo();

}  // namespace sims::task
