// The skill vocabulary: every skill's name and the traits other modules act on (time-out
// class, success hold, walk-like navigation, object binding, follow-up skill, which trained
// policy serves it, ...). It is plain data in the lowest module so that the planner (which
// never runs a skill and does not depend on task/) and the state machine, evaluation and task
// registry all read one table and none of them compares skill names. task::SkillInfo binds an
// entry to the skill's code (factory, training scene, params); task::RegisterSkill adds both.
// The words naming a skill in scripts and sentences stay planner data: the aliases in
// configs/planner/vocabulary.json (planner::Vocabulary::Validate checks its skills against
// this table) and the fallback verbs in configs/planner/sentence.json, which resolve through them.
#pragma once

#include <deque>
#include <string>
#include <vector>

namespace sims {

/// Which of a story's time budgets (time-out and success-hold steps) a skill's instruction gets.
enum class StoryTiming {
  kWalk,    ///< StoryOptions::walk_timeout_s (+ per metre of detour), walk_success_hold_steps.
  kObject,  ///< StoryOptions::skill_timeout_s, success_hold_steps.
};

/// What the rest of the framework knows about a skill without its code.
struct SkillTraits {
  std::string name;             ///< Registry key (walk, sit, lie, reach, getup, ...).
  std::string description;      ///< One line for --help.
  bool scripted = false;        ///< A keyframe verb of planned scripts (the planner's skills).
  bool affordance = false;      ///< Furniture categories list it among their affordances.
  bool navigates = false;       ///< Walk-like: the goal is a floor point (A* waypoints, xy error).
  bool needs_object = false;    ///< A placed instruction must bind a scene object.
  bool hand_target = false;     ///< The target names a hand and a height band (from the caption).
  bool flat_scene = false;      ///< Trained on an empty floor: stories feed it a flat heightmap.
  bool required = false;        ///< Every story needs its policy (walk: the way between keyframes).
  bool recovers_falls = false;  ///< Stands the character up after a fall in a story.
  bool contact_steps = false;   ///< Runs UniHSI chain-of-contact steps (ScenePlans).
  StoryTiming timing = StoryTiming::kObject;  ///< Story time-out and success-hold class.
  std::string follow_up;  ///< Skill that ends the posture it leaves (sit, lie → getup), or "".
  /// Its policy starts from standing: stories run the get-up (the skill that recovers falls)
  /// first when the character is not standing (after a sit, a lie, a get-up that timed out).
  bool starts_standing = false;
};

/// Every known skill: the built-in ones in a fixed order (the planner's scripted skills first:
/// walk, sit, lie, reach, getup), then registered ones. References stay valid.
const std::deque<SkillTraits>& SkillVocabulary();
/// The entry named `name`, or nullptr.
const SkillTraits* FindSkillTraits(const std::string& name);
/// The entry named `name`; throws sims::Error listing the known names.
const SkillTraits& SkillTraitsOf(const std::string& name);
/// Skills with `scripted` set, in vocabulary order.
std::vector<const SkillTraits*> ScriptedSkills();
/// The names of the skills for which `pred` holds, joined with ", " (for messages).
template <class Pred>
std::string SkillNames(Pred pred) {
  std::string out;
  for (const SkillTraits& t : SkillVocabulary())
    if (pred(t)) out += (out.empty() ? "" : ", ") + t.name;
  return out;
}
/// Adds a skill (tests, plugins); throws sims::Error when the name is taken. Not thread-safe:
/// register before anything runs.
const SkillTraits& RegisterSkillTraits(SkillTraits traits);

}  // namespace sims
