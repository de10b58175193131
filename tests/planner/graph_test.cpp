// Graph edit distance: exact values on hand-made graphs, approximation ≥ exact, Hungarian.
#include "sims/planner/graph_edit_distance.h"

#include <algorithm>
#include <functional>

#include <gtest/gtest.h>

#include "sims/core/rng.h"

namespace sims::planner {
namespace {

SceneGraph MakeGraph(const std::vector<std::string>& labels,
                     const std::vector<std::pair<int, int>>& edges) {
  SceneGraph g;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    GraphNode n;
    n.category = labels[i];
    n.instance = labels[i] + std::to_string(i);
    g.nodes.push_back(n);
  }
  for (auto [a, b] : edges) g.AddEdge(a, b);
  return g;
}

// Enumerates every partial injection G1 → G2 (tiny graphs only).
double BruteForce(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& c) {
  std::vector<int> f(g1.size(), -1);
  std::vector<char> used(g2.size(), 0);
  double best = 1e300;
  std::function<void(int)> rec = [&](int i) {
    if (i == g1.size()) {
      best = std::min(best, EditPathCost(g1, g2, c, f));
      return;
    }
    f[i] = -1;
    rec(i + 1);
    for (int j = 0; j < g2.size(); ++j) {
      if (used[j]) continue;
      used[j] = 1;
      f[i] = j;
      rec(i + 1);
      used[j] = 0;
      f[i] = -1;
    }
  };
  rec(0);
  return best;
}

TEST(GraphEditDistanceTest, ZeroForIsomorphicGraphs) {
  // A 4-cycle with a chord, relabelled and permuted.
  SceneGraph a =
      MakeGraph({"sofa", "table", "chair", "lamp"}, {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}});
  SceneGraph b =
      MakeGraph({"lamp", "chair", "sofa", "table"}, {{2, 3}, {3, 1}, {1, 0}, {0, 2}, {2, 1}});
  GedResult r = ExactGed(a, b, EditCosts::Uniform());
  EXPECT_TRUE(r.exact);
  EXPECT_DOUBLE_EQ(r.cost, 0.0);
  EXPECT_EQ(r.mapping, (std::vector<int>{2, 3, 1, 0}));
  EXPECT_DOUBLE_EQ(BipartiteGed(a, b, EditCosts::Uniform()).cost, 0.0);
}

TEST(GraphEditDistanceTest, ExactValuesOnSmallGraphs) {
  EditCosts u = EditCosts::Uniform();
  SceneGraph path = MakeGraph({"x", "x", "x"}, {{0, 1}, {1, 2}});
  SceneGraph triangle = MakeGraph({"x", "x", "x"}, {{0, 1}, {1, 2}, {0, 2}});
  EXPECT_DOUBLE_EQ(ExactGed(path, triangle, u).cost, 1.0);  // one edge insertion
  EXPECT_DOUBLE_EQ(ExactGed(triangle, path, u).cost, 1.0);  // one edge deletion
  SceneGraph relabel = MakeGraph({"x", "y", "x"}, {{0, 1}, {1, 2}});
  EXPECT_DOUBLE_EQ(ExactGed(path, relabel, u).cost, 1.0);  // one substitution
  SceneGraph star = MakeGraph({"x", "x", "x", "x"}, {{0, 1}, {0, 2}, {0, 3}});
  SceneGraph path4 = MakeGraph({"x", "x", "x", "x"}, {{0, 1}, {1, 2}, {2, 3}});
  EXPECT_DOUBLE_EQ(ExactGed(star, path4, u).cost, 2.0);  // move one edge
  SceneGraph empty;
  EXPECT_DOUBLE_EQ(ExactGed(empty, path, u).cost, 5.0);  // 3 nodes + 2 edges inserted
  EXPECT_DOUBLE_EQ(ExactGed(path, empty, u).cost, 5.0);
  SceneGraph extra = MakeGraph({"x", "x", "x", "z"}, {{0, 1}, {1, 2}, {2, 3}});
  EXPECT_DOUBLE_EQ(ExactGed(path, extra, u).cost, 2.0);  // node z + its edge
  // Two disjoint edges vs a path of four: one edge moves (delete + insert) = 2... or the
  // path's middle edge is inserted and nothing else changes = 1.
  SceneGraph two = MakeGraph({"x", "x", "x", "x"}, {{0, 1}, {2, 3}});
  EXPECT_DOUBLE_EQ(ExactGed(two, path4, u).cost, 1.0);
}

