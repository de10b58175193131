// Lie: the pelvis on a bed's mattress and the head on a pillow. Contact reward (see
// contact_reward.h) with the anchor x* at the mattress centre and g_j the surface point of
// the goal part nearest to joint j (the nearest of the bed's pillows for the head); success
// when both joints are within contact_success_threshold (0.30 m for lie) of their parts; the
// episode ends without failure once success has held for success_hold_steps. Reference init
// places lie clips on the env's bed by the clip's stored bed height, edge and head end.
#pragma once

#include "sims/task/object_skill.h"

namespace sims::task {

/// The lie skill.
class LieSkill : public ObjectSkill {
 public:
  /// Uses the scene's objects with a mattress.
  LieSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "lie"; }
  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;

  /// Updates env i's goals for body states `b`; returns Σ‖g_j − x_j‖² and the largest
  /// joint-to-part distance (what the success test compares).
  double UpdateGoals(int env_id, const sim::BodyStates& b, double* max_distance);

 protected:
  bool Accepts(const ObjectGeometry& g) const override { return g.mattress >= 0; }
  bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) override;
};

/// Registry entry for lie.
SkillInfo LieSkillInfo();

}  // namespace sims::task
