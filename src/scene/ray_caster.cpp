#include "sims/scene/ray_caster.h"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <embree3/rtcore.h>
#include <omp.h>

#include "sims/core/error.h"
#include "sims/core/parallel.h"

namespace sims::scene {

namespace {

void OnEmbreeError(void*, RTCError code, const char* str) {
  // Embree reports misuse and out-of-memory here; both are bugs or fatal, not user input.
  internal::AbortInvariant(
      "Embree error", __FILE__, __LINE__,
      "code " + std::to_string(static_cast<int>(code)) + ": " + (str ? str : ""));
}

}  // namespace

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Aabb bounds;
  int64_t triangles = 0;
  std::vector<std::pair<int, int>> geom_owner;  // geomID -> (object, part)
  double top = 0.0;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void AddMesh(const TriangleMesh& mesh, int object, int part) {
    if (mesh.empty()) return;
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          mesh.vertices.size()));
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(mesh.vertices[i][k]);
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    if (geom_owner.size() <= id) geom_owner.resize(id + 1, {-1, -1});
    geom_owner[id] = {object, part};
    triangles += static_cast<int64_t>(mesh.triangles.size());
    bounds.Extend(mesh.Bounds());
  }

  bool Intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double tnear,
                 double tfar, RTCRayHit* rh) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rh->ray.org_x = static_cast<float>(origin.x());
    rh->ray.org_y = static_cast<float>(origin.y());
    rh->ray.org_z = static_cast<float>(origin.z());
    rh->ray.dir_x = static_cast<float>(dir.x());
    rh->ray.dir_y = static_cast<float>(dir.y());
    rh->ray.dir_z = static_cast<float>(dir.z());
    rh->ray.tnear = static_cast<float>(tnear);
    rh->ray.tfar = static_cast<float>(tfar);
    rh->ray.time = 0.0f;
    rh->ray.mask = 0xFFFFFFFFu;
    rh->ray.id = 0;
    rh->ray.flags = 0;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, rh);
    return rh->hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }

  double Down(double x, double y) const {
    if (triangles == 0) return 0.0;
    RTCRayHit rh;
    const double z0 = top + 1.0;
    if (!Intersect({x, y, z0}, {0, 0, -1}, 0.0, z0 + 1.0, &rh)) return 0.0;
    return std::max(0.0, z0 - static_cast<double>(rh.ray.tfar));
  }
};

RayCaster::RayCaster(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice("verbose=0");
  SIMS_CHECK_MSG(impl_->device != nullptr, "rtcNewDevice failed");
  rtcSetDeviceErrorFunction(impl_->device, OnEmbreeError, nullptr);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  for (std::size_t o = 0; o < scene.objects.size(); ++o)
    for (std::size_t p = 0; p < scene.objects[o].parts.size(); ++p)
      impl_->AddMesh(scene.objects[o].parts[p].mesh, static_cast<int>(o), static_cast<int>(p));
  impl_->AddMesh(scene.walls, -1, -1);
  rtcCommitScene(impl_->scene);
  impl_->top = impl_->bounds.empty() ? 0.0 : impl_->bounds.max.z();
}

RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

std::optional<double> RayCaster::Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                      double max_dist) const {
  const double len = dir.norm();
  SIMS_CHECK_MSG(len > 0, "RayCaster::Cast needs a non-zero direction");
  RTCRayHit rh;
  if (!impl_->Intersect(origin, dir / len, 0.0, max_dist, &rh)) return std::nullopt;
  return static_cast<double>(rh.ray.tfar);
}

std::optional<RayHit> RayCaster::CastHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                         double max_dist) const {
  const double len = dir.norm();
  SIMS_CHECK_MSG(len > 0, "RayCaster::CastHit needs a non-zero direction");
  const Eigen::Vector3d d = dir / len;
  RTCRayHit rh;
  if (!impl_->Intersect(origin, d, 0.0, max_dist, &rh)) return std::nullopt;
  RayHit hit;
  hit.distance = rh.ray.tfar;
  hit.point = origin + hit.distance * d;
  hit.normal = Eigen::Vector3d(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).normalized();
  const auto& owner = impl_->geom_owner[rh.hit.geomID];
  hit.object = owner.first;
  hit.part = owner.second;
  return hit;
}

bool RayCaster::Occluded(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  const Eigen::Vector3d d = b - a;
  const double len = d.norm();
  constexpr double kTolerance = 1e-3;
  if (len <= 2 * kTolerance || impl_->triangles == 0) return false;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray;
  const Eigen::Vector3d u = d / len;
  ray.org_x = static_cast<float>(a.x());
  ray.org_y = static_cast<float>(a.y());
  ray.org_z = static_cast<float>(a.z());
  ray.dir_x = static_cast<float>(u.x());
  ray.dir_y = static_cast<float>(u.y());
  ray.dir_z = static_cast<float>(u.z());
  ray.tnear = static_cast<float>(kTolerance);
  ray.tfar = static_cast<float>(len - kTolerance);
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(impl_->scene, &ctx, &ray);
  // Embree marks an occluded ray by setting tfar to -inf.
  return ray.tfar < 0.0f;
}

double RayCaster::HeightAt(double x, double y) const { return impl_->Down(x, y); }

void RayCaster::HeightsAt(const double* xy, int64_t n, double* out, int num_threads) const {
  const int threads = num_threads > 0 ? num_threads : ThreadCount();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int64_t i = 0; i < n; ++i) out[i] = impl_->Down(xy[2 * i], xy[2 * i + 1]);
}

const Aabb& RayCaster::bounds() const { return impl_->bounds; }

int64_t RayCaster::num_triangles() const { return impl_->triangles; }

}  // namespace sims::scene
