#include "sims/scene/mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "sims/core/error.h"

namespace sims::scene {

namespace {

// Hash of a quantised position: vertices within one quantum weld together (neighbouring
// quanta are checked too so points straddling a cell border still merge).
struct CellKey {
  int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellKeyHash {
  std::size_t operator()(const CellKey& k) const {
    uint64_t h = static_cast<uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<uint64_t>(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

int FindRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

Aabb TriangleMesh::Bounds() const {
  Aabb b;
  for (const auto& v : vertices) b.Extend(v);
  return b;
}

double TriangleMesh::Area() const {
  double a = 0;
  for (const auto& t : triangles) {
    a += 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
  }
  return a;
}

void TriangleMesh::Append(const TriangleMesh& other) {
  const int offset = static_cast<int>(vertices.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  triangles.reserve(triangles.size() + other.triangles.size());
  for (const auto& t : other.triangles) triangles.push_back(t + Eigen::Vector3i::Constant(offset));
}

void TriangleMesh::Transform(const Eigen::Affine3d& X) {
  for (auto& v : vertices) v = X * v;
  // A reflection flips the winding; keep triangles counter-clockwise seen from outside.
  if (X.linear().determinant() < 0) {
    for (auto& t : triangles) std::swap(t[1], t[2]);
  }
}

TriangleMesh TriangleMesh::Transformed(const Eigen::Affine3d& X) const {
  TriangleMesh m = *this;
  m.Transform(X);
  return m;
}

std::vector<Eigen::Vector3d> TriangleMesh::SamplePoints(int n, Rng& rng) const {
  std::vector<Eigen::Vector3d> out;
  if (n <= 0 || triangles.empty()) return out;
  std::vector<double> cdf(triangles.size());
  double total = 0;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    total += 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
    cdf[i] = total;
  }
  if (total <= 0) return out;
  out.reserve(n);
  for (int k = 0; k < n; ++k) {
    const double u = rng.Uniform() * total;
    std::size_t i = std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin();
    i = std::min(i, triangles.size() - 1);
    const auto& t = triangles[i];
    // sqrt warping makes barycentric samples uniform over the triangle.
    const double r1 = std::sqrt(rng.Uniform());
    const double r2 = rng.Uniform();
    out.push_back((1 - r1) * vertices[t[0]] + r1 * (1 - r2) * vertices[t[1]] +
                  r1 * r2 * vertices[t[2]]);
  }
  return out;
}

Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Voronoi-region walk over vertices, edges and the face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = va + vb + vc;
  if (std::abs(denom) < 1e-300) return a;  // degenerate triangle
  const double v = vb / denom, w = vc / denom;
  return a + v * ab + w * ac;
}

Eigen::Vector3d TriangleMesh::ClosestPoint(const Eigen::Vector3d& p) const {
  SIMS_CHECK_MSG(!triangles.empty(), "ClosestPoint on an empty mesh");
  Eigen::Vector3d best = vertices[triangles[0][0]];
  double best_d2 = (best - p).squaredNorm();
  for (const auto& t : triangles) {
    const Eigen::Vector3d q =
        ClosestPointOnTriangle(p, vertices[t[0]], vertices[t[1]], vertices[t[2]]);
    const double d2 = (q - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = q;
    }
  }
  return best;
}

TriangleMesh TriangleMesh::Box(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? max.x() : min.x(), (i & 2) ? max.y() : min.y(),
                            (i & 4) ? max.z() : min.z());
  }
  // Outward-facing, counter-clockwise quads split in two.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.emplace_back(q[0], q[1], q[2]);
    m.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return m;
}

TriangleMesh TriangleMesh::Cylinder(const Eigen::Vector3d& base_center, double radius,
                                    double height, int segments) {
  SIMS_CHECK(segments >= 3);
  TriangleMesh m;
  const int n = segments;
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      m.vertices.push_back(base_center +
                           Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), k * height));
    }
  }
  m.vertices.push_back(base_center);
  m.vertices.push_back(base_center + Eigen::Vector3d(0, 0, height));
  const int cb = 2 * n, ct = 2 * n + 1;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(i, j, n + j);
    m.triangles.emplace_back(i, n + j, n + i);
    m.triangles.emplace_back(cb, j, i);
    m.triangles.emplace_back(ct, n + i, n + j);
  }
  return m;
}

double TriangleMesh::SignedVolume() const {
  double v = 0;
  for (const auto& t : triangles)
    v += vertices[t[0]].dot(vertices[t[1]].cross(vertices[t[2]])) / 6.0;
  return v;
}

