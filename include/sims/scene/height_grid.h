// Precomputed scene height grids and the egocentric heightmap observation. Rays are cast once
// per scene (coarse grid over the whole scene, fine grids over every object's and wall
// piece's bounding box, as SIMS does); the per-step sampler only reads the grids.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sims/core/config.h"
#include "sims/scene/ray_caster.h"
#include "sims/scene/scene.h"

namespace sims::scene {

/// Resolutions of the precomputed grid.
struct HeightGridConfig {
  double coarse_resolution = 0.1;  ///< Cell size over the whole scene (m).
  double fine_resolution = 0.02;   ///< Cell size over object bounding boxes (m).
  double margin = 1.0;             ///< Coarse grid extends this far beyond the scene (m).
  double fine_margin = 0.1;        ///< Fine grids extend this far beyond each object (m).
  int num_threads = 0;             ///< Casting threads (0 = process-wide thread count).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(coarse_resolution));
    a->Visit(SIMS_NVP(fine_resolution));
    a->Visit(SIMS_NVP(margin));
    a->Visit(SIMS_NVP(fine_margin));
    a->Visit(SIMS_NVP(num_threads));
  }
  /// Positive resolutions, fine no coarser than coarse.
  void Validate() const;
};

/// Top-surface heights of a scene on a coarse grid plus fine per-object grids.
class SceneHeightGrid {
 public:
  /// Casts the grids with a ray caster built for `scene`.
  explicit SceneHeightGrid(const Scene& scene, const HeightGridConfig& config = {});
  /// Casts the grids with an existing caster of the same scene.
  SceneHeightGrid(const Scene& scene, const RayCaster& caster, const HeightGridConfig& config);

  /// Height at (x, y): the fine grid cell containing it if any, else the coarse cell, else 0.
  float Height(double x, double y) const {
    // Cells are compared as doubles first: a body far away (a simulation blowing up) or NaN
    // must not reach the int cast.
    const double gx = std::floor((x - x0_) * inv_coarse_);
    const double gy = std::floor((y - y0_) * inv_coarse_);
    if (!(gx >= 0 && gy >= 0 && gx < nx_ && gy < ny_)) return 0.0f;
    const int64_t cell = static_cast<int64_t>(gy) * nx_ + static_cast<int64_t>(gx);
    for (int32_t k = cell_begin_[cell]; k < cell_begin_[cell + 1]; ++k) {
      const Fine& f = fine_[cell_fine_[k]];
      const double fx = std::floor((x - f.x0) * inv_fine_);
      const double fy = std::floor((y - f.y0) * inv_fine_);
      if (fx >= 0 && fy >= 0 && fx < f.nx && fy < f.ny)
        return f.heights[static_cast<int64_t>(fy) * f.nx + static_cast<int64_t>(fx)];
    }
    return coarse_[cell];
  }
  /// Rays cast to build the grids.
  int64_t num_rays() const { return num_rays_; }
  /// Number of fine grids.
  int num_fine_grids() const { return static_cast<int>(fine_.size()); }
  /// The configuration used.
  const HeightGridConfig& config() const { return config_; }

 private:
  struct Fine {
    double x0, y0;
    int nx, ny;
    std::vector<float> heights;
  };
  void Build(const Scene& scene, const RayCaster& caster);

  HeightGridConfig config_;
  double x0_ = 0, y0_ = 0, inv_coarse_ = 1, inv_fine_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<float> coarse_;
  std::vector<Fine> fine_;
  std::vector<int32_t> cell_begin_, cell_fine_;  // coarse cell -> overlapping fine grids (CSR)
  int64_t num_rays_ = 0;
};

/// Layout of the egocentric heightmap: sample (i, j) sits at
/// (origin_x + i·spacing, origin_y + j·spacing) in the heading frame, flat index j·size_x + i.
struct HeightmapConfig {
  int size_x = 16;               ///< Samples along the heading direction.
  int size_y = 16;               ///< Samples across it.
  double spacing = 0.1;          ///< Sample spacing (m).
  double origin_x = -0.75;       ///< Heading-frame x of sample (0, 0) (m).
  double origin_y = -0.75;       ///< Heading-frame y of sample (0, 0) (m).
  bool relative_to_root = true;  ///< Heights minus root z (else absolute world z).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(size_x));
    a->Visit(SIMS_NVP(size_y));
    a->Visit(SIMS_NVP(spacing));
    a->Visit(SIMS_NVP(origin_x));
    a->Visit(SIMS_NVP(origin_y));
    a->Visit(SIMS_NVP(relative_to_root));
  }
  /// Positive sizes and spacing.
  void Validate() const;
  /// size_x · size_y.
  int size() const { return size_x * size_y; }
  /// An n×n grid centred on the root.
  static HeightmapConfig Centered(int n, double spacing);
  /// UniHSI's 9×9 grid at 0.2 m, x in [-0.4, 1.2], y in [-0.8, 0.8], absolute z.
  static HeightmapConfig UniHsi();
};

/// Heading (yaw) of a rotation: atan2 of the rotated x axis in the xy plane.
double HeadingOf(const Eigen::Quaterniond& q);

/// Samples egocentric heightmaps from a precomputed grid for many environments at once.
class HeightmapSampler {
 public:
  /// Keeps a shared reference to the grid.
  HeightmapSampler(std::shared_ptr<const SceneHeightGrid> grid, const HeightmapConfig& config);
  /// Values per heightmap.
  int size() const { return config_.size(); }
  /// The layout.
  const HeightmapConfig& config() const { return config_; }
  /// Heading-frame (x, y) of each sample, in flat order.
  const std::vector<Eigen::Vector2d>& offsets() const { return offsets_; }
  /// One heightmap into out[size()].
  void SampleOne(const Eigen::Vector3d& root, double heading, float* out) const;
  /// root_pos is [num_envs, 3] row-major, heading [num_envs], out [num_envs, size()]
  /// preallocated; OpenMP over envs with `num_threads` (0 = process-wide thread count).
  void Sample(int num_envs, const double* root_pos, const double* heading, float* out,
              int num_threads = 0) const;

 private:
  std::shared_ptr<const SceneHeightGrid> grid_;
  HeightmapConfig config_;
  std::vector<Eigen::Vector2d> offsets_;
};

}  // namespace sims::scene
