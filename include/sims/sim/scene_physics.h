// Scene -> static MuJoCo geometry. Every part (and every connected wall piece) is split into
// edge-connected pieces; a convex piece becomes one box (when it is a box) or one convex
// mesh, a clearly non-convex piece is voxelised and covered by merged boxes, so a chair's seat
// and back never fuse into one solid hull.
#pragma once

#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/humanoid/model_builder.h"
#include "sims/scene/scene.h"

namespace sims::sim {

/// How scene meshes become collision geometry.
struct ScenePhysicsOptions {
  double voxel_size = 0.03;           ///< Cell size of the non-convex decomposition (m).
  double convexity_tolerance = 0.01;  ///< Vertices may stick out of a face plane this much (m)
  double convexity_relative = 0.04;   ///< ... or this fraction of the piece's diagonal.
  double min_thickness = 0.02;        ///< Flat pieces are thickened to this (m).
  double min_piece_size = 0.01;       ///< Pieces with a smaller bounding-box diagonal are dropped.
  int max_boxes_per_piece = 64;       ///< Coarser voxels when a piece needs more boxes.
  double friction = 1.0;              ///< Sliding friction of all scene geoms.
  bool include_walls = true;          ///< Compile scene.walls.
  std::vector<std::string> skip_categories;  ///< Object categories left out of physics.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(voxel_size));
    a->Visit(SIMS_NVP(convexity_tolerance));
    a->Visit(SIMS_NVP(convexity_relative));
    a->Visit(SIMS_NVP(min_thickness));
    a->Visit(SIMS_NVP(min_piece_size));
    a->Visit(SIMS_NVP(max_boxes_per_piece));
    a->Visit(SIMS_NVP(friction));
    a->Visit(SIMS_NVP(include_walls));
    a->Visit(SIMS_NVP(skip_categories));
  }
  /// Positive sizes and limits.
  void Validate() const;
};

/// Static geoms of all objects (except skipped categories and non-static objects) and walls.
/// Geom names are "<instance>/<part name>#<part id>/<k>" and "walls/<k>".
humanoid::StaticGeometry CompileSceneGeometry(const scene::Scene& scene,
                                              const ScenePhysicsOptions& options = {});

/// The geoms of one mesh piece set (exposed for tests and custom scenes): split into
/// edge-connected pieces, then box / convex mesh / voxel boxes as above.
std::vector<humanoid::StaticGeom> CompileMeshGeometry(const scene::TriangleMesh& mesh,
                                                      const std::string& name_prefix,
                                                      const ScenePhysicsOptions& options = {});

/// True when no vertex lies more than `tolerance` outside any triangle's plane (both sides
/// are tried, so the winding does not matter).
bool IsConvexPiece(const scene::TriangleMesh& mesh, double tolerance);

}  // namespace sims::sim
