// The plan file: what the planner hands to the story runner (FSM). It is a long script whose
// keyframes are bound to object instances of a concrete layout, plus that layout's recipe (which
// scenes, which rooms, where they go, walls and doors) and the narrative.
//
// JSON schema (version 1; every field is always written):
// {
//   "version": 1,
//   "theme": "...",                  // "" when planned from a script file
//   "difficulty": "simple|mid|hard",
//   "seed": 0,
//   "planner": "embedded" | "llm:<model>" | "script",
//   "planner_note": "...",           // e.g. why the LLM back-end fell back to the embedded one
//   "arc": ["happy", "sad"],          // emotional arc in order
//   "script_ids": ["bedroom_happy_1", ...],
//   "keyframes": [{
//       "index": 0, "skill": "walk|sit|lie|reach|getup", "caption": "...",
//       "emotion": "sad", "style": "slow_bowed",   // style ids: configs/planner/vocabulary.json
//       "furniture": "sofa",          // category the script asked for ("floor" = none)
//       "instance": 0,                // which object of that category within its short script
//       "object": "living/sofa_0",    // bound instance in the materialised scene ("" = none)
//       "object_category": "loveseat", // category of the bound object (may be a substitute)
//       "room": "living",             // room id of the bound object
//       "script_id": "...", "segment": 0, "inserted": false,
//       "placed": true,               // false: could not be bound, `note` says why
//       "note": "..."}],
//   "layout": {
//       "name": "...", "mode": "single|composed|given", "cost": 0.0, "exact": true,
//       "rooms": [{"id", "type", "source": {"kind", "path", "model_dir", "name", "room_id"},
//                  "offset": [x, y, z], "footprint": [xmin, ymin, xmax, ymax]}],
//       "walls": [{"from": [x, y], "to": [x, y], "thickness": 0.1, "height": 2.5}],
//       "doors": [{"center": [x, y], "width": 1.0, "rooms": ["a", "b"]}]},
//   "narrative": "...",
//   "warnings": ["..."]
// }
// A walk keyframe is bound to the object it walks to (the next interaction's object); a walk
// with nothing after it has object "" and placed = true (free floor of `room`).
// Layout sources: kind "builtin_room" (name = scene::BuiltinScene name), "builtin_house",
// "morse" (the MORSE apartment), "front3d" (path = house JSON, model_dir = 3D-FUTURE models),
// "scene_file" (path for scene::LoadSceneFile) or "given" (the scene the caller passed in).
// In "composed" layouts object instances are "<room id>/<source instance>" and the walls are the
// plan's wall segments; in "single" layouts instances keep their source names and the source
// scene's walls are used.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/core/config.h"

namespace sims::planner {

/// Where a room's geometry comes from.
struct LayoutSource {
  std::string kind;       ///< builtin_room, builtin_house, morse, front3d, scene_file, given.
  std::string path;       ///< File (front3d house JSON, scene file), if any.
  std::string model_dir;  ///< 3D-FUTURE model folder (front3d).
  std::string name;       ///< Built-in scene name or display name.
  std::string room_id;    ///< Only this room's objects ("" = all objects of the source).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(kind));
    a->Visit(SIMS_NVP(path));
    a->Visit(SIMS_NVP(model_dir));
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(room_id));
  }
  /// Known kind.
  void Validate() const;
  /// A key identifying the source scene (kind, path, model_dir and name; room_id excluded).
  std::string SceneKey() const;
};

/// One room of a layout.
struct PlanRoom {
  std::string id;                               ///< Room id in the materialised scene.
  std::string type;                             ///< Room type (bedroom, living room, ...).
  LayoutSource source;                          ///< Where its objects come from.
  std::array<double, 3> offset{0, 0, 0};        ///< Translation applied to the source objects.
  std::array<double, 4> footprint{0, 0, 0, 0};  ///< xmin, ymin, xmax, ymax after the offset.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(id));
    a->Visit(SIMS_NVP(type));
    a->Visit(SIMS_NVP(source));
    a->Visit(SIMS_NVP(offset));
    a->Visit(SIMS_NVP(footprint));
  }
};

/// A straight wall segment (a box of `thickness` centred on from→to, `height` tall).
struct PlanWall {
  std::array<double, 2> from{0, 0};  ///< Start (xy).
  std::array<double, 2> to{0, 0};    ///< End (xy).
  double thickness = 0.1;            ///< Thickness (m).
  double height = 2.5;               ///< Height (m).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(from));
    a->Visit(SIMS_NVP(to));
    a->Visit(SIMS_NVP(thickness));
    a->Visit(SIMS_NVP(height));
  }
};

/// A door opening between two rooms.
struct PlanDoor {
  std::array<double, 2> center{0, 0};  ///< Centre of the opening (xy).
  double width = 1.0;                  ///< Opening width (m).
  std::vector<std::string> rooms;      ///< The two room ids it connects.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(center));
    a->Visit(SIMS_NVP(width));
    a->Visit(SIMS_NVP(rooms));
  }
};

