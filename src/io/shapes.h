// Triangle soups with normals for the exporters: the humanoid's collision shapes per body
// (read from the compiled model, in body frame) and flat-shaded copies of scene meshes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sims/humanoid/humanoid.h"
#include "sims/scene/mesh.h"

namespace sims::io {

/// Float positions/normals (xyz interleaved per vertex) and triangle indices.
struct ShapeMesh {
  std::vector<float> positions;   ///< 3 per vertex.
  std::vector<float> normals;     ///< 3 per vertex, unit length.
  std::vector<uint32_t> indices;  ///< 3 per triangle, counter-clockwise.

  /// Vertices so far.
  uint32_t num_vertices() const { return static_cast<uint32_t>(positions.size() / 3); }
  /// Appends a vertex; returns its index.
  uint32_t AddVertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n);
};

/// The humanoid's geoms (spheres, capsules, boxes, ...) merged per AMP body, in body frame.
std::array<ShapeMesh, humanoid::kNumBodies> HumanoidBodyShapes(const humanoid::Humanoid& humanoid,
                                                               int segments = 16);

/// One vertex per triangle corner with the face normal; degenerate triangles are dropped.
ShapeMesh FlatShadedMesh(const scene::TriangleMesh& mesh);

/// An upward-facing quad on z = 0 spanning [lo, hi] in xy.
ShapeMesh FloorQuad(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);

}  // namespace sims::io
