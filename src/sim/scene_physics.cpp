#include "sims/sim/scene_physics.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Eigenvalues>

#include "sims/core/error.h"
#include "sims/scene/voxels.h"

namespace sims::sim {

namespace {

using Eigen::Vector3d;
using scene::TriangleMesh;

// Beyond this many face-vertex pairs the exact convexity test is too slow; such pieces go
// straight to the voxel decomposition.
constexpr double kMaxConvexityWork = 2e7;

Eigen::Vector4f CategoryColor(const std::string& category) {
  static const std::map<std::string, Eigen::Vector4f> colors = {
      {"chair", {0.62f, 0.42f, 0.25f, 1}}, {"armchair", {0.55f, 0.2f, 0.2f, 1}},
      {"sofa", {0.35f, 0.4f, 0.6f, 1}},    {"bed", {0.85f, 0.85f, 0.8f, 1}},
      {"table", {0.5f, 0.35f, 0.2f, 1}},   {"desk", {0.45f, 0.33f, 0.22f, 1}},
      {"shelf", {0.6f, 0.5f, 0.35f, 1}},   {"lamp", {0.9f, 0.85f, 0.5f, 1}},
      {"walls", {0.75f, 0.75f, 0.72f, 1}},
  };
  auto it = colors.find(category);
  return it != colors.end() ? it->second : Eigen::Vector4f(0.55f, 0.45f, 0.35f, 1);
}

// Distinct face-normal directions (up to sign), area-weighted clustering.
std::vector<Vector3d> NormalDirections(const TriangleMesh& m) {
  std::vector<Vector3d> dirs;
  for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
    const Vector3d n = m.TriangleNormal(t);
    if (n.squaredNorm() < 0.5) continue;
    bool found = false;
    for (const auto& d : dirs)
      if (std::abs(d.dot(n)) > 0.9999) {
        found = true;
        break;
      }
    if (!found) dirs.push_back(n);
    if (dirs.size() > 3) break;
  }
  return dirs;
}

// Recognises an (oriented) box: three orthogonal normal directions and every vertex at an
// extreme along each of them.
bool AsBox(const TriangleMesh& m, double tol, humanoid::StaticGeom* g) {
  const std::vector<Vector3d> dirs = NormalDirections(m);
  if (dirs.size() != 3) return false;
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (std::abs(dirs[a].dot(dirs[b])) > 1e-6) return false;
  Eigen::Matrix3d R;
  for (int k = 0; k < 3; ++k) R.col(k) = dirs[k];
  if (R.determinant() < 0) R.col(2) *= -1;
  Vector3d lo = Vector3d::Constant(1e300), hi = Vector3d::Constant(-1e300);
  for (const auto& v : m.vertices) {
    const Vector3d q = R.transpose() * v;
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  for (const auto& v : m.vertices) {
    const Vector3d q = R.transpose() * v;
    for (int k = 0; k < 3; ++k)
      if (std::min(std::abs(q[k] - lo[k]), std::abs(q[k] - hi[k])) > tol) return false;
  }
  g->type = humanoid::StaticGeom::Type::kBox;
  g->X_WG = Eigen::Isometry3d::Identity();
  g->X_WG.linear() = R;
  g->X_WG.translation() = R * (0.5 * (lo + hi));
  g->half_size = (0.5 * (hi - lo)).cwiseMax(Vector3d::Constant(5e-4));
  return true;
}

// Convex mesh geom from the piece's vertices; flat pieces get thickness along their normal
// (downwards for horizontal ones, so a seat's top stays where it is).
humanoid::StaticGeom AsConvexMesh(const TriangleMesh& m, double min_thickness) {
  humanoid::StaticGeom g;
  g.type = humanoid::StaticGeom::Type::kConvexMesh;
  g.vertices = m.vertices;
  Vector3d mean = Vector3d::Zero();
  for (const auto& v : m.vertices) mean += v;
  mean /= static_cast<double>(m.vertices.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& v : m.vertices) cov += (v - mean) * (v - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Vector3d n = eig.eigenvectors().col(0);  // smallest spread
  if (n.z() < 0) n = -n;
  double lo = 1e300, hi = -1e300;
  for (const auto& v : m.vertices) {
    lo = std::min(lo, n.dot(v));
    hi = std::max(hi, n.dot(v));
  }
  if (hi - lo < min_thickness) {
    const double extra = min_thickness - (hi - lo);
    for (const auto& v : m.vertices) g.vertices.push_back(v - extra * n);
  }
  return g;
}

std::vector<humanoid::StaticGeom> VoxelBoxes(const TriangleMesh& m, const ScenePhysicsOptions& o) {
  double res = o.voxel_size;
  for (int attempt = 0; attempt < 8; ++attempt, res *= 1.5) {
    const scene::VoxelGrid grid = scene::VoxelizeSolid(m, res);
    std::vector<scene::Aabb> boxes = scene::MergeVoxelsToBoxes(grid);
    if (static_cast<int>(boxes.size()) > o.max_boxes_per_piece && attempt < 7) continue;
    boxes = scene::TightenBoxesToSurface(boxes, grid, m);
    std::vector<humanoid::StaticGeom> out;
    for (const auto& b : boxes) {
      humanoid::StaticGeom g;
      g.type = humanoid::StaticGeom::Type::kBox;
      g.X_WG.translation() = b.center();
      g.half_size = 0.5 * b.size();
      out.push_back(std::move(g));
    }
    return out;
  }
  return {};
}

}  // namespace

void ScenePhysicsOptions::Validate() const {
  Require(voxel_size > 0.002 && voxel_size < 1, "voxel_size", "a cell size in (0.002, 1) m");
  Require(convexity_tolerance >= 0, "convexity_tolerance", "a non-negative distance");
  Require(convexity_relative >= 0 && convexity_relative < 0.5, "convexity_relative",
          "a fraction in [0, 0.5)");
  Require(min_thickness > 0, "min_thickness", "a positive thickness");
  Require(min_piece_size >= 0, "min_piece_size", "a non-negative size");
  Require(max_boxes_per_piece >= 1, "max_boxes_per_piece", "at least 1");
  Require(friction >= 0, "friction", "a non-negative friction");
}

bool IsConvexPiece(const TriangleMesh& mesh, double tolerance) {
  if (mesh.triangles.empty()) return false;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Vector3d n = mesh.TriangleNormal(t);
    if (n.squaredNorm() < 0.5) continue;
    const Vector3d& a = mesh.vertices[mesh.triangles[t][0]];
    double lo = 0, hi = 0;
    for (const auto& v : mesh.vertices) {
      const double d = n.dot(v - a);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
      if (lo < -tolerance && hi > tolerance) return false;
    }
  }
  return true;
}

std::vector<humanoid::StaticGeom> CompileMeshGeometry(const TriangleMesh& mesh,
                                                      const std::string& name_prefix,
                                                      const ScenePhysicsOptions& options) {
  std::vector<humanoid::StaticGeom> out;
  const double weld = 1e-6;
  for (const TriangleMesh& piece : mesh.EdgeConnectedComponents(weld)) {
    if (piece.Bounds().size().norm() < options.min_piece_size) continue;
    std::vector<humanoid::StaticGeom> geoms;
    const double work =
        static_cast<double>(piece.triangles.size()) * static_cast<double>(piece.vertices.size());
    const double diagonal = piece.Bounds().size().norm();
    const double tolerance =
        std::max(options.convexity_tolerance, options.convexity_relative * diagonal);
    if (work <= kMaxConvexityWork && IsConvexPiece(piece, tolerance)) {
      humanoid::StaticGeom g;
      if (!AsBox(piece, 1e-6 + 1e-4 * piece.Bounds().size().norm(), &g))
        g = AsConvexMesh(piece, options.min_thickness);
      geoms.push_back(std::move(g));
    } else {
      geoms = VoxelBoxes(piece, options);
    }
    for (auto& g : geoms) {
      g.name = name_prefix + "/" + std::to_string(out.size());
      g.friction = options.friction;
      out.push_back(std::move(g));
    }
  }
  return out;
}

humanoid::StaticGeometry CompileSceneGeometry(const scene::Scene& scene,
                                              const ScenePhysicsOptions& options) {
  ValidateConfig(options, "scene physics options");
  humanoid::StaticGeometry geometry;
  for (const auto& o : scene.objects) {
    if (!o.is_static) continue;
    if (std::find(options.skip_categories.begin(), options.skip_categories.end(), o.category) !=
        options.skip_categories.end())
      continue;
    for (const auto& p : o.parts) {
      if (p.mesh.empty()) continue;
      auto geoms = CompileMeshGeometry(
          p.mesh, o.instance + "/" + p.name + "#" + std::to_string(p.id), options);
      for (auto& g : geoms) {
        g.rgba = CategoryColor(o.category);
        g.body = "scene/" + o.instance;
        geometry.geoms.push_back(std::move(g));
      }
    }
  }
  if (options.include_walls && !scene.walls.empty()) {
    for (auto& g : CompileMeshGeometry(scene.walls, "walls", options)) {
      g.rgba = CategoryColor("walls");
      g.body = "scene/walls";
      geometry.geoms.push_back(std::move(g));
    }
  }
  return geometry;
}

}  // namespace sims::sim
