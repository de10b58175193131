// Contact targets for rewards and task parsing: nearest surface points of parts to joints,
// and free stand points in front of (or around) an object.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sims/core/config.h"
#include "sims/scene/ray_caster.h"
#include "sims/scene/scene.h"

namespace sims::scene {

/// A point on an object's surface.
struct SurfacePoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< Closest point (world).
  int part = -1;                                    ///< Part index it lies on.
  double distance = 0.0;                            ///< Distance from the query.
};

/// Exact closest point of a part's surface to p (over its triangles).
Eigen::Vector3d NearestPointOnPart(const Part& part, const Eigen::Vector3d& p);

/// Closest of the part's surface samples to p (UniHSI's target point); falls back to the
/// exact surface point when the part has no samples.
Eigen::Vector3d NearestSamplePoint(const Part& part, const Eigen::Vector3d& p);

/// Closest surface point over all parts of an object.
SurfacePoint NearestPointOnObject(const Object& object, const Eigen::Vector3d& p);

/// How stand points are searched.
struct StandPointOptions {
  double distance = 0.45;          ///< Gap between the object's footprint and the point (m).
  double clearance_radius = 0.25;  ///< Free floor disk required around the point (m).
  double max_floor_height = 0.05;  ///< Heights up to this (rugs) still count as free floor.
  double side_offset = 0.3;        ///< Extra candidates shifted sideways by this (m).
  bool front_only = false;         ///< Only candidates in front (+x of the object frame).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(distance));
    a->Visit(SIMS_NVP(clearance_radius));
    a->Visit(SIMS_NVP(max_floor_height));
    a->Visit(SIMS_NVP(side_offset));
    a->Visit(SIMS_NVP(front_only));
  }
  /// Non-negative distances.
  void Validate() const;
};

/// Floor points (z = 0) from which the object can be approached, best first: in front of the
/// object (its +x side), then its sides, then behind. A point qualifies when the floor disk
/// around it is free, it lies in a room (if the scene has rooms), and nothing but the object
/// itself lies between it and the object.
std::vector<Eigen::Vector3d> StandPoints(const Scene& scene, const RayCaster& caster,
                                         int object_index, const StandPointOptions& options = {});

/// As above, building a ray caster for the scene (use the other overload in loops).
std::vector<Eigen::Vector3d> StandPoints(const Scene& scene, int object_index,
                                         const StandPointOptions& options = {});

}  // namespace sims::scene
