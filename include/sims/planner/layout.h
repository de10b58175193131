// Layout retrieval (SIMS scene matching): a database of layout scene graphs (built-in rooms and
// house, the MORSE apartment, 3D-FRONT houses and their rooms), graph-edit-distance matching of
// a script's required graph against every layout, multi-room composition when no single layout
// fits (rooms of different types placed side by side with walls and door openings), binding of
// every keyframe to an object instance, and materialisation of the chosen layout as a scene.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/planner/composer.h"
#include "sims/planner/plan.h"
#include "sims/planner/scene_graph.h"
#include "sims/scene/scene.h"

namespace sims::planner {

/// A node of a stored layout graph.
struct LayoutNode {
  std::string category;                     ///< Canonical category.
  std::string instance;                     ///< Object instance in the source scene.
  bool important = true;                    ///< Scene-graph importance.
  std::array<double, 3> position{0, 0, 0};  ///< Bounds centre (source coordinates).
  std::array<double, 4> box{0, 0, 0, 0};    ///< Footprint xmin, ymin, xmax, ymax.
  std::string room;                         ///< Room id in the source scene.
  std::string room_type;                    ///< Canonical type of that room ("" if unknown).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(category));
    a->Visit(SIMS_NVP(instance));
    a->Visit(SIMS_NVP(important));
    a->Visit(SIMS_NVP(position));
    a->Visit(SIMS_NVP(box));
    a->Visit(SIMS_NVP(room));
    a->Visit(SIMS_NVP(room_type));
  }
};

/// One layout: a whole scene or one room of it.
struct LayoutEntry {
  std::string name;                             ///< Display name ("builtin house / bedroom").
  LayoutSource source;                          ///< How to load it.
  std::vector<std::string> room_types;          ///< Canonical room types it contains.
  std::array<double, 4> footprint{0, 0, 0, 0};  ///< xmin, ymin, xmax, ymax (source coordinates).
  std::vector<LayoutNode> nodes;                ///< Furniture nodes.
  std::vector<std::array<int, 2>> edges;        ///< Undirected edges (node indices).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(source));
    a->Visit(SIMS_NVP(room_types));
    a->Visit(SIMS_NVP(footprint));
    a->Visit(SIMS_NVP(nodes));
    a->Visit(SIMS_NVP(edges));
  }
  /// Edge indices in range.
  void Validate() const;
  /// The layout as a scene graph.
  SceneGraph Graph() const;
  /// True for a single room (usable in multi-room composition).
  bool IsSingleRoom() const { return room_types.size() == 1; }
};

/// The layout database file written by apps/index_layouts.
struct LayoutDatabase {
  int version = 1;                   ///< Schema version.
  std::vector<LayoutEntry> layouts;  ///< Entries.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(version));
    a->Visit(SIMS_NVP(layouts));
  }
  /// Version 1.
  void Validate() const;
  /// Reads a database file (errors name the file and field).
  static LayoutDatabase Load(const std::filesystem::path& path);
  /// Writes it atomically.
  void Save(const std::filesystem::path& path) const;
};

/// Walls and doors of composed layouts.
struct CompositionConfig {
  double wall_thickness = 0.1;  ///< Wall thickness (m).
  double wall_height = 2.5;     ///< Wall height (m).
  double door_width = 1.0;      ///< Opening width (m).
  double door_clearance = 0.8;  ///< Free depth required on both sides of a door (m).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(wall_thickness));
    a->Visit(SIMS_NVP(wall_height));
    a->Visit(SIMS_NVP(door_width));
    a->Visit(SIMS_NVP(door_clearance));
  }
  /// Positive sizes.
  void Validate() const;
};

/// Everything layout retrieval needs.
struct LayoutConfig {
  SceneGraphConfig graph;            ///< Scene-graph construction.
  MatchCostConfig costs;             ///< Matching costs.
  CompositionConfig composition;     ///< Walls and doors.
  int exact_max_nodes = 10;          ///< Required graphs up to this size are matched exactly.
  int exact_max_target_nodes = 80;   ///< Layouts up to this size are matched exactly.
  int64_t max_expansions = 2000000;  ///< Exact search budget per match.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(graph));
    a->Visit(SIMS_NVP(costs));
    a->Visit(SIMS_NVP(composition));
    a->Visit(SIMS_NVP(exact_max_nodes));
    a->Visit(SIMS_NVP(exact_max_target_nodes));
    a->Visit(SIMS_NVP(max_expansions));
  }
  /// Non-negative limits.
  void Validate() const;
  /// The GED options these fields describe.
  GedOptions Ged() const;
};