TEST(GraphEditDistanceTest, ExactMatchesBruteForceAndApproximationIsAnUpperBound) {
  Rng rng(17);
  const std::vector<std::string> labels = {"a", "b", "c"};
  EditCosts c = EditCosts::Uniform();
  c.substitute = [](const GraphNode& x, const GraphNode& y) {
    return x.category == y.category ? 0.0 : (x.category == "c" || y.category == "c") ? 1e300 : 0.6;
  };
  c.remove = [](const GraphNode& x) { return x.category == "a" ? 1.0 : 0.7; };
  c.insert = [](const GraphNode&) { return 0.4; };
  c.edge_remove = 0.5;
  c.edge_insert = 0.3;
  for (int trial = 0; trial < 60; ++trial) {
    auto random_graph = [&](int n) {
      std::vector<std::string> l;
      for (int i = 0; i < n; ++i) l.push_back(labels[rng.UniformInt(3)]);
      std::vector<std::pair<int, int>> e;
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
          if (rng.Bernoulli(0.45)) e.push_back({i, j});
      return MakeGraph(l, e);
    };
    SceneGraph g1 = random_graph(1 + static_cast<int>(rng.UniformInt(4)));
    SceneGraph g2 = random_graph(1 + static_cast<int>(rng.UniformInt(5)));
    for (const EditCosts* costs : {&c}) {
      GedResult exact = ExactGed(g1, g2, *costs);
      GedResult approx = BipartiteGed(g1, g2, *costs);
      ASSERT_TRUE(exact.exact);
      EXPECT_NEAR(exact.cost, BruteForce(g1, g2, *costs), 1e-9) << "trial " << trial;
      EXPECT_GE(approx.cost, exact.cost - 1e-9) << "trial " << trial;
      EXPECT_NEAR(approx.cost, EditPathCost(g1, g2, *costs, approx.mapping), 1e-9);
    }
    GedResult u_exact = ExactGed(g1, g2, EditCosts::Uniform());
    EXPECT_NEAR(u_exact.cost, BruteForce(g1, g2, EditCosts::Uniform()), 1e-9);
    EXPECT_GE(BipartiteGed(g1, g2, EditCosts::Uniform()).cost, u_exact.cost - 1e-9);
  }
}

TEST(GraphEditDistanceTest, LargeGraphsUseTheApproximation) {
  Rng rng(5);
  SceneGraph g1, g2;
  for (int i = 0; i < 30; ++i) {
    GraphNode n;
    n.category = "c" + std::to_string(rng.UniformInt(6));
    g1.nodes.push_back(n);
    n.category = "c" + std::to_string(rng.UniformInt(6));
    g2.nodes.push_back(n);
  }
  for (int i = 0; i < 60; ++i) {
    g1.AddEdge(static_cast<int>(rng.UniformInt(30)), static_cast<int>(rng.UniformInt(30)));
    g2.AddEdge(static_cast<int>(rng.UniformInt(30)), static_cast<int>(rng.UniformInt(30)));
  }
  GedOptions opt;
  opt.exact_max_nodes = 10;
  GedResult r = GraphEditDistance(g1, g2, EditCosts::Uniform(), opt);
  EXPECT_FALSE(r.exact);
  EXPECT_NEAR(r.cost, EditPathCost(g1, g2, EditCosts::Uniform(), r.mapping), 1e-9);
  // A tiny search budget still returns a valid path, no worse than the bipartite one.
  GedResult budget = ExactGed(g1, g2, EditCosts::Uniform(), 50);
  EXPECT_FALSE(budget.exact);
  EXPECT_LE(budget.cost, BipartiteGed(g1, g2, EditCosts::Uniform()).cost + 1e-9);
}

TEST(HungarianTest, FindsTheOptimalAssignment) {
  std::vector<std::vector<double>> cost = {{4, 1, 3}, {2, 0, 5}, {3, 2, 2}};
  std::vector<int> a = HungarianAssignment(cost);
  EXPECT_EQ(a, (std::vector<int>{1, 0, 2}));  // 1 + 2 + 2 = 5
  std::vector<std::vector<double>> rect = {{7, 3, 9, 1}, {2, 8, 1, 6}};
  EXPECT_EQ(HungarianAssignment(rect), (std::vector<int>{3, 2}));
}

}  // namespace
}  // namespace sims::planner
