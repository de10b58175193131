#include "sims/planner/plan.h"

#include <algorithm>
#include <cstdio>

#include "sims/core/skill_vocabulary.h"

namespace sims::planner {

namespace {
bool OneOf(const std::string& s, std::initializer_list<const char*> values) {
  return std::any_of(values.begin(), values.end(), [&](const char* v) { return s == v; });
}
}  // namespace

void LayoutSource::Validate() const {
  Require(OneOf(kind, {"builtin_room", "builtin_house", "morse", "front3d", "scene_file", "given"}),
          "kind", "one of builtin_room, builtin_house, morse, front3d, scene_file, given");
  if (kind == "front3d" || kind == "scene_file") Require(!path.empty(), "path", "a file path");
  if (kind == "builtin_room") Require(!name.empty(), "name", "a built-in room name");
}

std::string LayoutSource::SceneKey() const {
  return kind + "|" + path + "|" + model_dir + "|" + name;
}

void PlanLayout::Validate() const {
  Require(OneOf(mode, {"single", "composed", "given"}), "mode", "single, composed or given");
  if (mode != "given") Require(!rooms.empty(), "rooms", "at least one room");
}

void PlanKeyframe::Validate() const {
  const SkillTraits* traits = FindSkillTraits(skill);
  Require(traits && traits->scripted, "skill",
          "one of " + SkillNames([](const SkillTraits& t) { return t.scripted; }));
  // Walks may end on free floor and a get-up may happen on the floor; a placed keyframe of a
  // skill that needs an object binds one.
  if (placed && traits->needs_object)
    Require(!object.empty(), "object", "an object instance when placed");
}

void Plan::Validate() const {
  Require(version == 1, "version", "1");
  Require(OneOf(difficulty, {"simple", "mid", "hard"}), "difficulty", "simple, mid or hard");
  for (std::size_t i = 0; i < keyframes.size(); ++i)
    Require(keyframes[i].index == static_cast<int>(i), "keyframes[" + std::to_string(i) + "].index",
            "the keyframe's position " + std::to_string(i));
}

bool Plan::AllPlaced() const { return Unplaced().empty(); }

std::vector<int> Plan::Unplaced() const {
  std::vector<int> out;
  for (const PlanKeyframe& k : keyframes)
    if (!k.placed) out.push_back(k.index);
  return out;
}

nlohmann::json PlanToJson(const Plan& plan) { return ConfigToJson(plan); }

Plan PlanFromJson(const nlohmann::json& j, const std::string& source) {
  return ConfigFromJson<Plan>(j, source);
}

Plan LoadPlan(const std::filesystem::path& path) { return LoadConfig<Plan>(path); }

void SavePlan(const std::filesystem::path& path, const Plan& plan) {
  ValidateConfig(plan, path.string());
  WriteJsonFile(path, PlanToJson(plan));
}

std::string DescribePlan(const Plan& p) {
  std::string s;
  s += "planner: " + p.planner + (p.planner_note.empty() ? "" : " (" + p.planner_note + ")") + "\n";
  std::string arc;
  for (const std::string& a : p.arc) arc += (arc.empty() ? "" : " -> ") + a;
  s += "arc: " + arc + "\n";
  s += "layout: " + p.layout.name + " [" + p.layout.mode + ", cost " +
       std::to_string(p.layout.cost).substr(0, 6) + (p.layout.exact ? ", exact" : ", approximate") +
       "]\n";
  for (const PlanRoom& r : p.layout.rooms)
    s += "  room " + r.id + " (" + r.type + ") from " + r.source.kind +
         (r.source.name.empty() ? "" : " " + r.source.name) +
         (r.source.room_id.empty() ? "" : " / " + r.source.room_id) + "\n";
  for (const PlanKeyframe& k : p.keyframes) {
    char line[512];
    std::snprintf(line, sizeof(line), "%3d %-5s %-8s %-18s %-28s %s%s%s\n", k.index,
                  k.skill.c_str(), k.emotion.c_str(), k.style.c_str(),
                  (k.object.empty() ? (k.placed ? std::string("(floor)") : std::string("UNPLACED"))
                                    : k.object)
                      .c_str(),
                  k.caption.c_str(), k.inserted ? " [inserted]" : "",
                  k.note.empty() ? "" : ("  -- " + k.note).c_str());
    s += line;
  }
  for (const std::string& w : p.warnings) s += "warning: " + w + "\n";
  s += "story: " + p.narrative + "\n";
  return s;
}

}  // namespace sims::planner