/// Entries for a scene: the whole scene, plus one entry per room when it has several rooms.
/// Edges are computed once on the whole scene (walls between rooms cut them).
std::vector<LayoutEntry> MakeLayoutEntries(const scene::Scene& scene, const LayoutSource& source,
                                           const SceneGraphConfig& config = {},
                                           const Vocabulary& vocab = Vocabulary::Default(),
                                           const LineOfSight& line_of_sight = {});

/// A room to compose: its footprint and furniture footprints in source coordinates.
struct RoomPiece {
  std::string id;                                ///< Room id in the composed layout.
  std::array<double, 4> footprint{0, 0, 0, 0};   ///< xmin, ymin, xmax, ymax.
  std::vector<std::array<double, 4>> obstacles;  ///< Furniture footprints.
};

/// Result of ComposeRooms.
struct Composition {
  std::vector<std::array<double, 3>> offsets;     ///< Translation per room.
  std::vector<std::array<double, 4>> footprints;  ///< Room footprints after the offset.
  std::vector<PlanWall> walls;                    ///< Outer walls and shared walls with gaps.
  std::vector<PlanDoor> doors;                    ///< One opening per pair of neighbours.
};

/// Places rooms side by side along +x (bottoms aligned at y = 0, one wall thickness apart),
/// walls every room in and opens a door in each shared wall where no furniture blocks it.
Composition ComposeRooms(const std::vector<RoomPiece>& rooms, const CompositionConfig& config = {});

/// Binding of one keyframe.
struct Binding {
  std::string object;           ///< Bound instance ("" = none).
  std::string object_category;  ///< Its category.
  std::string room;             ///< Room id.
  bool placed = false;          ///< Bound, or a free walk.
  std::string note;             ///< Substitution / failure explanation.
};

/// A layout choice and the keyframe bindings it implies.
struct LayoutMatch {
  PlanLayout layout;                  ///< The layout recipe.
  std::vector<Binding> bindings;      ///< One per keyframe of the long script.
  std::vector<std::string> warnings;  ///< Unplaced keyframes and other problems.
};

/// Matches a long script against every layout (and against multi-room compositions of single
/// rooms, one per room type the script visits) and binds its keyframes. Throws sims::Error if
/// the database is empty.
LayoutMatch MatchLayouts(const LongScript& script, const LayoutDatabase& db,
                         const LayoutConfig& config = {},
                         const Vocabulary& vocab = Vocabulary::Default());

/// Binds a long script to a scene the caller chose (mode "given").
LayoutMatch MatchScene(const LongScript& script, const scene::Scene& scene,
                       const LayoutConfig& config = {},
                       const Vocabulary& vocab = Vocabulary::Default(),
                       const LineOfSight& line_of_sight = {});

/// Loads the scene a layout source names.
using SceneLoader = std::function<scene::Scene(const LayoutSource&)>;

/// The scene module's loaders (built-in scenes, MORSE, 3D-FRONT, scene files); throws
/// sims::Error for kind "given" and when the planner was built without the scene module.
SceneLoader DefaultSceneLoader();

/// Builds the scene of a plan layout: single layouts load their source (only the room's
/// objects when a room id is set); composed layouts load each room, move its objects by the
/// offset, rename them "<room id>/<instance>" and build the plan's walls.
scene::Scene MaterializeLayout(const PlanLayout& layout,
                               const SceneLoader& loader = DefaultSceneLoader());

/// Indexes the built-in rooms and house, the MORSE apartment (if `morse`; skipped with a warning
/// when its data is missing) and every 3D-FRONT house JSON in `front3d_dirs` (models in
/// `future_dir`). Returns the database and appends human-readable remarks to `log`.
LayoutDatabase BuildLayoutDatabase(bool builtin, bool morse,
                                   const std::vector<std::filesystem::path>& front3d_dirs,
                                   const std::filesystem::path& future_dir,
                                   const LayoutConfig& config, std::vector<std::string>* log,
                                   const Vocabulary& vocab = Vocabulary::Default());

}  // namespace sims::planner
