#include "sims/scene/voxels.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "sims/core/error.h"

namespace sims::scene {

namespace {

using Eigen::Vector3d;

// Separating-axis test of a triangle against an axis-aligned box (centre c, half size h).
bool TriangleOverlapsBox(const Vector3d& c, const Vector3d& h, const Vector3d& a0,
                         const Vector3d& a1, const Vector3d& a2) {
  const Vector3d v0 = a0 - c, v1 = a1 - c, v2 = a2 - c;
  // Box face normals.
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({v0[k], v1[k], v2[k]}), hi = std::max({v0[k], v1[k], v2[k]});
    if (lo > h[k] || hi < -h[k]) return false;
  }
  const Vector3d e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
  // Triangle plane.
  const Vector3d n = e0.cross(e1);
  const double r_plane = h.dot(n.cwiseAbs());
  if (std::abs(n.dot(v0)) > r_plane) return false;
  // Edge × box-axis cross products.
  const Vector3d edges[3] = {e0, e1, e2};
  for (const Vector3d& e : edges) {
    for (int k = 0; k < 3; ++k) {
      Vector3d axis = Vector3d::Zero();
      axis[k] = 1;
      const Vector3d a = axis.cross(e);
      if (a.squaredNorm() < 1e-24) continue;
      const double p0 = a.dot(v0), p1 = a.dot(v1), p2 = a.dot(v2);
      const double r = h.dot(a.cwiseAbs());
      if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
    }
  }
  return true;
}

// Solid angle of triangle (a, b, c) seen from the origin (Van Oosterom–Strackee).
double SolidAngle(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double num = a.dot(b.cross(c));
  const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2.0 * std::atan2(num, den);
}

}  // namespace

bool VoxelGrid::Occupied(const Eigen::Vector3d& p) const {
  const Vector3d q = (p - origin) / resolution;
  return At(static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y())),
            static_cast<int>(std::floor(q.z())));
}

Aabb VoxelGrid::Bounds() const {
  Aabb b;
  b.min = origin;
  b.max = origin + resolution * dims.cast<double>();
  return b;
}

int64_t VoxelGrid::Count() const {
  return std::count_if(cells.begin(), cells.end(), [](uint8_t c) { return c != 0; });
}

VoxelGrid VoxelizeSolid(const TriangleMesh& mesh, double resolution) {
  SIMS_CHECK(resolution > 0);
  VoxelGrid g;
  g.resolution = resolution;
  if (mesh.empty()) return g;
  const Aabb b = mesh.Bounds();
  // A tiny irrational shift keeps axis-aligned faces off cell borders, so a face marks one
  // layer of cells instead of two.
  const Vector3d shift = Vector3d::Constant(0.0137 * resolution);
  g.origin = b.min - Vector3d::Constant(resolution) - shift;
  const Vector3d size = b.max - g.origin + Vector3d::Constant(resolution);
  for (int k = 0; k < 3; ++k)
    g.dims[k] = std::max(1, static_cast<int>(std::ceil(size[k] / resolution)));
  const int64_t n = static_cast<int64_t>(g.dims.x()) * g.dims.y() * g.dims.z();
  g.cells.assign(n, 0);
  const Vector3d half = Vector3d::Constant(0.5 * resolution * (1 + 1e-9));
  for (const auto& t : mesh.triangles) {
    const Vector3d& a = mesh.vertices[t[0]];
    const Vector3d& bb = mesh.vertices[t[1]];
    const Vector3d& c = mesh.vertices[t[2]];
    const Vector3d lo = a.cwiseMin(bb).cwiseMin(c), hi = a.cwiseMax(bb).cwiseMax(c);
    Eigen::Vector3i i0, i1;
    for (int k = 0; k < 3; ++k) {
      i0[k] = std::clamp(static_cast<int>(std::floor((lo[k] - g.origin[k]) / resolution)), 0,
                         g.dims[k] - 1);
      i1[k] = std::clamp(static_cast<int>(std::floor((hi[k] - g.origin[k]) / resolution)), 0,
                         g.dims[k] - 1);
    }
    for (int z = i0.z(); z <= i1.z(); ++z)
      for (int y = i0.y(); y <= i1.y(); ++y)
        for (int x = i0.x(); x <= i1.x(); ++x) {
          const int64_t idx = g.Index(x, y, z);
          if (g.cells[idx]) continue;
          if (TriangleOverlapsBox(g.CellCenter(x, y, z), half, a, bb, c)) g.cells[idx] = 1;
        }
  }
  // Flood the outside from the padded corner through empty cells (6-connected).
  std::vector<uint8_t> outside(n, 0);
  std::deque<int64_t> queue;
  outside[0] = 1;
  queue.push_back(0);
  const int64_t sx = 1, sy = g.dims.x(), sz = static_cast<int64_t>(g.dims.x()) * g.dims.y();
  while (!queue.empty()) {
    const int64_t idx = queue.front();
    queue.pop_front();
    const int x = static_cast<int>(idx % sy);
    const int y = static_cast<int>((idx / sy) % g.dims.y());
    const int z = static_cast<int>(idx / sz);
    auto visit = [&](int64_t j) {
      if (!outside[j] && !g.cells[j]) {
        outside[j] = 1;
        queue.push_back(j);
      }
    };
    if (x > 0) visit(idx - sx);
    if (x + 1 < g.dims.x()) visit(idx + sx);
    if (y > 0) visit(idx - sy);
    if (y + 1 < g.dims.y()) visit(idx + sy);
    if (z > 0) visit(idx - sz);
    if (z + 1 < g.dims.z()) visit(idx + sz);
  }
  for (int64_t i = 0; i < n; ++i) g.cells[i] = outside[i] ? 0 : 1;
  return g;
}

