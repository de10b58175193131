#include "sims/bench/heightmap_bench.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include "sims/core/parallel.h"
#include "sims/core/rng.h"
#include "sims/humanoid/model_builder.h"
#include "sims/scene/builtin.h"
#include "sims/scene/height_grid.h"
#include "sims/scene/ray_caster.h"
#include "sims/sim/scene_physics.h"

namespace sims::bench {

using humanoid::BuildModel;
using humanoid::MakeData;
using humanoid::MjDataPtr;
using humanoid::MjModelPtr;
using humanoid::StaticGeometry;
using sim::CompileSceneGeometry;

namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a) {
  return std::chrono::duration<double>(Clock::now() - a).count();
}

// Free floor positions (nothing within 0.4 m above 5 cm) in the house, for roots and bodies.
std::vector<Eigen::Vector2d> FreeSpots(const scene::RayCaster& caster, int n, Rng& rng) {
  std::vector<Eigen::Vector2d> out;
  const scene::Aabb b = caster.bounds();
  while (static_cast<int>(out.size()) < n) {
    const Eigen::Vector2d p(rng.Uniform(b.min.x() + 0.5, b.max.x() - 0.5),
                            rng.Uniform(b.min.y() + 0.5, b.max.y() - 0.5));
    bool free = true;
    for (double dx : {-0.4, 0.0, 0.4})
      for (double dy : {-0.4, 0.0, 0.4})
        if (caster.HeightAt(p.x() + dx, p.y() + dy) > 0.05) free = false;
    if (free) out.push_back(p);
  }
  return out;
}

double SamplerMicrosPerEnv(const scene::HeightmapSampler& sampler, const std::vector<double>& roots,
                           const std::vector<double>& headings, const HeightmapBenchOptions& o) {
  std::vector<float> out(static_cast<size_t>(o.num_envs) * sampler.size());
  double best = 1e300;
  for (int r = 0; r < o.repeats; ++r) {
    const auto t0 = Clock::now();
    for (int k = 0; k < o.sampler_repeats; ++k)
      sampler.Sample(o.num_envs, roots.data(), headings.data(), out.data(), 1);
    best =
        std::min(best, Seconds(t0) * 1e6 / (static_cast<double>(o.sampler_repeats) * o.num_envs));
  }
  return best;
}

}  // namespace

nlohmann::json RunHeightmapBenchmark(const HeightmapBenchOptions& o) {
  const scene::Scene house = scene::BuiltinHouse();
  const scene::RayCaster caster(house);
  Rng rng(2024);

  // Raw Embree down-rays at random points of the house.
  std::vector<double> xy(2 * static_cast<size_t>(o.rays)), heights(o.rays);
  const scene::Aabb b = caster.bounds();
  for (int i = 0; i < o.rays; ++i) {
    xy[2 * i] = rng.Uniform(b.min.x(), b.max.x());
    xy[2 * i + 1] = rng.Uniform(b.min.y(), b.max.y());
  }
  auto ray_rate = [&](int threads) {
    double best = 0;
    for (int r = 0; r < o.repeats; ++r) {
      const auto t0 = Clock::now();
      caster.HeightsAt(xy.data(), o.rays, heights.data(), threads);
      best = std::max(best, o.rays / Seconds(t0));
    }
    return best;
  };
  const double rays_1 = ray_rate(1);
  const double rays_n = ray_rate(ThreadCount());

  // Precomputed grid and egocentric sampling.
  scene::HeightGridConfig grid_config;
  grid_config.num_threads = 1;
  const auto tg = Clock::now();
  auto grid = std::make_shared<const scene::SceneHeightGrid>(house, caster, grid_config);
  const double grid_build_s = Seconds(tg);
  const auto spots = FreeSpots(caster, o.num_envs, rng);
  std::vector<double> roots(3 * static_cast<size_t>(o.num_envs)), headings(o.num_envs);
  for (int e = 0; e < o.num_envs; ++e) {
    roots[3 * e] = spots[e].x();
    roots[3 * e + 1] = spots[e].y();
    roots[3 * e + 2] = 0.89;
    headings[e] = rng.Uniform(-M_PI, M_PI);
  }
  const scene::HeightmapSampler sampler(grid, scene::HeightmapConfig{});
  const scene::HeightmapSampler unihsi(grid, scene::HeightmapConfig::UniHsi());
  const double sampler_us = SamplerMicrosPerEnv(sampler, roots, headings, o);
  const double unihsi_us = SamplerMicrosPerEnv(unihsi, roots, headings, o);

  // Physics reference: humanoids standing in the house model, 4 mj_step per control step
  // (and, for scale, the same humanoids on an empty floor).
  const StaticGeometry geometry = CompileSceneGeometry(house);
  const auto bodies = FreeSpots(caster, o.physics_envs, rng);
  const int substeps = 4;
  auto physics_micros = [&](const StaticGeometry& g) {
    const MjModelPtr model = BuildModel(g);
    const mjModel* m = model.get();
    std::vector<MjDataPtr> datas;
    for (int i = 0; i < o.physics_envs; ++i) datas.push_back(MakeData(m));
    double best = 1e300;
    for (int r = 0; r < o.repeats; ++r) {
      for (int i = 0; i < o.physics_envs; ++i) {
        mjData* d = datas[i].get();
        mj_resetData(m, d);
        d->qpos[0] = bodies[i].x();
        d->qpos[1] = bodies[i].y();
        mj_forward(m, d);
      }
      const auto t0 = Clock::now();
      for (int t = 0; t < o.control_steps; ++t)
        for (int i = 0; i < o.physics_envs; ++i)
          for (int k = 0; k < substeps; ++k) mj_step(m, datas[i].get());
      best = std::min(best,
                      Seconds(t0) * 1e6 / (static_cast<double>(o.control_steps) * o.physics_envs));
    }
    return best;
  };
  const double physics_us = physics_micros(geometry);
  const double physics_empty_us = physics_micros(StaticGeometry{});

  nlohmann::json j;
  j["rays_per_s"] = rays_1;
  j["rays_per_s_threads"] = rays_n;
  j["threads"] = ThreadCount();
  j["grid_build_s"] = grid_build_s;
  j["grid_rays"] = grid->num_rays();
  j["sampler_us_per_env"] = sampler_us;
  j["sampler_unihsi_us_per_env"] = unihsi_us;
  j["physics_us_per_env"] = physics_us;
  j["physics_empty_floor_us_per_env"] = physics_empty_us;
  j["ratio"] = sampler_us / physics_us;
  j["heightmap"] = {{"size_x", sampler.config().size_x},
                    {"size_y", sampler.config().size_y},
                    {"spacing", sampler.config().spacing}};
  j["scene"] = {{"name", house.name},
                {"objects", house.objects.size()},
                {"triangles", caster.num_triangles()},
                {"static_geoms", geometry.geoms.size()}};
  j["settings"] = {{"rays", o.rays},
                   {"num_envs", o.num_envs},
                   {"physics_envs", o.physics_envs},
                   {"control_steps", o.control_steps},
                   {"substeps", substeps}};
  return j;
}

}  // namespace sims::bench
