#include "sims/fsm/instruction.h"

#include <algorithm>
#include <sstream>

#include "sims/core/error.h"
#include "sims/core/skill_vocabulary.h"
#include "sims/humanoid/humanoid.h"
#include "sims/planner/sentence.h"
#include "sims/scene/contact_targets.h"
#include "sims/scene/navigation.h"

namespace sims::fsm {

namespace {
// The first vocabulary skill with a trait (a story's walk, the ScenePlan runner).
template <class Pred>
std::string SkillWith(Pred pred) {
  for (const SkillTraits& t : SkillVocabulary())
    if (pred(t)) return t.name;
  SIMS_CHECK_MSG(false, "the skill vocabulary lacks a skill this story needs");
  return {};
}

// Centre of the room's floor polygon, for walks that end on free floor.
std::optional<Eigen::Vector2d> RoomCentre(const scene::Scene& scene, const std::string& room) {
  for (const auto& r : scene.rooms) {
    if (r.id != room || r.floor_polygon.empty()) continue;
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : r.floor_polygon) c += p;
    return c / static_cast<double>(r.floor_polygon.size());
  }
  return std::nullopt;
}
}  // namespace

int FindObjectIndex(const scene::Scene& scene, const std::string& instance) {
  for (size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].instance == instance) return static_cast<int>(i);
  return -1;
}

std::vector<Instruction> BuildInstructions(const planner::Plan& plan, const scene::Scene& scene,
                                           const scene::RayCaster& caster) {
  std::vector<Instruction> out;
  for (const auto& k : plan.keyframes) {
    Instruction in;
    in.keyframe = k.index;
    in.skill = k.skill;
    in.caption = k.caption;
    in.emotion = k.emotion;
    in.object_name = k.object;
    in.placed = k.placed;
    in.note = k.note;
    const int obj = k.object.empty() ? -1 : FindObjectIndex(scene, k.object);
    if (!k.object.empty() && obj < 0) {
      in.placed = false;
      in.note = "object '" + k.object + "' is not in the scene";
    }
    in.target.object = obj;
    // A plan may name a skill no one registered: it gets no traits and fails in the FSM.
    static const SkillTraits kUnknown;
    const SkillTraits* found = FindSkillTraits(k.skill);
    const SkillTraits& traits = found ? *found : kUnknown;
    if (traits.navigates) {
      if (obj >= 0) {
        // A stand point the body fits at with its arms swinging (the navigation's clearance),
        // else the tightest one the scene offers.
        scene::StandPointOptions roomy;
        roomy.clearance_radius = scene::NavigationConfig{}.clearance;
        auto stands = scene::StandPoints(scene, caster, obj, roomy);
        if (stands.empty()) stands = scene::StandPoints(scene, caster, obj);
        if (!stands.empty()) {
          in.target.point = stands.front();
          in.target.has_point = true;
        } else {
          in.note = "no free stand point around '" + k.object + "'; walking to its centre";
        }
      } else if (auto c = RoomCentre(scene, k.room)) {
        in.target.point = {c->x(), c->y(), 0};
        in.target.has_point = true;
      } else if (in.placed) {
        in.placed = false;
        in.note = "walk keyframe without an object or a room to walk to";
      }
    } else if (traits.hand_target) {
      in.target.hand =
          planner::ReachUsesLeftHand(k.caption) ? humanoid::kCjLeftHand : humanoid::kCjRightHand;
      in.target.height = planner::ReachHeightFromCaption(k.caption);
    }
    if (traits.needs_object && obj < 0 && in.placed) {
      in.placed = false;
      in.note = k.skill + " keyframe without a bound object";
    }
    out.push_back(std::move(in));
  }
  return out;
}

namespace {

// "pelvis on seat_soft_surface (chair000), torso not on back (chair000)".
std::string ContactStepCaption(const task::ContactStep& step, const scene::Scene& scene) {
  std::string text;
  for (const auto& p : step.pairs) {
    if (p.type == task::ContactType::kNone) continue;
    std::string what;
    if (p.target_joint >= 0) {
      what = humanoid::ContactJointNames()[p.target_joint];
    } else if (p.object >= 0 && p.object < static_cast<int>(scene.objects.size())) {
      const auto& o = scene.objects[p.object];
      what = (p.part >= 0 && p.part < static_cast<int>(o.parts.size()) ? o.parts[p.part].name
                                                                       : o.category) +
             " (" + o.instance + ")";
    }
    text += (text.empty() ? "" : ", ") + std::string(humanoid::ContactJointNames()[p.joint]) +
            (p.type == task::ContactType::kContact ? " on " : " not on ") + what;
  }
  return text.empty() ? "contact step" : text;
}

}  // namespace

std::vector<Instruction> BuildInstructions(const task::ContactPlan& plan,
                                           const scene::Scene& scene) {
  // Walking steps go to the story's walk-like skill, contact steps to the chain-of-contacts one.
  const std::string walk_skill = SkillWith([](const SkillTraits& t) { return t.navigates; });
  const std::string contact_skill = SkillWith([](const SkillTraits& t) { return t.contact_steps; });
  std::vector<Instruction> out;
  for (size_t k = 0; k < plan.steps.size(); ++k) {
    const task::ContactStep& step = plan.steps[k];
    Instruction in;
    in.keyframe = static_cast<int>(k);
    in.target.object = step.object;
    if (step.object >= 0 && step.object < static_cast<int>(scene.objects.size()))
      in.object_name = scene.objects[step.object].instance;
    if (step.walking()) {
      in.skill = walk_skill;
      in.caption = "walk to " + in.object_name;
      in.target.point = {step.stand_point.x(), step.stand_point.y(), 0};
      in.target.has_point = true;
    } else {
      in.skill = contact_skill;
      in.caption = ContactStepCaption(step, scene);
      in.target.contact_step = std::make_shared<const task::ContactStep>(step);
    }
    out.push_back(std::move(in));
  }
  return out;
}

}  // namespace sims::fsm