/// The chosen layout and how to build it.
struct PlanLayout {
  std::string name;             ///< Display name.
  std::string mode = "single";  ///< single | composed | given.
  double cost = 0.0;            ///< Graph-matching cost of the choice.
  bool exact = true;            ///< Every graph edit distance involved was exact.
  std::vector<PlanRoom> rooms;  ///< Rooms (one for single layouts).
  std::vector<PlanWall> walls;  ///< Composed layouts: all walls.
  std::vector<PlanDoor> doors;  ///< Composed layouts: openings between neighbouring rooms.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(mode));
    a->Visit(SIMS_NVP(cost));
    a->Visit(SIMS_NVP(exact));
    a->Visit(SIMS_NVP(rooms));
    a->Visit(SIMS_NVP(walls));
    a->Visit(SIMS_NVP(doors));
  }
  /// Known mode, at least one room for single/composed.
  void Validate() const;
};

/// One keyframe of the plan.
struct PlanKeyframe {
  int index = 0;                ///< Position in the plan.
  std::string skill;            ///< walk, sit, lie, reach, getup.
  std::string caption;          ///< Motion description (language conditioning).
  std::string emotion;          ///< Canonical emotion.
  std::string style;            ///< Style id for the skill.
  std::string furniture;        ///< Requested category ("floor" = none).
  int instance = 0;             ///< Object index within its short script.
  std::string object;           ///< Bound instance in the materialised scene ("" = none).
  std::string object_category;  ///< Category of the bound object.
  std::string room;             ///< Room id of the bound object (or of the free floor).
  std::string script_id;        ///< Short script it came from.
  int segment = 0;              ///< Index of that short script in the plan.
  bool inserted = false;        ///< Added by the composer (walk / get-up).
  bool placed = false;          ///< Bound (or a free walk); false = could not be placed.
  std::string note;             ///< Substitution or failure explanation.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(index));
    a->Visit(SIMS_NVP(skill));
    a->Visit(SIMS_NVP(caption));
    a->Visit(SIMS_NVP(emotion));
    a->Visit(SIMS_NVP(style));
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(instance));
    a->Visit(SIMS_NVP(object));
    a->Visit(SIMS_NVP(object_category));
    a->Visit(SIMS_NVP(room));
    a->Visit(SIMS_NVP(script_id));
    a->Visit(SIMS_NVP(segment));
    a->Visit(SIMS_NVP(inserted));
    a->Visit(SIMS_NVP(placed));
    a->Visit(SIMS_NVP(note));
  }
  /// Known skill; a placed interaction names an object.
  void Validate() const;
};

/// A complete plan (see the schema at the top of this file).
struct Plan {
  int version = 1;                      ///< Schema version.
  std::string theme;                    ///< User theme ("" for script input).
  std::string difficulty = "mid";       ///< simple | mid | hard.
  uint64_t seed = 0;                    ///< Seed.
  std::string planner = "embedded";     ///< Which planner produced the keyframes.
  std::string planner_note;             ///< Fall-back reason or other planner remarks.
  std::vector<std::string> arc;         ///< Emotional arc.
  std::vector<std::string> script_ids;  ///< Short scripts used.
  std::vector<PlanKeyframe> keyframes;  ///< Bound keyframes.
  PlanLayout layout;                    ///< Chosen layout.
  std::string narrative;                ///< Story text.
  std::vector<std::string> warnings;    ///< Non-fatal problems (unplaced keyframes, ...).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(version));
    a->Visit(SIMS_NVP(theme));
    a->Visit(SIMS_NVP(difficulty));
    a->Visit(SIMS_NVP(seed));
    a->Visit(SIMS_NVP(planner));
    a->Visit(SIMS_NVP(planner_note));
    a->Visit(SIMS_NVP(arc));
    a->Visit(SIMS_NVP(script_ids));
    a->Visit(SIMS_NVP(keyframes));
    a->Visit(SIMS_NVP(layout));
    a->Visit(SIMS_NVP(narrative));
    a->Visit(SIMS_NVP(warnings));
  }
  /// Version 1, known difficulty, keyframes indexed 0..n-1.
  void Validate() const;
  /// True when every keyframe is placed.
  bool AllPlaced() const;
  /// Indices of keyframes that could not be placed.
  std::vector<int> Unplaced() const;
};

/// Plan → JSON.
nlohmann::json PlanToJson(const Plan& plan);
/// JSON → plan; errors name `source` and the field.
Plan PlanFromJson(const nlohmann::json& j, const std::string& source);
/// Reads a plan file.
Plan LoadPlan(const std::filesystem::path& path);
/// Writes a plan file atomically.
void SavePlan(const std::filesystem::path& path, const Plan& plan);
/// A human-readable summary (planner, arc, keyframes with bindings, layout, warnings, story).
std::string DescribePlan(const Plan& plan);

}  // namespace sims::planner
