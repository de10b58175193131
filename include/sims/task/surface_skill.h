// The code sit and lie share: put the pelvis on one furniture part (a seat surface, a mattress)
// and optionally one more contact joint on the nearest of some other parts (the torso on the
// back rest, the head on a pillow). Contact reward (contact_reward.h) with the anchor x* at the
// centre of the pelvis part and g_j the surface point of the goal part nearest to joint j;
// success when the pelvis (and the extra joint, where it counts) is within
// contact_success_threshold of its part; the episode ends without failure once success has
// held for success_hold_steps. Reference init places the skill's clips on the env's furniture
// by the clips' stored furniture parameters (ObjectSkill::FurnitureClipInit).
#pragma once

#include <string>
#include <vector>

#include "sims/task/object_skill.h"

namespace sims::task {

/// Which parts a surface skill targets (sit.cpp and lie.cpp each fill one).
struct SurfaceTask {
  std::string clip_skill;            ///< Motion clips of this label feed reference init.
  std::string what;                  ///< The object it needs, for "no suitable object" errors.
  int ObjectGeometry::*pelvis_part;  ///< The part the pelvis goes on (seat, mattress).
  scene::Aabb ObjectGeometry::*pelvis_bounds;  ///< That part's bounds (the reward's anchor).
  int extra_joint = -1;                        ///< A second contact joint (−1 = none).
  /// The parts of object g the extra joint may touch (nearest wins; none = no goal).
  std::vector<int> (*extra_parts)(const ObjectGeometry& g, const SkillConfig& c) = nullptr;
  bool extra_in_success = false;  ///< The extra joint's distance counts for success.
};

/// A skill that rests body joints on furniture surfaces (see the file comment).
class SurfaceSkill : public ObjectSkill {
 public:
  /// Uses the scene's objects that have task.pelvis_part.
  SurfaceSkill(const SkillConfig& config, const SkillContext& context, SurfaceTask task);

  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;

  /// Where env i's pelvis should go: the pelvis part's point nearest to `pelvis` (world).
  Eigen::Vector3d PelvisTarget(int env_id, const Eigen::Vector3d& pelvis) const;
  /// Updates env i's goals for body states `b`; returns Σ‖g_j − x_j‖² and sets the distance
  /// the success test compares (the pelvis's, or the larger of both joints').
  double UpdateGoals(int env_id, const sim::BodyStates& b, double* success_distance);

 protected:
  bool Accepts(const ObjectGeometry& g) const override { return g.*task_.pelvis_part >= 0; }
  bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) override;

 private:
  SurfaceTask task_;
  std::vector<std::vector<int>> extra_parts_;  // per object slot, fixed by the config
};

}  // namespace sims::task
