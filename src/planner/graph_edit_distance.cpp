#include "sims/planner/graph_edit_distance.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "sims/core/error.h"

namespace sims::planner {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Stand-in for forbidden pairings inside the Hungarian matrix (must dominate every real path).
constexpr double kForbidden = 1e9;

struct Problem {
  int n1, n2;
  std::vector<std::vector<double>> sub;  // n1 × n2 (may be +inf)
  std::vector<double> del, ins;
  std::vector<std::vector<char>> a1, a2;
  double er, ei;
};

Problem MakeProblem(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& c) {
  SIMS_CHECK_MSG(c.substitute && c.remove && c.insert, "EditCosts needs all three node costs");
  Problem p;
  p.n1 = g1.size();
  p.n2 = g2.size();
  p.sub.assign(p.n1, std::vector<double>(p.n2, kInf));
  for (int i = 0; i < p.n1; ++i)
    for (int j = 0; j < p.n2; ++j) {
      double s = c.substitute(g1.nodes[i], g2.nodes[j]);
      p.sub[i][j] = s >= kForbidden ? kInf : s;  // huge costs mean "never"
    }
  for (int i = 0; i < p.n1; ++i) p.del.push_back(c.remove(g1.nodes[i]));
  for (int j = 0; j < p.n2; ++j) p.ins.push_back(c.insert(g2.nodes[j]));
  p.a1 = g1.Adjacency();
  p.a2 = g2.Adjacency();
  p.er = c.edge_remove;
  p.ei = c.edge_insert;
  return p;
}

double PathCost(const Problem& p, const std::vector<int>& f) {
  double cost = 0.0;
  std::vector<char> used(p.n2, 0);
  for (int i = 0; i < p.n1; ++i) {
    if (f[i] >= 0) {
      cost += p.sub[i][f[i]];
      used[f[i]] = 1;
    } else {
      cost += p.del[i];
    }
  }
  for (int j = 0; j < p.n2; ++j)
    if (!used[j]) cost += p.ins[j];
  for (int i = 0; i < p.n1; ++i)
    for (int k = i + 1; k < p.n1; ++k) {
      bool e1 = p.a1[i][k];
      bool e2 = f[i] >= 0 && f[k] >= 0 && p.a2[f[i]][f[k]];
      if (e1 && !e2) cost += p.er;
      if (!e1 && e2) cost += p.ei;
    }
  for (int a = 0; a < p.n2; ++a)
    for (int b = a + 1; b < p.n2; ++b)
      if (p.a2[a][b] && (!used[a] || !used[b])) cost += p.ei;
  return cost;
}

GedResult Bipartite(const Problem& p) {
  // Riesen–Bunke square matrix: [sub | del-diagonal; ins-diagonal | 0]; the local edge cost of a
  // substitution is the optimal matching of incident (unlabelled) edges, i.e. the degree
  // difference, halved because each edge is seen from both ends.
  const int n = p.n1 + p.n2;
  GedResult r;
  r.mapping.assign(p.n1, -1);
  if (n == 0) {
    r.cost = 0.0;
    return r;
  }
  std::vector<int> deg1(p.n1, 0), deg2(p.n2, 0);
  for (int i = 0; i < p.n1; ++i) deg1[i] = std::accumulate(p.a1[i].begin(), p.a1[i].end(), 0);
  for (int j = 0; j < p.n2; ++j) deg2[j] = std::accumulate(p.a2[j].begin(), p.a2[j].end(), 0);
  std::vector<std::vector<double>> m(n, std::vector<double>(n, kForbidden));
  for (int i = 0; i < p.n1; ++i) {
    for (int j = 0; j < p.n2; ++j) {
      if (std::isinf(p.sub[i][j])) continue;
      double edges =
          0.5 * (deg1[i] > deg2[j] ? (deg1[i] - deg2[j]) * p.er : (deg2[j] - deg1[i]) * p.ei);
      m[i][j] = p.sub[i][j] + edges;
    }
    m[i][p.n2 + i] = p.del[i] + 0.5 * deg1[i] * p.er;
  }
  for (int j = 0; j < p.n2; ++j) {
    m[p.n1 + j][j] = p.ins[j] + 0.5 * deg2[j] * p.ei;
    for (int i = 0; i < p.n1; ++i) m[p.n1 + j][p.n2 + i] = 0.0;
  }
  std::vector<int> assign = HungarianAssignment(m);
  for (int i = 0; i < p.n1; ++i) r.mapping[i] = assign[i] < p.n2 ? assign[i] : -1;
  r.cost = PathCost(p, r.mapping);
  return r;
}

class BranchAndBound {
 public:
  BranchAndBound(const Problem& p, int64_t budget) : p_(p), budget_(budget) {
    // Most constrained first: high degree, then few finite substitutions.
    order_.resize(p.n1);
    std::iota(order_.begin(), order_.end(), 0);
    std::vector<int> deg(p.n1), options(p.n1);
    for (int i = 0; i < p.n1; ++i) {
      deg[i] = std::accumulate(p.a1[i].begin(), p.a1[i].end(), 0);
      options[i] = static_cast<int>(
          std::count_if(p.sub[i].begin(), p.sub[i].end(), [](double c) { return !std::isinf(c); }));
    }
    std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
      return deg[a] != deg[b] ? deg[a] > deg[b] : options[a] < options[b];
    });
    // Candidates per node: finite substitutions by cost, deletion included as -1.
    cands_.resize(p.n1);
    for (int i = 0; i < p.n1; ++i) {
      std::vector<std::pair<double, int>> c;
      for (int j = 0; j < p.n2; ++j)
        if (!std::isinf(p.sub[i][j])) c.push_back({p.sub[i][j], j});
      c.push_back({p.del[i], -1});
      std::stable_sort(c.begin(), c.end());
      for (auto& [cost, j] : c) cands_[i].push_back(j);
    }
    ins_sorted_.resize(p.n2);
    std::iota(ins_sorted_.begin(), ins_sorted_.end(), 0);
    std::stable_sort(ins_sorted_.begin(), ins_sorted_.end(),
                     [&](int a, int b) { return p.ins[a] < p.ins[b]; });
    f_.assign(p.n1, -1);
    used_.assign(p.n2, 0);
  }

  GedResult Solve(const GedResult& upper) {
    best_ = upper;
    best_.exact = false;
    best_cost_ = upper.cost + 1e-12;
    Search(0, 0.0);
    best_.exact = !exhausted_;
    best_.expansions = expansions_;
    best_.cost = PathCost(p_, best_.mapping);
    return best_;
  }

 private:
  double LowerBound(int depth, double g) const {
    double lb = g;
    for (int d = depth; d < p_.n1; ++d) {
      int i = order_[d];
      double m = p_.del[i];
      for (int j = 0; j < p_.n2; ++j)
        if (!used_[j] && p_.sub[i][j] < m) m = p_.sub[i][j];
      lb += m;
    }
    int unused = 0;
    for (int j = 0; j < p_.n2; ++j) unused += !used_[j];
    int surplus = unused - (p_.n1 - depth);
    for (int k = 0, taken = 0; taken < surplus && k < p_.n2; ++k) {
      int j = ins_sorted_[k];
      if (used_[j]) continue;
      lb += p_.ins[j];
      ++taken;
    }
    return lb;
  }

  double Added(int depth, int i, int j) const {
    double c = j >= 0 ? p_.sub[i][j] : p_.del[i];
    for (int d = 0; d < depth; ++d) {
      int k = order_[d];
      bool e1 = p_.a1[i][k];
      bool e2 = j >= 0 && f_[k] >= 0 && p_.a2[j][f_[k]];
      if (e1 && !e2) c += p_.er;
      if (!e1 && e2) c += p_.ei;
    }
    return c;
  }

  double Completion() const {
    double c = 0.0;
    for (int j = 0; j < p_.n2; ++j)
      if (!used_[j]) c += p_.ins[j];
    for (int a = 0; a < p_.n2; ++a)
      for (int b = a + 1; b < p_.n2; ++b)
        if (p_.a2[a][b] && (!used_[a] || !used_[b])) c += p_.ei;
    return c;
  }

  void Search(int depth, double g) {
    if (exhausted_) return;
    if (++expansions_ > budget_) {
      exhausted_ = true;
      return;
    }
    if (depth == p_.n1) {
      double total = g + Completion();
      if (total < best_cost_) {
        best_cost_ = total;
        best_.mapping = f_;
        best_.cost = total;
      }
      return;
    }
    if (LowerBound(depth, g) >= best_cost_) return;
    int i = order_[depth];
    for (int j : cands_[i]) {
      if (j >= 0 && used_[j]) continue;
      double add = Added(depth, i, j);
      if (g + add >= best_cost_) continue;
      f_[i] = j;
      if (j >= 0) used_[j] = 1;
      Search(depth + 1, g + add);
      if (j >= 0) used_[j] = 0;
      f_[i] = -1;
      if (exhausted_) return;
    }
  }

  const Problem& p_;
  int64_t budget_;
  int64_t expansions_ = 0;
  bool exhausted_ = false;
  std::vector<int> order_, ins_sorted_;
  std::vector<std::vector<int>> cands_;
  std::vector<int> f_;
  std::vector<char> used_;
  GedResult best_;
  double best_cost_ = kInf;
};

}  // namespace

