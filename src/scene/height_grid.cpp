#include "sims/scene/height_grid.h"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "sims/core/error.h"
#include "sims/core/parallel.h"

namespace sims::scene {

void HeightGridConfig::Validate() const {
  Require(coarse_resolution > 0 && coarse_resolution <= 2, "coarse_resolution",
          "a cell size in (0, 2] m");
  Require(fine_resolution > 0 && fine_resolution <= coarse_resolution, "fine_resolution",
          "a cell size in (0, coarse_resolution]");
  Require(margin >= 0, "margin", "a non-negative margin");
  Require(fine_margin >= 0, "fine_margin", "a non-negative margin");
  Require(num_threads >= 0, "num_threads", "0 (all) or a positive thread count");
}

SceneHeightGrid::SceneHeightGrid(const Scene& scene, const HeightGridConfig& config)
    : config_(config) {
  ValidateConfig(config, "height grid config");
  RayCaster caster(scene);
  Build(scene, caster);
}

SceneHeightGrid::SceneHeightGrid(const Scene& scene, const RayCaster& caster,
                                 const HeightGridConfig& config)
    : config_(config) {
  ValidateConfig(config, "height grid config");
  Build(scene, caster);
}

void SceneHeightGrid::Build(const Scene& scene, const RayCaster& caster) {
  const int threads = config_.num_threads > 0 ? config_.num_threads : ThreadCount();
  inv_coarse_ = 1.0 / config_.coarse_resolution;
  inv_fine_ = 1.0 / config_.fine_resolution;
  // Regions that get fine grids: every object and every connected wall piece.
  std::vector<Aabb> regions;
  for (const auto& o : scene.objects)
    if (!o.parts.empty()) regions.push_back(o.Bounds());
  for (const auto& piece : scene.walls.EdgeConnectedComponents()) regions.push_back(piece.Bounds());
  Aabb all;
  for (const auto& r : regions) all.Extend(r);
  if (all.empty()) {
    all.Extend(Eigen::Vector3d::Zero());
  }
  x0_ = all.min.x() - config_.margin;
  y0_ = all.min.y() - config_.margin;
  nx_ =
      std::max(1, static_cast<int>(std::ceil((all.max.x() + config_.margin - x0_) * inv_coarse_)));
  ny_ =
      std::max(1, static_cast<int>(std::ceil((all.max.y() + config_.margin - y0_) * inv_coarse_)));

  // Coarse grid: one down-cast per cell centre.
  std::vector<double> xy(2 * static_cast<std::size_t>(nx_) * ny_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * nx_ + i;
      xy[2 * c] = x0_ + (i + 0.5) * config_.coarse_resolution;
      xy[2 * c + 1] = y0_ + (j + 0.5) * config_.coarse_resolution;
    }
  std::vector<double> heights(static_cast<std::size_t>(nx_) * ny_);
  caster.HeightsAt(xy.data(), static_cast<int64_t>(heights.size()), heights.data(), threads);
  coarse_.assign(heights.begin(), heights.end());
  num_rays_ = static_cast<int64_t>(heights.size());

  // Fine grids.
  fine_.clear();
  std::vector<std::vector<int32_t>> per_cell(static_cast<std::size_t>(nx_) * ny_);
  for (const auto& r : regions) {
    Fine f;
    f.x0 = r.min.x() - config_.fine_margin;
    f.y0 = r.min.y() - config_.fine_margin;
    f.nx = std::max(
        1, static_cast<int>(std::ceil((r.max.x() + config_.fine_margin - f.x0) * inv_fine_)));
    f.ny = std::max(
        1, static_cast<int>(std::ceil((r.max.y() + config_.fine_margin - f.y0) * inv_fine_)));
    const std::size_t n = static_cast<std::size_t>(f.nx) * f.ny;
    std::vector<double> fxy(2 * n), fh(n);
    for (int j = 0; j < f.ny; ++j)
      for (int i = 0; i < f.nx; ++i) {
        const std::size_t c = static_cast<std::size_t>(j) * f.nx + i;
        fxy[2 * c] = f.x0 + (i + 0.5) * config_.fine_resolution;
        fxy[2 * c + 1] = f.y0 + (j + 0.5) * config_.fine_resolution;
      }
    caster.HeightsAt(fxy.data(), static_cast<int64_t>(n), fh.data(), threads);
    num_rays_ += static_cast<int64_t>(n);
    f.heights.assign(fh.begin(), fh.end());
    const int32_t id = static_cast<int32_t>(fine_.size());
    const double fx1 = f.x0 + f.nx * config_.fine_resolution;
    const double fy1 = f.y0 + f.ny * config_.fine_resolution;
    const int i0 = std::max(0, static_cast<int>(std::floor((f.x0 - x0_) * inv_coarse_)));
    const int j0 = std::max(0, static_cast<int>(std::floor((f.y0 - y0_) * inv_coarse_)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((fx1 - x0_) * inv_coarse_)));
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((fy1 - y0_) * inv_coarse_)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) per_cell[static_cast<std::size_t>(j) * nx_ + i].push_back(id);
    fine_.push_back(std::move(f));
  }
  cell_begin_.assign(per_cell.size() + 1, 0);
  cell_fine_.clear();
  for (std::size_t c = 0; c < per_cell.size(); ++c) {
    cell_begin_[c] = static_cast<int32_t>(cell_fine_.size());
    cell_fine_.insert(cell_fine_.end(), per_cell[c].begin(), per_cell[c].end());
  }
  cell_begin_[per_cell.size()] = static_cast<int32_t>(cell_fine_.size());
}

