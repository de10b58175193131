// Scene loaders: any mesh file Assimp reads (incl. .blend), the categorised MORSE furniture
// and apartment, 3D-FRONT houses, ScanNet scans, PartNet objects and UniHSI ScenePlans.
// Every loader returns Z-up metres and answers bad input with a sims::Error naming the file,
// the field and what was expected.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/scene/scene.h"

namespace sims::scene {

/// Maps object / label names to normalised categories with ordered, case-insensitive
/// ECMAScript regular expressions (first match wins). JSON:
/// {"categories": [{"pattern": "^IKEA_chair", "category": "chair", "important": true}, ...],
///  "structure": ["^C6_plein_ext"], "ignore": ["^Plane$"]}. "structure" names become walls,
/// "ignore" names are dropped.
class CategoryTable {
 public:
  /// What a name is.
  enum class Kind { kObject, kStructure, kIgnore, kUnknown };
  /// Result of Classify.
  struct Match {
    Kind kind = Kind::kUnknown;  ///< Object, structure, ignored, or no rule matched.
    std::string category;        ///< Category for kObject.
    bool important = true;       ///< Scene-graph importance for kObject.
  };
  /// An empty table (everything is kUnknown).
  CategoryTable();
  /// Reads a table; errors name the file and the offending field.
  static CategoryTable Load(const std::filesystem::path& path);
  /// Parses a table from JSON; `source` names it in errors.
  static CategoryTable FromJson(const nlohmann::json& j, const std::string& source);
  /// Classifies a name.
  Match Classify(const std::string& name) const;
  /// True when no rule exists.
  bool empty() const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

/// How a generic mesh file becomes a scene.
struct MeshLoadOptions {
  double unit_scale = 1.0;          ///< Multiplies coordinates (0.01 for centimetres).
  std::string up_axis = "auto";     ///< "z", "y", or "auto" (.blend/.ply/.stl/.off: z; else y).
  std::string split = "nodes";      ///< "nodes": one object per top-level node; "single": one.
  std::string category = "object";  ///< Category of objects no table rule matches.
  std::string category_table;       ///< Optional JSON table path (see CategoryTable).
  int points_per_part = Object::kDefaultPointsPerPart;  ///< Surface samples per part.
  bool drop_to_floor = false;  ///< Shift so the lowest vertex sits at z = 0.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(unit_scale));
    a->Visit(SIMS_NVP(up_axis));
    a->Visit(SIMS_NVP(split));
    a->Visit(SIMS_NVP(category));
    a->Visit(SIMS_NVP(category_table));
    a->Visit(SIMS_NVP(points_per_part));
    a->Visit(SIMS_NVP(drop_to_floor));
  }
  /// Known up axis and split mode, positive scale.
  void Validate() const;
};

/// Loads any Assimp-readable file. With split "nodes", each top-level node with geometry is
/// one object (pose = the node's transform, category from the table by node name) whose parts
/// are its meshes (named after the mesh, else its material, else "body"); table "structure"
/// nodes go to the walls.
Scene LoadMeshScene(const std::filesystem::path& path, const MeshLoadOptions& options = {});

/// All triangles of a mesh file merged (unit scale and up axis applied).
TriangleMesh LoadTriangleMesh(const std::filesystem::path& path,
                              const MeshLoadOptions& options = {});

/// Where the Debian morse-simulator-data lives: the installed Environment's morse_dir
/// ($SIMS_MORSE_DIR in the apps), else /usr/share/morse/data.
std::filesystem::path MorseDataDir();

/// A MORSE .blend file categorised by configs/scene/morse_categories.json.
Scene LoadMorseScene(const std::filesystem::path& blend_path);

/// The MORSE furniture props (props/furnitures.blend): IKEA beds, chairs, sofas, shelves, ...
Scene LoadMorseFurniture();

/// The furnished MORSE apartment (environments/apartment.blend) with its walls.
Scene LoadMorseApartment();

/// Options of the 3D-FRONT loader.
struct Front3DOptions {
  std::string category_table;  ///< JSON table for 3D-FUTURE categories ("" = configs default).
  int points_per_part = Object::kDefaultPointsPerPart;  ///< Surface samples per part.
  bool skip_missing_models = true;  ///< Warn and skip furniture whose model folder is absent.
};

/// A 3D-FRONT house (Y-up JSON: furniture[], mesh[], scene.room[].children[]) with its
/// 3D-FUTURE models (<future_model_dir>/<jid>/raw_model.obj, categories from model_info.json
/// in the model folder or a list in <future_model_dir>/model_info.json). Placement is
/// world = R(rot) (v ⊙ scale) + pos with rot = (x, y, z, w), then Y-up → Z-up.
Scene LoadFront3D(const std::filesystem::path& house_json,
                  const std::filesystem::path& future_model_dir,
                  const Front3DOptions& options = {});

/// A ScanNet scan: <id>_vh_clean_2.ply, <id>.aggregation.json (or <id>_vh_clean.aggregation
/// .json), <id>_vh_clean_2.0.010000.segs.json and optionally <id>.txt (axisAlignment). Each
/// segGroup becomes an object (category from configs/scene/scannet_categories.json); walls
/// go to the walls; the floor is moved to z = 0.
Scene LoadScanNet(const std::filesystem::path& scene_dir_or_ply);

/// Options of the PartNet loader.
struct PartNetOptions {
  bool y_up_to_z_up = true;  ///< Convert PartNet's Y-up to Z-up (off for ScenePlans).
  std::string category;      ///< Category override ("" = from the root node's name).
  int points_per_part = Object::kDefaultPointsPerPart;  ///< Surface samples per part.
};

/// A PartNet object: <dir>/result.json (tree of {id, name, text, children | objs}) and
/// <dir>/objs/<name>.obj. Every leaf becomes a part named after the leaf ('_' → ' ') with the
/// leaf's id; its UniHSI key is UniHsiPartKey(part) ("seat_soft_surface16").
Object LoadPartNet(const std::filesystem::path& dir, const PartNetOptions& options = {});

/// Plan ids in a UniHSI ScenePlan JSON, in file order.
std::vector<std::string> ScenePlanIds(const std::filesystem::path& json_path);

/// One UniHSI ScenePlan: each obj {id, name, rotate [[x,y,z],...], scale, transfer} loads
/// <partnet_root>/<id> in PartNet's frame, applies each rotate entry as Rx·Ry·Rz about the
/// origin in order, scales about the vertex centroid, drops the mesh to z = 0 and adds
/// transfer. Objects are named name + key ("chair000"). Empty plan_id = the first plan.
Scene LoadScenePlan(const std::filesystem::path& json_path,
                    const std::filesystem::path& partnet_root, const std::string& plan_id = "");

/// A ScenePlan reference: "plan.json#<id>" (no "#": the first plan).
struct ScenePlanRef {
  std::filesystem::path file;  ///< The ScenePlan JSON.
  std::string id;              ///< Plan id ("" = the first).
};

/// Splits "plan.json#<id>" (a file whose name really contains '#' is taken whole).
ScenePlanRef ParseScenePlanRef(const std::string& ref);

/// PartNet folder for ScenePlans: the installed Environment's partnet_dir ($SIMS_PARTNET_DIR in
/// the apps), else data/partnet.
std::filesystem::path DefaultPartNetRoot();

/// Loads by extension and content: a built-in scene name (BuiltinSceneNames, optionally
/// "builtin:<name>"), a PartNet folder, a ScanNet folder or .ply with annotations, a 3D-FRONT
/// house .json (models in the installed Environment's future_dir, else ../3D-FUTURE-model), a
/// ScenePlan .json ("plan.json#<id>"; PartNet in DefaultPartNetRoot()), a .blend (MORSE
/// categories), or any other mesh file.
Scene LoadSceneFile(const std::string& path);

}  // namespace sims::scene
