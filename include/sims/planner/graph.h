// Undirected labelled graphs used for scene-graph matching: nodes are furniture (category,
// instance), edges join objects that are near each other and mutually visible.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sims/planner/vocabulary.h"

namespace sims::planner {

/// One furniture node.
struct GraphNode {
  std::string category;                                ///< Canonical category (the label).
  std::string instance;                                ///< Object instance id (or "sofa#0").
  bool important = true;                               ///< Lamps, vases, decor: false.
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< Bounds centre (world).
  std::string room;                                    ///< Room id ("" if none).
  std::vector<std::string> room_types;                 ///< Room type(s) of the node.
  /// Skills a script performs on it (required graphs; scene graphs leave it empty): a
  /// substitute must afford each.
  std::vector<Skill> uses;
};

/// An undirected simple graph.
struct SceneGraph {
  std::string name;                        ///< Layout or script name, for messages.
  std::vector<GraphNode> nodes;            ///< Nodes.
  std::vector<std::pair<int, int>> edges;  ///< Undirected edges (i < j), no duplicates.

  /// Adds edge {i, j} unless present or i == j.
  void AddEdge(int i, int j);
  /// True when {i, j} is an edge.
  bool HasEdge(int i, int j) const;
  /// Number of edges at node i.
  int Degree(int i) const;
  /// Dense adjacency matrix (nodes × nodes, 0/1).
  std::vector<std::vector<char>> Adjacency() const;
  /// Number of nodes.
  int size() const { return static_cast<int>(nodes.size()); }
};

}  // namespace sims::planner
