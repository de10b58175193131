// Reach: the left or right hand to a point on a part of an object (table, desk, cabinet,
// shelf, wardrobe) at a low, medium or high height. Contact reward (see contact_reward.h)
// with the hand's goal g at the target point and the far anchor x* a stand point in front of
// it (kStandDistance off the object's front face), so the approach comes from the front;
// success when the hand is within contact_success_threshold; the episode ends without failure
// once success has held for success_hold_steps. Targets are surface samples on the object's
// front (its +x side) in one of three height bands; reference init places a reach clip of the
// same hand whose stored target height matches so that its target lands on the point, the
// character facing the object, at a time before the hand arrives. The policy observes the
// object (ObjectSkill's "task" segment).
#pragma once

#include <array>

#include "sims/task/object_skill.h"

namespace sims::task {

/// Height bands of reach targets (m): low [0.25, 0.7), medium [0.7, 1.3), high [1.3, 1.95).
inline constexpr std::array<double, 4> kReachBandEdges = {0.25, 0.7, 1.3, 1.95};

/// Categories the reach skill trains on by default.
std::vector<std::string> ReachCategories();

/// The reach skill.
class ReachSkill : public ObjectSkill {
 public:
  /// Uses the scene's objects with front surface points in some height band.
  ReachSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "reach"; }
  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;
  /// As ObjectSkill's, then the caption's hand and height band (or target.point) pick the
  /// target: the candidate of that band nearest the character.
  bool BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) override;
  /// The height band of env i's target ("low", "medium", "high"), so evaluation reports
  /// success per band.
  std::string start_label(int env_id) const override;

  /// Env i's reaching contact joint (humanoid::kCjLeftHand or humanoid::kCjRightHand).
  int hand(int env_id) const { return hand_[env_id]; }
  /// Sets env i's hand and target (FSM / eval; resets the success counter).
  void SetTarget(int env_id, int hand_joint, const Eigen::Vector3d& target);
  /// Candidate targets of objects()[k] in height band b (world points).
  const std::vector<Eigen::Vector3d>& candidates(int k, int band) const {
    return candidates_[k][band];
  }

 protected:
  bool Accepts(const ObjectGeometry& g) const override;
  bool observes_object() const override { return true; }
  double ClipContactTime(int clip) const override;
  void SampleTask(int env_id, Rng& rng) override;
  bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) override;
  void SerializeTaskState(int env_id, StateArchive* archive) override;

 private:
  using Bands = std::array<std::vector<Eigen::Vector3d>, 3>;
  Bands FrontPoints(const ObjectGeometry& g) const;
  std::vector<Bands> candidates_;
  std::vector<int> hand_;  // per env: the reaching hand (its whole per-env state)
};

/// Registry entry for reach.
SkillInfo ReachSkillInfo();

}  // namespace sims::task
