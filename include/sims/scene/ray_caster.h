// Ray queries against a scene (Embree 3 behind a pimpl). The floor plane z = 0 is not part of
// the ray-cast geometry: a downward ray that hits nothing has reached the floor.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include <Eigen/Core>

#include "sims/scene/scene.h"

namespace sims::scene {

/// One ray hit.
struct RayHit {
  double distance = 0.0;                             ///< Along the normalised direction.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< Hit point (world).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< Unit geometric normal (unoriented).
  int object = -1;                                   ///< Scene object index; -1 for walls.
  int part = -1;                                     ///< Part index in that object; -1 for walls.
};

/// Embree scene of all object parts and the walls; thread-safe for queries once built.
class RayCaster {
 public:
  /// Builds the acceleration structure (copies the triangles).
  explicit RayCaster(const Scene& scene);
  ~RayCaster();
  /// Move-only.
  RayCaster(RayCaster&&) noexcept;
  /// Move-only.
  RayCaster& operator=(RayCaster&&) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Distance to the first hit along `dir` (normalised internally) within max_dist.
  std::optional<double> Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                             double max_dist) const;
  /// Full first-hit record along `dir` within max_dist.
  std::optional<RayHit> CastHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                double max_dist) const;
  /// Line of sight: true when geometry lies between a and b (1 mm tolerance at both ends).
  bool Occluded(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
  /// Top surface height at (x, y): the highest geometry below the scene top, or 0 (floor).
  double HeightAt(double x, double y) const;
  /// Batch of down-casts: xy holds n (x, y) pairs, out receives n heights; OpenMP over
  /// `num_threads` threads (0 = the process-wide thread count).
  void HeightsAt(const double* xy, int64_t n, double* out, int num_threads = 0) const;
  /// Bounds of all geometry.
  const Aabb& bounds() const;
  /// Triangles in the acceleration structure.
  int64_t num_triangles() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sims::scene
