// Navigation for long walks: a free-space grid derived from the scene height grid (floor cells
// farther than a body clearance from anything taller than a rug), A* over it, and the path cut
// into waypoints; a walk chases a carrot a little ahead along them (pure pursuit).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "sims/core/config.h"
#include "sims/scene/height_grid.h"
#include "sims/scene/scene.h"

namespace sims::scene {

/// Free-space grid settings.
struct NavigationConfig {
  double resolution = 0.1;         ///< Cell size (m).
  double clearance = 0.4;          ///< Body radius (arms swinging) kept free around the path (m).
  double max_floor_height = 0.05;  ///< Heights up to this are walkable floor (m).
  double margin = 1.0;             ///< Grid extends this far beyond the scene (m).
  double waypoint_spacing = 1.5;   ///< Maximum distance between waypoints (m).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(resolution));
    a->Visit(SIMS_NVP(clearance));
    a->Visit(SIMS_NVP(max_floor_height));
    a->Visit(SIMS_NVP(margin));
    a->Visit(SIMS_NVP(waypoint_spacing));
  }
  /// Positive sizes.
  void Validate() const;
};

/// Boolean occupancy of the floor with the body's clearance already applied.
class FreeSpaceGrid {
 public:
  /// Samples `heights` over the scene bounds (plus margin) and dilates obstacles by clearance.
  FreeSpaceGrid(const Scene& scene, const SceneHeightGrid& heights,
                const NavigationConfig& config = {});
  /// True when (x, y) is inside the grid and free.
  bool Free(const Eigen::Vector2d& p) const;
  /// True when the straight segment a→b stays in free cells.
  bool SegmentFree(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  /// Nearest free cell centre to p within `radius`, if any.
  std::optional<Eigen::Vector2d> NearestFree(const Eigen::Vector2d& p, double radius) const;
  /// A* shortest path (8-connected) from start to goal as cell centres, start and goal
  /// snapped to the nearest free cells; empty when unreachable.
  std::vector<Eigen::Vector2d> FindPath(const Eigen::Vector2d& start,
                                        const Eigen::Vector2d& goal) const;
  /// FindPath, shortened by line-of-sight and re-split so no leg exceeds waypoint_spacing;
  /// the last waypoint is `goal` itself. Empty when unreachable.
  std::vector<Eigen::Vector2d> Waypoints(const Eigen::Vector2d& start,
                                         const Eigen::Vector2d& goal) const;
  /// Grid size in cells.
  int nx() const { return nx_; }
  /// Grid size in cells.
  int ny() const { return ny_; }
  /// Number of free cells.
  int64_t free_cells() const;

 private:
  int Index(int ix, int iy) const { return iy * nx_ + ix; }
  bool CellOf(const Eigen::Vector2d& p, int* ix, int* iy) const;
  Eigen::Vector2d Centre(int ix, int iy) const;

  NavigationConfig config_;
  double x0_ = 0, y0_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<uint8_t> free_;
};

/// Length of the polyline from `from` through `waypoints` (m).
double PathLength(const Eigen::Vector2d& from, const std::vector<Eigen::Vector2d>& waypoints);

/// Pure pursuit along a path: the point `lookahead` metres further along the path than the
/// character's projection onto it, clamped at the path's end. The projection only moves
/// forward, and only the next stretch is searched, so a path that bends around a wall is not
/// short-cut through it.
class PathFollower {
 public:
  /// The path from `start` through `waypoints` (the last one is the goal).
  PathFollower(const Eigen::Vector2d& start, std::vector<Eigen::Vector2d> waypoints);
  /// The point to head for from `here` (advances the projection).
  Eigen::Vector2d Carrot(const Eigen::Vector2d& here, double lookahead);
  /// True when `carrot` is the path's end (the last stretch).
  bool IsEnd(const Eigen::Vector2d& carrot) const;
  /// The path's points: the start, then the waypoints.
  const std::vector<Eigen::Vector2d>& points() const { return points_; }
  /// The segment the last projection fell on (for snapshots).
  size_t segment() const { return segment_; }
  /// Where on that segment, in [0, 1] (for snapshots).
  double progress() const { return t_; }
  /// Puts the projection back where a snapshot had it (clamped to the path).
  void Restore(size_t segment, double progress);

 private:
  std::vector<Eigen::Vector2d> points_;
  size_t segment_ = 0;  // segment of the last projection ...
  double t_ = 0;        // ... and where on it
};

}  // namespace sims::scene