std::vector<Aabb> MergeVoxelsToBoxes(const VoxelGrid& grid) {
  std::vector<Aabb> boxes;
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  std::vector<uint8_t> used(grid.cells.size(), 0);
  auto free_cell = [&](int x, int y, int z) {
    const int64_t i = grid.Index(x, y, z);
    return grid.cells[i] && !used[i];
  };
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        if (!free_cell(x, y, z)) continue;
        int x1 = x + 1;
        while (x1 < nx && free_cell(x1, y, z)) ++x1;
        int y1 = y + 1;
        auto row_free = [&](int yy, int zz) {
          for (int xx = x; xx < x1; ++xx)
            if (!free_cell(xx, yy, zz)) return false;
          return true;
        };
        while (y1 < ny && row_free(y1, z)) ++y1;
        int z1 = z + 1;
        auto slab_free = [&](int zz) {
          for (int yy = y; yy < y1; ++yy)
            if (!row_free(yy, zz)) return false;
          return true;
        };
        while (z1 < nz && slab_free(z1)) ++z1;
        for (int zz = z; zz < z1; ++zz)
          for (int yy = y; yy < y1; ++yy)
            for (int xx = x; xx < x1; ++xx) used[grid.Index(xx, yy, zz)] = 1;
        Aabb box;
        box.min = grid.origin + grid.resolution * Vector3d(x, y, z);
        box.max = grid.origin + grid.resolution * Vector3d(x1, y1, z1);
        boxes.push_back(box);
      }
  return boxes;
}

namespace {

// Clips a convex polygon to the half-space sign * (p[axis] - value) <= 0.
void ClipPolygon(std::vector<Vector3d>* poly, int axis, double value, double sign) {
  std::vector<Vector3d> out;
  const std::size_t n = poly->size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vector3d& a = (*poly)[i];
    const Vector3d& b = (*poly)[(i + 1) % n];
    const double da = sign * (a[axis] - value), db = sign * (b[axis] - value);
    if (da <= 0) out.push_back(a);
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  poly->swap(out);
}

}  // namespace

std::vector<Aabb> TightenBoxesToSurface(const std::vector<Aabb>& boxes, const VoxelGrid& grid,
                                        const TriangleMesh& mesh) {
  std::vector<Aabb> out = boxes;
  const double r = grid.resolution;
  for (Aabb& box : out) {
    Eigen::Vector3i lo, hi;  // cell index range [lo, hi)
    for (int k = 0; k < 3; ++k) {
      lo[k] = static_cast<int>(std::lround((box.min[k] - grid.origin[k]) / r));
      hi[k] = static_cast<int>(std::lround((box.max[k] - grid.origin[k]) / r));
    }
    // Which faces have only empty cells beyond them.
    bool exterior[3][2];
    for (int axis = 0; axis < 3; ++axis) {
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      for (int side = 0; side < 2; ++side) {
        const int layer = side == 0 ? lo[axis] - 1 : hi[axis];
        bool empty = true;
        for (int u = lo[a1]; u < hi[a1] && empty; ++u)
          for (int v = lo[a2]; v < hi[a2] && empty; ++v) {
            Eigen::Vector3i c;
            c[axis] = layer;
            c[a1] = u;
            c[a2] = v;
            if (grid.At(c.x(), c.y(), c.z())) empty = false;
          }
        exterior[axis][side] = empty;
      }
    }
    // Bounds of the surface inside the box.
    Aabb surface;
    for (const auto& t : mesh.triangles) {
      const Vector3d& a = mesh.vertices[t[0]];
      const Vector3d& b = mesh.vertices[t[1]];
      const Vector3d& c = mesh.vertices[t[2]];
      if ((a.cwiseMax(b).cwiseMax(c).array() < box.min.array()).any() ||
          (a.cwiseMin(b).cwiseMin(c).array() > box.max.array()).any())
        continue;
      std::vector<Vector3d> poly = {a, b, c};
      for (int axis = 0; axis < 3 && !poly.empty(); ++axis) {
        ClipPolygon(&poly, axis, box.max[axis], 1.0);
        if (!poly.empty()) ClipPolygon(&poly, axis, box.min[axis], -1.0);
      }
      for (const auto& p : poly) surface.Extend(p);
    }
    if (surface.empty()) continue;
    for (int axis = 0; axis < 3; ++axis) {
      // Keep at least a sliver so a box never degenerates.
      if (exterior[axis][0]) box.min[axis] = std::min(surface.min[axis], box.max[axis] - 1e-3);
      if (exterior[axis][1]) box.max[axis] = std::max(surface.max[axis], box.min[axis] + 1e-3);
    }
  }
  return out;
}

