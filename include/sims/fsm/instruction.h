// Instructions: what the FSM runs. A planned long script becomes I = [(skill k, heightmap
// source h, goal g, style z)]: the skill's policy, the scene (whose height grid feeds the
// egocentric heightmap), the goal (object, part or point, see task::InstructionTarget) and
// the style embedding of the caption. UniHSI chain-of-contacts plans become instructions too.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/planner/plan.h"
#include "sims/scene/ray_caster.h"
#include "sims/scene/scene.h"
#include "sims/task/contact_plan.h"
#include "sims/task/skill.h"

namespace sims::fsm {

/// One step of a story.
struct Instruction {
  int keyframe = -1;        ///< Plan keyframe index (−1: added by the FSM, e.g. a recovery).
  std::string skill;        ///< walk, sit, lie, reach, getup (a policy-set key).
  std::string caption;      ///< Motion description.
  std::string emotion;      ///< Emotion label.
  std::string object_name;  ///< Bound object instance ("" = none).
  task::InstructionTarget target;  ///< Goal in the scene.
  Eigen::VectorXf z;               ///< Style embedding (empty = none).
  bool placed = true;  ///< False: the planner could not bind it; the FSM records a failure.
  std::string note;    ///< Why it is unplaced, or remarks.
};

/// Index of an object instance in the scene, or −1.
int FindObjectIndex(const scene::Scene& scene, const std::string& instance);

/// Turns a plan's keyframes into instructions in `scene` (the plan's materialised layout):
/// objects by instance name, walk targets at a free stand point of the object walked to (or
/// the free floor of the keyframe's room), reach height and hand from the caption.
std::vector<Instruction> BuildInstructions(const planner::Plan& plan, const scene::Scene& scene,
                                           const scene::RayCaster& caster);

/// Turns a UniHSI chain of contacts into instructions: a walking step becomes a walk to its
/// stand point (A* and the walk policy), a contact step runs the unified skill with the step's
/// contact pairs (goal + mask) on its object.
std::vector<Instruction> BuildInstructions(const task::ContactPlan& plan,
                                           const scene::Scene& scene);

}  // namespace sims::fsm
