// Voxels: solid voxelisation of triangle meshes, greedy voxel-to-box merging (used for the
// physics decomposition), scene occupancy (LINGO's dual 32³ voxel observation) and the
// penetration measures of the evaluation.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sims/core/config.h"
#include "sims/scene/mesh.h"
#include "sims/scene/scene.h"

namespace sims::scene {

/// A dense occupancy grid over an axis-aligned box; cell (i, j, k) spans
/// origin + [i, i+1) * resolution etc.; x varies fastest in `cells`.
struct VoxelGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< Lower corner of cell (0, 0, 0).
  double resolution = 0.02;                          ///< Cell edge (m).
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();    ///< Cells per axis.
  std::vector<uint8_t> cells;                        ///< 1 = occupied.

  /// Flat index of cell (i, j, k).
  int64_t Index(int i, int j, int k) const {
    return (static_cast<int64_t>(k) * dims.y() + j) * dims.x() + i;
  }
  /// Occupancy of cell (i, j, k); cells outside the grid are empty.
  bool At(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= dims.x() || j >= dims.y() || k >= dims.z()) return false;
    return cells[Index(i, j, k)] != 0;
  }
  /// Occupancy of the cell containing p (false outside the grid).
  bool Occupied(const Eigen::Vector3d& p) const;
  /// Centre of cell (i, j, k).
  Eigen::Vector3d CellCenter(int i, int j, int k) const {
    return origin + resolution * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
  }
  /// World bounds of the grid.
  Aabb Bounds() const;
  /// Number of occupied cells.
  int64_t Count() const;
};

/// Solid voxelisation: cells touched by a triangle (exact triangle–box overlap) plus every
/// cell not reachable from outside through empty cells. Robust to overlapping primitives and
/// inconsistent winding; open surfaces become one-cell shells. The grid is padded by one cell.
VoxelGrid VoxelizeSolid(const TriangleMesh& mesh, double resolution);

/// Covers the occupied cells with disjoint axis-aligned boxes (greedy growth along x, then y,
/// then z), returned in world coordinates.
std::vector<Aabb> MergeVoxelsToBoxes(const VoxelGrid& grid);

/// Shrinks the exterior faces of boxes from MergeVoxelsToBoxes(grid) to the mesh surface they
/// contain, removing the up-to-one-cell inflation of the voxelisation (a voxelised seat keeps
/// its true height). Faces next to other occupied cells stay put so the boxes remain a cover.
std::vector<Aabb> TightenBoxesToSurface(const std::vector<Aabb>& boxes, const VoxelGrid& grid,
                                        const TriangleMesh& mesh);

/// Exact inside test by the generalised winding number (closed, outward-wound meshes; a
/// union of closed shells counts as inside where any shell contains the point).
bool InsideByWindingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p);

/// Which scene geometry the occupancy covers and how finely.
struct OccupancyOptions {
  double resolution = 0.02;       ///< Cell edge of the precomputed per-object grids (m).
  bool include_walls = true;      ///< Walls count as occupied.
  bool include_floor = true;      ///< Everything below z = 0 counts as occupied.
  int64_t max_cells = 4'000'000;  ///< Per-grid cap; coarser resolution beyond it.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(resolution));
    a->Visit(SIMS_NVP(include_walls));
    a->Visit(SIMS_NVP(include_floor));
    a->Visit(SIMS_NVP(max_cells));
  }
  /// Positive resolution and cell cap.
  void Validate() const;
};

/// Scene occupancy precomputed once per scene (one solid grid per object and per connected
/// wall piece), answering inside/outside and penetration-depth queries.
class SceneOccupancy {
 public:
  /// Voxelises every object and wall piece of the scene.
  explicit SceneOccupancy(const Scene& scene, const OccupancyOptions& options = {});
  /// True when p is inside scene geometry (grid lookup; error below one cell).
  bool Inside(const Eigen::Vector3d& p) const;
  /// Exact variant by winding numbers against the triangles (slower; for validation).
  bool InsideExact(const Eigen::Vector3d& p) const;
  /// Distance from p to the surface of the geometry it is inside (0 when outside).
  double PenetrationDepth(const Eigen::Vector3d& p) const;
  /// Number of precomputed grids.
  int num_grids() const { return static_cast<int>(grids_.size()); }

 private:
  struct Piece {
    VoxelGrid grid;
    Aabb bounds;
    TriangleMesh mesh;
  };
  std::vector<Piece> grids_;
  OccupancyOptions options_;
};

/// An egocentric voxel cube: `cells`³ cells over `extent` metres, centred at a point and
/// rotated about z by a heading (LINGO: 32³ over 1.2 m).
struct VoxelObservationConfig {
  int cells = 32;       ///< Cells per axis.
  double extent = 1.2;  ///< Edge of the cube (m).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(cells));
    a->Visit(SIMS_NVP(extent));
  }
  /// 1..128 cells, positive extent.
  void Validate() const;
  /// cells³.
  int size() const { return cells * cells * cells; }
};

/// Fills out[cells³] (x fastest, then y, then z, in the heading frame) with 1 for occupied
/// cell centres and 0 otherwise.
void SampleOccupancy(const SceneOccupancy& occupancy, const Eigen::Vector3d& center, double heading,
                     const VoxelObservationConfig& config, float* out);

/// LINGO's dual voxels: out[0, cells³) around the body at `root`, out[cells³, 2·cells³)
/// around the goal, both in the body's heading frame.
void SampleDualOccupancy(const SceneOccupancy& occupancy, const Eigen::Vector3d& root,
                         const Eigen::Vector3d& goal, double heading,
                         const VoxelObservationConfig& config, float* out);

/// Penetration of a set of body sample points into the scene.
struct PenetrationStats {
  int num_points = 0;            ///< Points tested.
  double fraction_inside = 0.0;  ///< Share of points inside geometry.
  double mean_depth = 0.0;       ///< Mean depth over the points inside (0 if none).
  double max_depth = 0.0;        ///< Largest depth.
};

/// Inside fraction and depths of the points.
PenetrationStats MeasurePenetration(const SceneOccupancy& occupancy,
                                    const std::vector<Eigen::Vector3d>& points);

}  // namespace sims::scene
