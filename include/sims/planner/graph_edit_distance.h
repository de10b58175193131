// Graph edit distance between a script's required graph G1 and a layout graph G2 (SIMS scene
// retrieval). Costs are arbitrary non-negative functions, so the same code computes textbook GED
// (uniform costs) and the asymmetric retrieval cost (a missing sofa is expensive, an extra lamp
// nearly free, a stool may stand in for a chair at a price).
//
// ExactGed is a depth-first branch and bound over assignments of G1's nodes (to a G2 node or to
// deletion) with an admissible bound (node costs of the unassigned nodes + the cheapest forced
// insertions), seeded with the bipartite upper bound. BipartiteGed is the Riesen–Bunke
// approximation: a Hungarian assignment on node costs plus local edge (degree) costs; the cost
// of the edit path it induces is evaluated exactly, so it is an upper bound: approx ≥ exact.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "sims/planner/graph.h"

namespace sims::planner {

/// Edit operation costs. Substitution may return +infinity to forbid a pairing.
struct EditCosts {
  /// Cost of mapping node a of G1 onto node b of G2.
  std::function<double(const GraphNode& a, const GraphNode& b)> substitute;
  /// Cost of deleting node a of G1 (it has no counterpart).
  std::function<double(const GraphNode& a)> remove;
  /// Cost of inserting node b of G2 (nothing maps onto it).
  std::function<double(const GraphNode& b)> insert;
  double edge_remove = 1.0;  ///< An edge of G1 whose image is not an edge of G2.
  double edge_insert = 1.0;  ///< An edge of G2 that is not the image of an edge of G1.

  /// Textbook unit costs: label mismatch 1, node deletion/insertion 1, edge deletion/insertion 1.
  static EditCosts Uniform();
};

/// Result of a GED computation.
struct GedResult {
  double cost = std::numeric_limits<double>::infinity();  ///< Edit path cost.
  std::vector<int> mapping;  ///< G1 node → G2 node, or -1 for deleted nodes.
  bool exact = false;        ///< True when the search proved optimality.
  int64_t expansions = 0;    ///< Search nodes expanded (exact search only).
};

/// Exact GED by branch and bound; gives up after `max_expansions` (then `exact` is false and the
/// best path found so far is returned).
GedResult ExactGed(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& costs,
                   int64_t max_expansions = 2'000'000);

/// Bipartite (Hungarian) approximation; an upper bound of the exact GED.
GedResult BipartiteGed(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& costs);

/// Exact when G1 has at most `exact_max_nodes` nodes and G2 at most `exact_max_target_nodes`,
/// otherwise (or when the exact search runs out of budget) the better of the two paths.
struct GedOptions {
  int exact_max_nodes = 10;            ///< Largest G1 solved exactly.
  int exact_max_target_nodes = 80;     ///< Largest G2 solved exactly.
  int64_t max_expansions = 2'000'000;  ///< Exact search budget.
};

/// GED with the strategy chosen by size.
GedResult GraphEditDistance(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& costs,
                            const GedOptions& options = {});

/// Exact cost of the edit path induced by a node mapping (G1 → G2 or -1).
double EditPathCost(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& costs,
                    const std::vector<int>& mapping);

/// Minimum-cost assignment of rows to distinct columns (rows ≤ columns), Hungarian algorithm
/// O(n²m); entries must be finite. Returns the column of each row.
std::vector<int> HungarianAssignment(const std::vector<std::vector<double>>& cost);

}  // namespace sims::planner
