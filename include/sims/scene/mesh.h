// Triangle meshes and area-uniform surface point clouds (the project's own type; Assimp and
// Embree types never leave the loaders' and ray caster's .cpp files).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sims/core/rng.h"

namespace sims::scene {

/// Axis-aligned bounding box.
struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(1e300);   ///< Lower corner.
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-1e300);  ///< Upper corner.
  /// True when no point was added.
  bool empty() const { return (min.array() > max.array()).any(); }
  /// Grows the box to contain p.
  void Extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  /// Grows the box to contain another box.
  void Extend(const Aabb& b) {
    if (!b.empty()) {
      Extend(b.min);
      Extend(b.max);
    }
  }
  /// max - min.
  Eigen::Vector3d size() const { return max - min; }
  /// (min + max) / 2.
  Eigen::Vector3d center() const { return 0.5 * (min + max); }
};

/// Indexed triangle mesh in metres; vertices are 3×N-free rows (one Vector3d per vertex).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;   ///< Vertex positions.
  std::vector<Eigen::Vector3i> triangles;  ///< Counter-clockwise vertex indices.

  /// True without triangles.
  bool empty() const { return triangles.empty(); }
  /// Bounding box of the vertices.
  Aabb Bounds() const;
  /// Total surface area.
  double Area() const;
  /// Appends another mesh (indices are offset).
  void Append(const TriangleMesh& other);
  /// Applies a rigid (or similarity) transform to every vertex.
  void Transform(const Eigen::Affine3d& X);
  /// Returns a transformed copy.
  TriangleMesh Transformed(const Eigen::Affine3d& X) const;
  /// Samples n points uniformly by area (deterministic for a given rng state).
  std::vector<Eigen::Vector3d> SamplePoints(int n, Rng& rng) const;
  /// Closest point on the surface to p (brute force; fine for furniture-part meshes).
  Eigen::Vector3d ClosestPoint(const Eigen::Vector3d& p) const;
  /// An axis-aligned box mesh (12 triangles) spanning [min, max].
  static TriangleMesh Box(const Eigen::Vector3d& min, const Eigen::Vector3d& max);
  /// A closed cylinder along z with the given segment count.
  static TriangleMesh Cylinder(const Eigen::Vector3d& base_center, double radius, double height,
                               int segments = 16);

  /// Signed volume by the divergence theorem (meaningful for closed, outward-wound meshes).
  double SignedVolume() const;
  /// Unit normal of triangle t (zero for degenerate triangles).
  Eigen::Vector3d TriangleNormal(int t) const;
  /// Merges vertices closer than `tolerance` and drops degenerate triangles.
  TriangleMesh Welded(double tolerance = 1e-6) const;
  /// Splits into pieces connected through shared manifold edges (after welding with
  /// `tolerance`), so primitives that merely touch (at a corner, an edge or a face) or overlap
  /// stay separate.
  std::vector<TriangleMesh> EdgeConnectedComponents(double tolerance = 1e-6) const;
  /// True when every edge is shared by exactly two triangles (after welding).
  bool IsClosed(double tolerance = 1e-6) const;
};

/// Closest point to p on triangle (a, b, c).
Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace sims::scene
