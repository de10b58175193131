#include "sims/scene/navigation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "sims/core/error.h"

namespace sims::scene {

void NavigationConfig::Validate() const {
  Require(resolution > 0, "resolution", "a positive cell size (m)");
  Require(clearance >= 0, "clearance", "a non-negative radius (m)");
  Require(margin >= 0, "margin", "a non-negative margin (m)");
  Require(waypoint_spacing > 0, "waypoint_spacing", "a positive distance (m)");
}

FreeSpaceGrid::FreeSpaceGrid(const Scene& scene, const SceneHeightGrid& heights,
                             const NavigationConfig& config)
    : config_(config) {
  ValidateConfig(config_, "navigation config");
  scene::Aabb box = scene.Bounds();
  if (box.empty()) {
    box.Extend(Eigen::Vector3d(-5, -5, 0));
    box.Extend(Eigen::Vector3d(5, 5, 0));
  }
  const double r = config_.resolution;
  x0_ = box.min.x() - config_.margin;
  y0_ = box.min.y() - config_.margin;
  nx_ = static_cast<int>(std::ceil((box.max.x() + config_.margin - x0_) / r));
  ny_ = static_cast<int>(std::ceil((box.max.y() + config_.margin - y0_) / r));
  std::vector<uint8_t> blocked(static_cast<size_t>(nx_) * ny_, 0);
  for (int iy = 0; iy < ny_; ++iy)
    for (int ix = 0; ix < nx_; ++ix) {
      const Eigen::Vector2d c = Centre(ix, iy);
      blocked[Index(ix, iy)] = heights.Height(c.x(), c.y()) > config_.max_floor_height;
    }
  // Dilate obstacles by the clearance disk so a free cell means "the body fits here".
  const int k = static_cast<int>(std::ceil(config_.clearance / r));
  std::vector<std::pair<int, int>> disk;
  for (int dy = -k; dy <= k; ++dy)
    for (int dx = -k; dx <= k; ++dx)
      if ((dx * dx + dy * dy) * r * r <= config_.clearance * config_.clearance + 1e-12)
        disk.emplace_back(dx, dy);
  free_.assign(blocked.size(), 1);
  for (int iy = 0; iy < ny_; ++iy)
    for (int ix = 0; ix < nx_; ++ix) {
      if (!blocked[Index(ix, iy)]) continue;
      for (auto [dx, dy] : disk) {
        const int x = ix + dx, y = iy + dy;
        if (x >= 0 && y >= 0 && x < nx_ && y < ny_) free_[Index(x, y)] = 0;
      }
    }
}

Eigen::Vector2d FreeSpaceGrid::Centre(int ix, int iy) const {
  return {x0_ + (ix + 0.5) * config_.resolution, y0_ + (iy + 0.5) * config_.resolution};
}

bool FreeSpaceGrid::CellOf(const Eigen::Vector2d& p, int* ix, int* iy) const {
  *ix = static_cast<int>(std::floor((p.x() - x0_) / config_.resolution));
  *iy = static_cast<int>(std::floor((p.y() - y0_) / config_.resolution));
  return *ix >= 0 && *iy >= 0 && *ix < nx_ && *iy < ny_;
}

bool FreeSpaceGrid::Free(const Eigen::Vector2d& p) const {
  int ix, iy;
  return CellOf(p, &ix, &iy) && free_[Index(ix, iy)];
}

int64_t FreeSpaceGrid::free_cells() const { return std::count(free_.begin(), free_.end(), 1); }

bool FreeSpaceGrid::SegmentFree(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  const double len = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(len / (0.5 * config_.resolution))));
  for (int s = 0; s <= steps; ++s)
    if (!Free(a + (b - a) * (static_cast<double>(s) / steps))) return false;
  return true;
}

std::optional<Eigen::Vector2d> FreeSpaceGrid::NearestFree(const Eigen::Vector2d& p,
                                                          double radius) const {
  int cx, cy;
  CellOf(p, &cx, &cy);
  const int k = static_cast<int>(std::ceil(radius / config_.resolution));
  std::optional<Eigen::Vector2d> best;
  double best_d = 1e300;
  for (int dy = -k; dy <= k; ++dy)
    for (int dx = -k; dx <= k; ++dx) {
      const int x = cx + dx, y = cy + dy;
      if (x < 0 || y < 0 || x >= nx_ || y >= ny_ || !free_[Index(x, y)]) continue;
      const Eigen::Vector2d c = Centre(x, y);
      const double d = (c - p).squaredNorm();
      if (d < best_d && d <= radius * radius) best_d = d, best = c;
    }
  return best;
}

