// Scene graphs (SIMS scene retrieval). A layout's graph has one node per furniture object
// (canonical category, instance) and an edge between two objects whose footprints are within
// `max_edge_distance` of each other and that see each other at `sight_height` (line of sight
// through scene::RayCaster::Occluded; walls and tall furniture cut edges). Lamps, vases and
// other decor are less important nodes (cheap to add or miss).
//
// A script's required graph is built from its keyframes: every object a keyframe touches or
// walks to becomes a node (node categorisation), consecutive objects within one short script
// are joined (edge integration: they are used together, so they should be near each other), and
// short scripts are merged greedily: per category the merged graph keeps the largest number of
// distinct instances any one short script uses (node consolidation).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/core/config.h"
#include "sims/planner/composer.h"
#include "sims/planner/graph.h"
#include "sims/planner/graph_edit_distance.h"
#include "sims/planner/vocabulary.h"
#include "sims/scene/scene.h"

namespace sims::planner {

/// Line-of-sight test between two world points: true when nothing blocks the segment.
using LineOfSight = std::function<bool(const Eigen::Vector3d& a, const Eigen::Vector3d& b)>;

/// Scene-graph construction settings.
struct SceneGraphConfig {
  double max_edge_distance = 1.5;  ///< Largest footprint-to-footprint gap of an edge (m).
  double sight_height = 0.9;       ///< Height of the line-of-sight segment (m).
  std::vector<std::string> ignore_categories = {"wall", "floor",  "ceiling", "door", "window",
                                                "rug",  "carpet", "curtain"};  ///< Not nodes.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(max_edge_distance));
    a->Visit(SIMS_NVP(sight_height));
    a->Visit(SIMS_NVP(ignore_categories));
  }
  /// Positive distances.
  void Validate() const;
};

/// Costs of matching a required graph against a layout graph.
struct MatchCostConfig {
  double missing_node = 1.0;          ///< A required object with no counterpart.
  double extra_node = 0.02;           ///< A layout object the script does not use.
  double missing_edge = 0.3;          ///< Two objects used together that are not near each other.
  double extra_edge = 0.0;            ///< Layout adjacency the script does not need.
  double unimportant_weight = 0.3;    ///< Scales node costs of lamps, vases, decor.
  double room_mismatch = 0.3;         ///< Per short script whose room type the layout lacks.
  double node_room_mismatch = 0.1;    ///< An object used in a room of another type.
  double composition_penalty = 0.25;  ///< Added to a multi-room composition's cost.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(missing_node));
    a->Visit(SIMS_NVP(extra_node));
    a->Visit(SIMS_NVP(missing_edge));
    a->Visit(SIMS_NVP(extra_edge));
    a->Visit(SIMS_NVP(unimportant_weight));
    a->Visit(SIMS_NVP(room_mismatch));
    a->Visit(SIMS_NVP(node_room_mismatch));
    a->Visit(SIMS_NVP(composition_penalty));
  }
  /// Non-negative costs.
  void Validate() const;
};

/// Edit costs for retrieval: same category free, substitution classes at their table cost,
/// anything else forbidden, plus `node_room_mismatch` when both nodes know their room types and
/// share none; deletions/insertions from `config`, scaled for unimportant nodes.
EditCosts RetrievalCosts(const MatchCostConfig& config,
                         const Vocabulary& vocab = Vocabulary::Default());

/// Canonical category of a scene object ("couch" → "sofa", unknown names lower-cased).
std::string CanonicalCategory(const std::string& category,
                              const Vocabulary& vocab = Vocabulary::Default());

/// The default line of sight of a scene: scene::RayCaster when the scene module is built,
/// otherwise segment tests against wall triangles and object bounding boxes.
LineOfSight DefaultLineOfSight(const scene::Scene& scene);

/// Builds the graph of a scene (objects whose `room` is in `rooms` when that list is non-empty).
SceneGraph BuildSceneGraph(const scene::Scene& scene, const SceneGraphConfig& config = {},
                           const Vocabulary& vocab = Vocabulary::Default(),
                           const LineOfSight& line_of_sight = {},
                           const std::vector<std::string>& rooms = {});

/// A script's required graph and where each keyframe lands in it.
struct RequiredGraph {
  SceneGraph graph;                ///< Consolidated required graph.
  std::vector<int> keyframe_node;  ///< Per keyframe of the long script: node index, or -1 (floor).
};

/// Builds the required graph of the keyframes whose segment is in `segments` (all if empty).
RequiredGraph BuildRequiredGraph(const LongScript& script, const std::vector<int>& segments = {},
                                 const Vocabulary& vocab = Vocabulary::Default());

/// Axis-aligned bounds of an object computed from its part meshes and points.
scene::Aabb ObjectBounds(const scene::Object& object);

}  // namespace sims::planner
