#include "sims/scene/contact_targets.h"

#include <cmath>
#include <limits>

#include "sims/core/error.h"

namespace sims::scene {

Eigen::Vector3d NearestPointOnPart(const Part& part, const Eigen::Vector3d& p) {
  SIMS_CHECK_MSG(!part.mesh.empty(), "part '" + part.name + "' has no triangles");
  return part.mesh.ClosestPoint(p);
}

Eigen::Vector3d NearestSamplePoint(const Part& part, const Eigen::Vector3d& p) {
  if (part.points.empty()) return NearestPointOnPart(part, p);
  const Eigen::Vector3d* best = &part.points[0];
  double best_d2 = (part.points[0] - p).squaredNorm();
  for (const auto& q : part.points) {
    const double d2 = (q - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = &q;
    }
  }
  return *best;
}

SurfacePoint NearestPointOnObject(const Object& object, const Eigen::Vector3d& p) {
  SurfacePoint best;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < object.parts.size(); ++i) {
    if (object.parts[i].mesh.empty()) continue;
    const Eigen::Vector3d q = object.parts[i].mesh.ClosestPoint(p);
    const double d = (q - p).norm();
    if (d < best.distance) {
      best = {q, static_cast<int>(i), d};
    }
  }
  SIMS_CHECK_MSG(best.part >= 0, "object '" + object.instance + "' has no triangles");
  return best;
}

void StandPointOptions::Validate() const {
  Require(distance >= 0, "distance", "a non-negative distance");
  Require(clearance_radius >= 0, "clearance_radius", "a non-negative radius");
  Require(side_offset >= 0, "side_offset", "a non-negative offset");
}

namespace {

std::vector<Eigen::Vector3d> StandPointsAt(const Scene& scene, const RayCaster& caster,
                                           int object_index, const StandPointOptions& options) {
  const Object& object = scene.objects[object_index];
  const Aabb local = object.LocalBounds();
  const Eigen::Vector3d c = local.center();
  const double d = options.distance, s = options.side_offset;
  // Candidates in the object frame, best first.
  std::vector<Eigen::Vector2d> candidates = {
      {local.max.x() + d, c.y()}, {local.max.x() + d, c.y() + s}, {local.max.x() + d, c.y() - s}};
  if (!options.front_only) {
    candidates.insert(candidates.end(), {{c.x(), local.max.y() + d},
                                         {c.x(), local.min.y() - d},
                                         {c.x() + s, local.max.y() + d},
                                         {c.x() + s, local.min.y() - d},
                                         {local.min.x() - d, c.y()}});
  }
  const Eigen::Vector3d center_W = object.X_WO * c;
  const double probe_z = std::min(std::max(0.3, 0.5 * (local.max.z() + local.min.z())), 1.0);
  std::vector<Eigen::Vector3d> out;
  for (const auto& q : candidates) {
    Eigen::Vector3d p = object.X_WO * Eigen::Vector3d(q.x(), q.y(), 0.0);
    p.z() = 0.0;
    if (!scene.rooms.empty() && !scene.RoomAt(p.x(), p.y())) continue;
    bool free = true;
    const double r = options.clearance_radius;
    for (int k = -1; k < 8 && free; ++k) {
      Eigen::Vector2d xy(p.x(), p.y());
      if (k >= 0) xy += r * Eigen::Vector2d(std::cos(k * M_PI / 4), std::sin(k * M_PI / 4));
      if (caster.HeightAt(xy.x(), xy.y()) > options.max_floor_height) free = false;
    }
    if (!free) continue;
    // The first thing seen from the stand point towards the object must be the object.
    const Eigen::Vector3d from(p.x(), p.y(), probe_z);
    const Eigen::Vector3d to(center_W.x(), center_W.y(), probe_z);
    const Eigen::Vector3d dir = to - from;
    if (dir.norm() > 1e-9) {
      const auto hit = caster.CastHit(from, dir, dir.norm());
      if (hit && hit->object != object_index) continue;
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

std::vector<Eigen::Vector3d> StandPoints(const Scene& scene, const RayCaster& caster,
                                         int object_index, const StandPointOptions& options) {
  if (object_index < 0 || object_index >= static_cast<int>(scene.objects.size()))
    ThrowInputError("scene '" + scene.name + "'", "object_index",
                    "an index below " + std::to_string(scene.objects.size()),
                    std::to_string(object_index));
  ValidateConfig(options, "stand point options");
  std::vector<Eigen::Vector3d> out = StandPointsAt(scene, caster, object_index, options);
  if (out.empty()) {
    // Tight layouts (a sofa facing a coffee table) may only leave room closer in.
    StandPointOptions closer = options;
    closer.distance = 0.6 * options.distance;
    out = StandPointsAt(scene, caster, object_index, closer);
  }
  return out;
}

std::vector<Eigen::Vector3d> StandPoints(const Scene& scene, int object_index,
                                         const StandPointOptions& options) {
  RayCaster caster(scene);
  return StandPoints(scene, caster, object_index, options);
}

}  // namespace sims::scene