void HeightmapConfig::Validate() const {
  Require(size_x >= 1 && size_x <= 256, "size_x", "1 to 256 samples");
  Require(size_y >= 1 && size_y <= 256, "size_y", "1 to 256 samples");
  Require(spacing > 0 && spacing <= 2, "spacing", "a spacing in (0, 2] m");
}

HeightmapConfig HeightmapConfig::Centered(int n, double spacing) {
  HeightmapConfig c;
  c.size_x = c.size_y = n;
  c.spacing = spacing;
  c.origin_x = c.origin_y = -0.5 * (n - 1) * spacing;
  return c;
}

HeightmapConfig HeightmapConfig::UniHsi() {
  HeightmapConfig c;
  c.size_x = c.size_y = 9;
  c.spacing = 0.2;
  c.origin_x = -0.4;
  c.origin_y = -0.8;
  c.relative_to_root = false;
  return c;
}

double HeadingOf(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d x = q * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

HeightmapSampler::HeightmapSampler(std::shared_ptr<const SceneHeightGrid> grid,
                                   const HeightmapConfig& config)
    : grid_(std::move(grid)), config_(config) {
  SIMS_CHECK_MSG(grid_ != nullptr, "HeightmapSampler needs a grid");
  ValidateConfig(config, "heightmap config");
  offsets_.reserve(config.size());
  for (int j = 0; j < config.size_y; ++j)
    for (int i = 0; i < config.size_x; ++i)
      offsets_.emplace_back(config.origin_x + i * config.spacing,
                            config.origin_y + j * config.spacing);
}

void HeightmapSampler::SampleOne(const Eigen::Vector3d& root, double heading, float* out) const {
  const double c = std::cos(heading), s = std::sin(heading);
  const float base = config_.relative_to_root ? static_cast<float>(root.z()) : 0.0f;
  const int n = static_cast<int>(offsets_.size());
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& o = offsets_[k];
    out[k] =
        grid_->Height(root.x() + c * o.x() - s * o.y(), root.y() + s * o.x() + c * o.y()) - base;
  }
}

void HeightmapSampler::Sample(int num_envs, const double* root_pos, const double* heading,
                              float* out, int num_threads) const {
  const int threads = num_threads > 0 ? num_threads : ThreadCount();
  const int n = size();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int e = 0; e < num_envs; ++e) {
    const Eigen::Vector3d root(root_pos[3 * e], root_pos[3 * e + 1], root_pos[3 * e + 2]);
    SampleOne(root, heading[e], out + static_cast<int64_t>(e) * n);
  }
}

}  // namespace sims::scene