std::vector<Eigen::Vector2d> FreeSpaceGrid::FindPath(const Eigen::Vector2d& start,
                                                     const Eigen::Vector2d& goal) const {
  const auto s = NearestFree(start, 1.0), g = NearestFree(goal, 1.0);
  if (!s || !g) return {};
  int sx, sy, gx, gy;
  CellOf(*s, &sx, &sy);
  CellOf(*g, &gx, &gy);
  const int n = nx_ * ny_, start_i = Index(sx, sy), goal_i = Index(gx, gy);
  std::vector<double> cost(n, 1e300);
  std::vector<int> parent(n, -1);
  using Item = std::pair<double, int>;  // (f = g + h, cell)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  auto h = [&](int i) { return std::hypot(i % nx_ - gx, i / nx_ - gy); };  // octile-admissible
  cost[start_i] = 0;
  open.push({h(start_i), start_i});
  const int dxs[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dys[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  while (!open.empty()) {
    const auto [f, i] = open.top();
    open.pop();
    if (i == goal_i) break;
    if (f > cost[i] + h(i) + 1e-9) continue;  // stale entry
    const int ix = i % nx_, iy = i / nx_;
    for (int k = 0; k < 8; ++k) {
      const int x = ix + dxs[k], y = iy + dys[k];
      if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
      const int j = Index(x, y);
      if (!free_[j]) continue;
      // No corner cutting: a diagonal move needs both side cells free.
      if (k >= 4 && (!free_[Index(ix + dxs[k], iy)] || !free_[Index(ix, iy + dys[k])])) continue;
      const double c = cost[i] + (k < 4 ? 1.0 : M_SQRT2);
      if (c < cost[j]) {
        cost[j] = c;
        parent[j] = i;
        open.push({c + h(j), j});
      }
    }
  }
  if (cost[goal_i] >= 1e300) return {};
  std::vector<Eigen::Vector2d> path;
  for (int i = goal_i; i != -1; i = parent[i]) path.push_back(Centre(i % nx_, i / nx_));
  std::reverse(path.begin(), path.end());
  return path;
}

std::vector<Eigen::Vector2d> FreeSpaceGrid::Waypoints(const Eigen::Vector2d& start,
                                                      const Eigen::Vector2d& goal) const {
  const auto path = FindPath(start, goal);
  if (path.empty()) return {};
  // Line-of-sight shortcutting: keep a cell only when the previous kept one cannot see past it.
  std::vector<Eigen::Vector2d> corners = {start};
  size_t anchor = 0;
  for (size_t k = 1; k < path.size(); ++k) {
    const Eigen::Vector2d& from = anchor == 0 ? start : path[anchor];
    if (!SegmentFree(from, path[k])) {
      corners.push_back(path[k - 1]);
      anchor = k - 1;
    }
  }
  corners.push_back(goal);
  std::vector<Eigen::Vector2d> out;
  for (size_t k = 1; k < corners.size(); ++k) {
    const Eigen::Vector2d a = corners[k - 1], b = corners[k];
    const int pieces =
        std::max(1, static_cast<int>(std::ceil((b - a).norm() / config_.waypoint_spacing)));
    for (int p = 1; p <= pieces; ++p)
      out.push_back(a + (b - a) * (static_cast<double>(p) / pieces));
  }
  return out;
}

double PathLength(const Eigen::Vector2d& from, const std::vector<Eigen::Vector2d>& waypoints) {
  double length = 0;
  Eigen::Vector2d prev = from;
  for (const auto& w : waypoints) {
    length += (w - prev).norm();
    prev = w;
  }
  return length;
}

PathFollower::PathFollower(const Eigen::Vector2d& start, std::vector<Eigen::Vector2d> waypoints)
    : points_(std::move(waypoints)) {
  points_.insert(points_.begin(), start);
}

Eigen::Vector2d PathFollower::Carrot(const Eigen::Vector2d& here, double lookahead) {
  if (points_.size() == 1) return points_.back();
  double best = std::numeric_limits<double>::infinity();
  size_t best_segment = segment_;
  double best_t = t_;
  double searched = 0;
  for (size_t k = segment_; k + 1 < points_.size() && searched < 2 * lookahead; ++k) {
    const Eigen::Vector2d a = points_[k], ab = points_[k + 1] - points_[k];
    const double len2 = std::max(ab.squaredNorm(), 1e-12);
    const double t_min = k == segment_ ? t_ : 0.0;
    const double t = std::clamp((here - a).dot(ab) / len2, t_min, 1.0);
    const double d = (a + t * ab - here).norm();
    if (d < best - 1e-9) best = d, best_segment = k, best_t = t;
    searched += std::sqrt(len2) * (1.0 - t_min);
  }
  segment_ = best_segment;
  t_ = best_t;
  double remaining = lookahead;
  Eigen::Vector2d p = points_[segment_] + t_ * (points_[segment_ + 1] - points_[segment_]);
  for (size_t k = segment_; k + 1 < points_.size(); ++k) {
    const double left = (points_[k + 1] - p).norm();
    if (left >= remaining) return p + remaining * (points_[k + 1] - p) / left;
    remaining -= left;
    p = points_[k + 1];
  }
  return points_.back();
}

bool PathFollower::IsEnd(const Eigen::Vector2d& carrot) const {
  return (carrot - points_.back()).norm() < 1e-9;
}

void PathFollower::Restore(size_t segment, double progress) {
  segment_ = points_.size() < 2 ? 0 : std::min(segment, points_.size() - 2);
  t_ = std::clamp(progress, 0.0, 1.0);
}

}  // namespace sims::scene
