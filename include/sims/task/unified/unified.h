// Unified: UniHSI's unified controller — one policy for arbitrary chains of contacts.
//
// Each episode runs a chain of steps (contact_plan.h). In training the chain is random over the
// env's object: an optional walking step to a stand point, then one or two interaction steps
// drawn from the object's templates (pelvis on the seat; + torso on / not on the back; + hands
// on the arm rests; + hands on the knees; pelvis on the mattress; + head on a pillow; one hand
// on a table top / shelf board / cabinet). With SetPlan() every episode runs a fixed plan (a
// ScenePlan for eval_policy and the FSM).
//
// Reward: the UniHSI contact-pair reward with adaptive weights, or the walking-step reward
// (contact_reward.h). Step rule: when CheckUniHsiStep triggers, the step
// advances (the simulation state is kept) if it passed the tight thresholds, otherwise the
// episode ends (truncation, as UniHSI resets). Passing the last step is a success and ends the
// episode. Excessive contact force terminates it.
//
// Observation: the shared layout [contact goal 60 | heightmap | z 64] — the goal of a pair is
// its current nearest target point, a walking step's is the stand point for the pelvis — then
// "contact_pairs": per joint the pair type (+1 contact, −1 not contact, 0 none; 15) and the
// required direction in the heading frame (45).
#pragma once

#include "sims/task/contact_plan.h"
#include "sims/task/object_skill.h"

namespace sims::task {

/// Values of the "contact_pairs" observation segment: 15 types + 15 × 3 directions.
inline constexpr int kContactPairObsDim = humanoid::kNumContactJoints * 4;

/// Categories the unified skill trains on by default.
std::vector<std::string> UnifiedCategories();

/// The per-env data of the unified skill (after its ObjectState in a snapshot).
struct UnifiedState {
  std::vector<ContactStep> steps;  ///< The env's chain.
  int step = 0;                    ///< Index of the current step.
  int still = 0;                   ///< Consecutive steps the character has been still.
  int completed = 0;               ///< Steps completed this episode.

  /// Lists the fields; `scene` bounds the object and part indices. Step labels are not stored:
  /// reading gives "walk" or "contact".
  void Serialize(StateArchive* a, const scene::Scene& scene);
};

/// The unified contact skill.
class UnifiedSkill : public ObjectSkill {
 public:
  /// Uses every object of the scene (objects without templates get walking steps).
  UnifiedSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "unified"; }
  int obs_dim() const override;
  std::vector<sim::ObsSegment> obs_segments() const override;
  void Observe(const sim::EnvView& view, float* out) const override;
  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;
  /// With target.contact_step: runs that one step on its object (the FSM's UniHSI plans);
  /// otherwise a chain on the target object as ObjectSkill does.
  bool BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) override;

  /// Runs `steps` in every following episode (empty = random chains again).
  void SetPlan(const std::vector<ContactStep>& steps);
  /// Env i's chain.
  const std::vector<ContactStep>& steps(int env_id) const { return unified_[env_id].steps; }
  /// Index of env i's current step.
  int step_index(int env_id) const { return unified_[env_id].step; }
  /// Steps env i has completed this episode.
  int steps_completed(int env_id) const { return unified_[env_id].completed; }
  /// Contact error of env i's current step at the last step (m; eval metric, see
  /// PairContactError; the stand-point distance for walking steps).
  double contact_error(int env_id) const { return env_[env_id].error; }
  /// A random chain over scene object objects()[k] (the training distribution).
  std::vector<ContactStep> RandomChain(int k, Rng& rng) const;

 protected:
  bool Accepts(const ObjectGeometry& g) const override { return g.object >= 0; }
  void SampleTask(int env_id, Rng& rng) override;
  void SerializeTaskState(int env_id, StateArchive* archive) override;

 private:
  void UpdateGoals(int env_id, const std::array<JointPair, humanoid::kNumContactJoints>& pairs);
  std::vector<ContactStep> Templates(int k) const;

  std::vector<ContactStep> plan_;
  std::vector<UnifiedState> unified_;  // per env
};

/// Registry entry for unified.
SkillInfo UnifiedSkillInfo();

}  // namespace sims::task
