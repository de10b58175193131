// Chains of contacts (UniHSI): a plan is a list of steps; each step asks some of the 15
// contact joints to touch (or avoid) a part of an object or another joint, optionally from a
// direction. A step without contacts is a walking step to the object's stand point. This
// header turns a UniHSI ScenePlan's "chain of contacts" / "contact_pairs" into steps resolved
// against the scene LoadScenePlan built (objects by "<name><key>", parts by UniHSI part key),
// for the unified skill, eval_policy and the FSM.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "sims/humanoid/state.h"
#include "sims/scene/scene.h"
#include "sims/task/contact_reward.h"

namespace sims::task {

/// One contact pair of a step.
struct ContactPairSpec {
  int joint = 0;                                        ///< Contact joint (humanoid::ContactJoint).
  ContactType type = ContactType::kContact;             ///< Contact, not contact or none.
  int object = -1;                                      ///< Scene object index (−1: joint pair).
  int part = -1;                                        ///< Part index in that object.
  int target_joint = -1;                                ///< Other joint of a joint–joint pair.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< World direction (unit) or zero.
};

/// One step of a chain of contacts.
struct ContactStep {
  std::vector<ContactPairSpec> pairs;                     ///< At most one pair per joint.
  int object = -1;                                        ///< Scene object the step is about.
  Eigen::Vector3d stand_point = Eigen::Vector3d::Zero();  ///< Walking target (world, root z).
  std::string label;                                      ///< Short description ("sit", ...).

  /// True when no pair has a type other than kNone (a walking step).
  bool walking() const;
  /// Bitmask of joints with a pair of type contact or not contact.
  uint32_t mask() const;
  /// Per-joint pair types (kNone where the joint has no pair).
  std::array<ContactType, humanoid::kNumContactJoints> types() const;
};

/// The step's per-joint goals for body states `b` (what the unified skill observes and rewards):
/// for each pair its type, the joint's position, its target — the part's surface sample nearest
/// to the joint (UniHSI), or the other joint — and the direction; kNone elsewhere.
std::array<JointPair, humanoid::kNumContactJoints> ResolveStep(const ContactStep& step,
                                                               const scene::Scene& scene,
                                                               const humanoid::BodyStates& b);

/// A resolved plan.
struct ContactPlan {
  std::string id;                  ///< Plan id.
  std::vector<ContactStep> steps;  ///< Steps in order.
};

/// Resolves one plan object ({"obj": {...}, "chain of contacts" | "contact_pairs": [...]})
/// against `scene`; errors name `source`, the plan id and the offending field.
ContactPlan ContactPlanFromJson(const nlohmann::json& plan, const scene::Scene& scene,
                                const std::string& source, const std::string& plan_id);

/// Loads plan `plan_id` (empty = the first) of a ScenePlan JSON file for the scene that
/// scene::LoadScenePlan built from the same file.
ContactPlan LoadContactPlan(const std::filesystem::path& json_path, const scene::Scene& scene,
                            const std::string& plan_id = "");

/// A ScenePlan reference loaded: the scene of its PartNet objects and its chain of contacts.
struct LoadedScenePlan {
  std::filesystem::path file;                 ///< The ScenePlan JSON.
  std::shared_ptr<const scene::Scene> scene;  ///< Its objects.
  ContactPlan plan;                           ///< Its steps (at least one).
};

/// Loads "plan.json[#id]" (scene::ParseScenePlanRef) with PartNet objects from
/// `partnet_root` ("" = scene::DefaultPartNetRoot()); throws sims::Error for a plan without
/// steps.
LoadedScenePlan LoadScenePlanRef(const std::string& ref,
                                 const std::filesystem::path& partnet_root = {});

}  // namespace sims::task
