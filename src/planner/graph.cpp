#include "sims/planner/graph.h"

#include <algorithm>

namespace sims::planner {

void SceneGraph::AddEdge(int i, int j) {
  if (i == j) return;
  if (i > j) std::swap(i, j);
  if (!HasEdge(i, j)) edges.emplace_back(i, j);
}

bool SceneGraph::HasEdge(int i, int j) const {
  if (i > j) std::swap(i, j);
  return std::find(edges.begin(), edges.end(), std::make_pair(i, j)) != edges.end();
}

int SceneGraph::Degree(int i) const {
  return static_cast<int>(std::count_if(
      edges.begin(), edges.end(), [i](const auto& e) { return e.first == i || e.second == i; }));
}

std::vector<std::vector<char>> SceneGraph::Adjacency() const {
  std::vector<std::vector<char>> a(nodes.size(), std::vector<char>(nodes.size(), 0));
  for (const auto& [i, j] : edges) a[i][j] = a[j][i] = 1;
  return a;
}

}  // namespace sims::planner
