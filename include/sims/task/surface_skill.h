// The code sit and lie share: put the pelvis on one furniture part (a seat surface, a mattress)
// and optionally one more contact joint on the nearest of some other parts (the torso on the
// back rest, the head on a pillow). Each episode fixes an object-local pelvis target (sit: the
// seat top behind its front edge, raised by the seated pelvis height; at a random place along
// wide seats) and a far anchor in front of the object, so the target never moves with the
// character nor points through a back rest. Contact reward (contact_reward.h) with g_pelvis the
// target and the extra joint's goal the nearest point of its parts; success when the pelvis
// (and the extra joint, where it counts) is within contact_success_threshold; the episode
// ends without failure once success has held for success_hold_steps. Reference init places
// the skill's clips on the env's furniture by their stored furniture parameters, at a time
// before the clip reaches the seat (ObjectSkill::FurnitureClipInit); the policy observes the
// object (ObjectSkill's "task" segment).
#pragma once

#include <string>
#include <vector>

#include "sims/task/object_skill.h"

namespace sims::task {

/// Which parts a surface skill targets (sit.cpp and lie.cpp each fill one).
struct SurfaceTask {
  std::string clip_skill;   ///< Motion clips of this label feed reference init.
  std::string what;         ///< The object it needs, for "no suitable object" errors.
  std::string pelvis_part;  ///< The part the pelvis goes on (kSeatPart, kMattressPart).
  /// The part used on objects without pelvis_part ("" = none; sit: a bed's mattress, whose
  /// foot end at +x is then the seat's front edge).
  std::string fallback_pelvis_part;
  /// The fallback part only where it is at least this wide (its y extent, m; lie: a sofa's
  /// seat, not a chair's).
  double fallback_min_width = 0.0;
  /// The episode's lateral choice on object g (e.g. SeatLateral; null = always 0).
  double (*lateral)(const ObjectGeometry& g, Rng& rng) = nullptr;
  /// The pelvis target in the object frame for that choice.
  Eigen::Vector3d (*target_local)(const ObjectGeometry& g, double lateral,
                                  const SkillConfig& c) = nullptr;
  /// The far anchor (a floor point in front of the object) in the object frame.
  Eigen::Vector3d (*anchor_local)(const ObjectGeometry& g, double lateral) = nullptr;
  int extra_joint = -1;  ///< A second contact joint (−1 = none).
  /// The parts of object g the extra joint may touch (nearest wins; none = no goal).
  std::vector<int> (*extra_parts)(const ObjectGeometry& g, const SkillConfig& c) = nullptr;
  bool extra_in_success = false;  ///< The extra joint's distance counts for success.
  /// Share of the wide kernel in r_near (contact_reward.h; lie: its joints start ~1 m away).
  double wide_near_share = 0.0;
};

/// A skill that rests body joints on furniture surfaces (see the file comment).
class SurfaceSkill : public ObjectSkill {
 public:
  /// Uses the scene's objects that have task.pelvis_part.
  SurfaceSkill(const SkillConfig& config, const SkillContext& context, SurfaceTask task);

  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;

  /// Updates env i's goals for body states `b`; returns Σ‖g_j − x_j‖² and sets the distance
  /// the success test compares (the pelvis's, or the larger of both joints') and the contact
  /// error: the mean distance over the joints success requires (UniHSI's per-pair mean).
  double UpdateGoals(int env_id, const humanoid::BodyStates& b, double* success_distance,
                     double* contact_error);
  /// Env i's lateral choice (m along the seat; lie: the side, ±1).
  double lateral(int env_id) const { return lateral_[env_id]; }
  /// task.pelvis_part, or the fallback part on objects without it.
  std::string support_part(const ObjectGeometry& g) const override;

 protected:
  bool Accepts(const ObjectGeometry& g) const override { return !support_part(g).empty(); }
  bool observes_object() const override { return true; }
  double ClipContactTime(int clip) const override;
  void SampleTask(int env_id, Rng& rng) override;
  bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) override;
  void SerializeTaskState(int env_id, StateArchive* archive) override;

 private:
  SurfaceTask task_;
  std::vector<std::vector<int>> extra_parts_;  // per object slot, fixed by the config
  std::vector<double> lateral_;  // per env: offset along a wide seat (its whole per-env state)
};

}  // namespace sims::task
