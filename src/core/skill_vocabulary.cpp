#include "sims/core/skill_vocabulary.h"

#include "sims/core/error.h"

namespace sims {

namespace {

// The built-in skills. Each skill's code lives in src/task/<skill>/; this is what the other
// modules know about it. The scripted skills come first, in the order of planner::Skill.
std::deque<SkillTraits> BuiltinSkills() {
  std::deque<SkillTraits> v;
  SkillTraits walk;
  walk.name = "walk";
  walk.description = "walk to a target on free floor in a style, then stand still";
  walk.scripted = true;
  walk.navigates = true;
  walk.flat_scene = true;  // trained on an empty floor: obstacles are the navigation's job
  walk.required = true;
  walk.timing = StoryTiming::kWalk;
  // A walk from the bed after a get-up that timed out went nowhere, and the story with it.
  walk.starts_standing = true;
  v.push_back(walk);

  SkillTraits sit;
  sit.name = "sit";
  sit.description = "sit down on a chair, armchair, sofa or stool";
  sit.scripted = sit.affordance = sit.needs_object = true;
  sit.follow_up = "getup";
  v.push_back(sit);

  SkillTraits lie;
  lie.name = "lie";
  lie.description = "lie down on a bed with the head on a pillow";
  lie.scripted = lie.affordance = lie.needs_object = true;
  lie.follow_up = "getup";
  // The bundled lie policy lies down on 84 of 100 held-out beds from standing but from where
  // the bundled sit left the character on beds and sofas on 15 of 97 (assets/policies/lie/).
  lie.starts_standing = true;
  v.push_back(lie);

  SkillTraits reach;
  reach.name = "reach";
  reach.description = "touch a point on a table, desk, cabinet, shelf or wardrobe with one hand";
  reach.scripted = reach.affordance = reach.needs_object = reach.hand_target = true;
  v.push_back(reach);

  SkillTraits getup;
  getup.name = "getup";
  getup.description = "get up from a seat, a bed or the floor and stand";
  getup.scripted = true;
  getup.recovers_falls = true;
  v.push_back(getup);

  SkillTraits unified;
  unified.name = "unified";
  unified.description = "one policy for chains of contacts (UniHSI): sit, lean, lie, touch, walk";
  unified.contact_steps = true;
  v.push_back(unified);
  return v;
}

std::deque<SkillTraits>& Table() {
  static std::deque<SkillTraits> table = BuiltinSkills();
  return table;
}

}  // namespace

const std::deque<SkillTraits>& SkillVocabulary() { return Table(); }

const SkillTraits* FindSkillTraits(const std::string& name) {
  for (const SkillTraits& t : Table())
    if (t.name == name) return &t;
  return nullptr;
}

const SkillTraits& SkillTraitsOf(const std::string& name) {
  if (const SkillTraits* t = FindSkillTraits(name)) return *t;
  ThrowInputError("skill", "skill",
                  "one of: " + SkillNames([](const SkillTraits&) { return true; }),
                  "'" + name + "'");
}

std::vector<const SkillTraits*> ScriptedSkills() {
  std::vector<const SkillTraits*> out;
  for (const SkillTraits& t : Table())
    if (t.scripted) out.push_back(&t);
  return out;
}

const SkillTraits& RegisterSkillTraits(SkillTraits traits) {
  if (traits.name.empty()) ThrowInputError("skill vocabulary", "name", "a skill name", "\"\"");
  if (FindSkillTraits(traits.name))
    ThrowInputError("skill vocabulary", "name", "a name not yet registered",
                    "'" + traits.name + "'");
  Table().push_back(std::move(traits));
  return Table().back();
}

}  // namespace sims