Eigen::Vector3d TriangleMesh::TriangleNormal(int t) const {
  const auto& tri = triangles[t];
  const Eigen::Vector3d n =
      (vertices[tri[1]] - vertices[tri[0]]).cross(vertices[tri[2]] - vertices[tri[0]]);
  const double len = n.norm();
  return len > 1e-300 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

namespace {

// Maps every vertex to a representative within `tolerance` (spatial hash over quantised
// cells; neighbouring cells are searched so points straddling a border still merge).
std::vector<int> WeldRemap(const std::vector<Eigen::Vector3d>& vertices, double tolerance,
                           std::vector<Eigen::Vector3d>* welded) {
  SIMS_CHECK(tolerance > 0);
  std::unordered_map<CellKey, std::vector<int>, CellKeyHash> grid;
  std::vector<int> remap(vertices.size());
  const double inv = 1.0 / tolerance;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Eigen::Vector3d& v = vertices[i];
    const CellKey key{static_cast<int64_t>(std::floor(v.x() * inv)),
                      static_cast<int64_t>(std::floor(v.y() * inv)),
                      static_cast<int64_t>(std::floor(v.z() * inv))};
    int found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          auto it = grid.find({key.x + dx, key.y + dy, key.z + dz});
          if (it == grid.end()) continue;
          for (int j : it->second) {
            if (((*welded)[j] - v).squaredNorm() <= tolerance * tolerance) {
              found = j;
              break;
            }
          }
        }
    if (found < 0) {
      found = static_cast<int>(welded->size());
      welded->push_back(v);
      grid[key].push_back(found);
    }
    remap[i] = found;
  }
  return remap;
}

uint64_t EdgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b);
}

// Unions triangles across edges used by exactly two triangles (manifold edges).
void UnionManifoldEdges(const std::vector<Eigen::Vector3i>& triangles, const std::vector<int>& map,
                        const std::vector<uint8_t>& skip, std::vector<int>* parent) {
  std::vector<std::pair<uint64_t, int>> edges;
  edges.reserve(triangles.size() * 3);
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    if (skip[t]) continue;
    for (int e = 0; e < 3; ++e)
      edges.emplace_back(EdgeKey(map[triangles[t][e]], map[triangles[t][(e + 1) % 3]]), t);
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i == 2) {
      const int a = FindRoot(*parent, edges[i].second), b = FindRoot(*parent, edges[i + 1].second);
      if (a != b) (*parent)[std::max(a, b)] = std::min(a, b);
    }
    i = j;
  }
}

}  // namespace

TriangleMesh TriangleMesh::Welded(double tolerance) const {
  TriangleMesh out;
  const std::vector<int> remap = WeldRemap(vertices, tolerance, &out.vertices);
  out.triangles.reserve(triangles.size());
  for (const auto& t : triangles) {
    const Eigen::Vector3i r(remap[t[0]], remap[t[1]], remap[t[2]]);
    if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2]) continue;
    out.triangles.push_back(r);
  }
  return out;
}

std::vector<TriangleMesh> TriangleMesh::EdgeConnectedComponents(double tolerance) const {
  std::vector<Eigen::Vector3d> welded;
  const std::vector<int> remap = WeldRemap(vertices, tolerance, &welded);
  const int nt = static_cast<int>(triangles.size());
  std::vector<uint8_t> degenerate(nt, 0);
  for (int t = 0; t < nt; ++t) {
    const Eigen::Vector3i r(remap[triangles[t][0]], remap[triangles[t][1]], remap[triangles[t][2]]);
    degenerate[t] = r[0] == r[1] || r[1] == r[2] || r[0] == r[2];
  }
  std::vector<int> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  // Connectivity through the mesh's own indices (keeps a primitive together) and through
  // welded positions (joins faces exporters wrote with duplicated vertices); in both only
  // manifold edges connect, so solids that merely touch along an edge or a face stay apart.
  std::vector<int> identity(vertices.size());
  std::iota(identity.begin(), identity.end(), 0);
  UnionManifoldEdges(triangles, identity, degenerate, &parent);
  UnionManifoldEdges(triangles, remap, degenerate, &parent);
  std::unordered_map<int, int> component_of_root;
  std::vector<TriangleMesh> out;
  std::vector<std::unordered_map<int, int>> vertex_maps;
  for (int t = 0; t < nt; ++t) {
    if (degenerate[t]) continue;
    const int root = FindRoot(parent, t);
    auto [it, inserted] = component_of_root.emplace(root, static_cast<int>(out.size()));
    if (inserted) {
      out.emplace_back();
      vertex_maps.emplace_back();
    }
    TriangleMesh& m = out[it->second];
    auto& vmap = vertex_maps[it->second];
    Eigen::Vector3i tri;
    for (int k = 0; k < 3; ++k) {
      const int v = remap[triangles[t][k]];
      auto [vit, vinserted] = vmap.emplace(v, static_cast<int>(m.vertices.size()));
      if (vinserted) m.vertices.push_back(welded[v]);
      tri[k] = vit->second;
    }
    m.triangles.push_back(tri);
  }
  return out;
}

bool TriangleMesh::IsClosed(double tolerance) const {
  const TriangleMesh w = Welded(tolerance);
  if (w.triangles.empty()) return false;
  std::unordered_map<uint64_t, int> count;
  for (const auto& t : w.triangles)
    for (int e = 0; e < 3; ++e) ++count[EdgeKey(t[e], t[(e + 1) % 3])];
  for (const auto& [key, c] : count)
    if (c != 2) return false;
  return true;
}

}  // namespace sims::scene