EditCosts EditCosts::Uniform() {
  EditCosts c;
  c.substitute = [](const GraphNode& a, const GraphNode& b) {
    return a.category == b.category ? 0.0 : 1.0;
  };
  c.remove = [](const GraphNode&) { return 1.0; };
  c.insert = [](const GraphNode&) { return 1.0; };
  return c;
}

std::vector<int> HungarianAssignment(const std::vector<std::vector<double>>& a) {
  const int n = static_cast<int>(a.size());
  if (n == 0) return {};
  const int m = static_cast<int>(a[0].size());
  SIMS_CHECK_MSG(n <= m, "HungarianAssignment needs rows <= columns");
  // Shortest augmenting paths with potentials u (rows) and v (columns), 1-based; column 0 is a
  // virtual column that holds the row being inserted.
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(m + 1, kInf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      int i0 = p[j0], j1 = 0;
      double delta = kInf;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        double cur = a[i0 - 1][j - 1] - u[i0] - v[j];
        if (cur < minv[j]) {
          minv[j] = cur;
          way[j] = j0;
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> row_to_col(n, -1);
  for (int j = 1; j <= m; ++j)
    if (p[j] != 0) row_to_col[p[j] - 1] = j - 1;
  return row_to_col;
}

double EditPathCost(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& costs,
                    const std::vector<int>& mapping) {
  SIMS_CHECK(static_cast<int>(mapping.size()) == g1.size());
  return PathCost(MakeProblem(g1, g2, costs), mapping);
}

GedResult BipartiteGed(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& costs) {
  GedResult r = Bipartite(MakeProblem(g1, g2, costs));
  r.exact = false;
  return r;
}

GedResult ExactGed(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& costs,
                   int64_t max_expansions) {
  Problem p = MakeProblem(g1, g2, costs);
  GedResult upper = Bipartite(p);
  BranchAndBound bb(p, max_expansions);
  return bb.Solve(upper);
}

GedResult GraphEditDistance(const SceneGraph& g1, const SceneGraph& g2, const EditCosts& costs,
                            const GedOptions& options) {
  if (g1.size() <= options.exact_max_nodes && g2.size() <= options.exact_max_target_nodes)
    return ExactGed(g1, g2, costs, options.max_expansions);
  return BipartiteGed(g1, g2, costs);
}

}  // namespace sims::planner