bool InsideByWindingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double total = 0;
  for (const auto& t : mesh.triangles)
    total += SolidAngle(mesh.vertices[t[0]] - p, mesh.vertices[t[1]] - p, mesh.vertices[t[2]] - p);
  return std::abs(total) / (4.0 * M_PI) > 0.5;
}

void OccupancyOptions::Validate() const {
  Require(resolution > 0 && resolution < 1, "resolution", "a cell size in (0, 1) m");
  Require(max_cells >= 1000, "max_cells", "at least 1000");
}

SceneOccupancy::SceneOccupancy(const Scene& scene, const OccupancyOptions& options)
    : options_(options) {
  ValidateConfig(options, "occupancy options");
  auto add = [&](TriangleMesh mesh) {
    if (mesh.empty()) return;
    const Aabb b = mesh.Bounds();
    double res = options.resolution;
    // Coarsen until the grid fits the cell cap.
    while (true) {
      const Vector3d cells = (b.size() / res).array() + 3.0;
      if (cells.prod() <= static_cast<double>(options.max_cells)) break;
      res *= 1.5;
    }
    Piece piece;
    piece.grid = VoxelizeSolid(mesh, res);
    piece.bounds = piece.grid.Bounds();
    piece.mesh = std::move(mesh);
    grids_.push_back(std::move(piece));
  };
  for (const auto& o : scene.objects) add(o.MergedMesh());
  if (options.include_walls)
    for (auto& piece : scene.walls.EdgeConnectedComponents()) add(std::move(piece));
}

namespace {
bool InBox(const Aabb& b, const Vector3d& p) {
  return (p.array() >= b.min.array()).all() && (p.array() < b.max.array()).all();
}
}  // namespace

bool SceneOccupancy::Inside(const Eigen::Vector3d& p) const {
  if (options_.include_floor && p.z() < 0) return true;
  for (const auto& g : grids_)
    if (InBox(g.bounds, p) && g.grid.Occupied(p)) return true;
  return false;
}

bool SceneOccupancy::InsideExact(const Eigen::Vector3d& p) const {
  if (options_.include_floor && p.z() < 0) return true;
  for (const auto& g : grids_)
    if (InBox(g.bounds, p) && InsideByWindingNumber(g.mesh, p)) return true;
  return false;
}

double SceneOccupancy::PenetrationDepth(const Eigen::Vector3d& p) const {
  double depth = 0;
  if (options_.include_floor && p.z() < 0) depth = -p.z();
  for (const auto& g : grids_) {
    if (!InBox(g.bounds, p) || !g.grid.Occupied(p)) continue;
    depth = std::max(depth, (g.mesh.ClosestPoint(p) - p).norm());
  }
  return depth;
}

void VoxelObservationConfig::Validate() const {
  Require(cells >= 1 && cells <= 128, "cells", "1 to 128 cells per axis");
  Require(extent > 0, "extent", "a positive edge length");
}

void SampleOccupancy(const SceneOccupancy& occupancy, const Eigen::Vector3d& center, double heading,
                     const VoxelObservationConfig& config, float* out) {
  const int n = config.cells;
  const double step = config.extent / n;
  const double c = std::cos(heading), s = std::sin(heading);
  int64_t idx = 0;
  for (int k = 0; k < n; ++k) {
    const double lz = -0.5 * config.extent + (k + 0.5) * step;
    for (int j = 0; j < n; ++j) {
      const double ly = -0.5 * config.extent + (j + 0.5) * step;
      for (int i = 0; i < n; ++i, ++idx) {
        const double lx = -0.5 * config.extent + (i + 0.5) * step;
        const Vector3d p = center + Vector3d(c * lx - s * ly, s * lx + c * ly, lz);
        out[idx] = occupancy.Inside(p) ? 1.0f : 0.0f;
      }
    }
  }
}

void SampleDualOccupancy(const SceneOccupancy& occupancy, const Eigen::Vector3d& root,
                         const Eigen::Vector3d& goal, double heading,
                         const VoxelObservationConfig& config, float* out) {
  SampleOccupancy(occupancy, root, heading, config, out);
  SampleOccupancy(occupancy, goal, heading, config, out + config.size());
}

PenetrationStats MeasurePenetration(const SceneOccupancy& occupancy,
                                    const std::vector<Eigen::Vector3d>& points) {
  PenetrationStats s;
  s.num_points = static_cast<int>(points.size());
  int inside = 0;
  double sum = 0;
  for (const auto& p : points) {
    if (!occupancy.Inside(p)) continue;
    ++inside;
    const double d = occupancy.PenetrationDepth(p);
    sum += d;
    s.max_depth = std::max(s.max_depth, d);
  }
  if (s.num_points > 0) s.fraction_inside = static_cast<double>(inside) / s.num_points;
  if (inside > 0) s.mean_depth = sum / inside;
  return s;
}

}  // namespace sims::scene
