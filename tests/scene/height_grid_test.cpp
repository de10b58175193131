#include "sims/scene/height_grid.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "scene/test_scenes.h"
#include "sims/core/error.h"
#include "sims/scene/builtin.h"

namespace sims::scene {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// Box [1, 2] x [-0.5, 0.5] x [0, 0.8] plus a 0.4 m block at [-1.5, -1] x [-1, 1].
Scene TwoBoxes() {
  Scene s = testing::BoxScene({1, -0.5, 0}, {2, 0.5, 0.8});
  Object low = s.objects[0];
  low.instance = "";
  low.parts[0].mesh = TriangleMesh::Box({-1.5, -1, 0}, {-1, 1, 0.4});
  s.AddObject(low);
  return s;
}

double Analytic(double x, double y) {
  if (x >= 1 && x <= 2 && y >= -0.5 && y <= 0.5) return 0.8;
  if (x >= -1.5 && x <= -1 && y >= -1 && y <= 1) return 0.4;
  return 0.0;
}

// Distance from (x, y) to the nearest footprint edge of either box.
double EdgeDistance(double x, double y) {
  auto rect = [](double x, double y, double x0, double x1, double y0, double y1) {
    const double dx = std::max({x0 - x, x - x1, 0.0}), dy = std::max({y0 - y, y - y1, 0.0});
    const double outside = std::hypot(dx, dy);
    if (outside > 0) return outside;
    return std::min({x - x0, x1 - x, y - y0, y1 - y});
  };
  return std::min(rect(x, y, 1, 2, -0.5, 0.5), rect(x, y, -1.5, -1, -1, 1));
}

TEST(HeightGridTest, HeightmapMatchesAnalyticHeights) {
  const Scene s = TwoBoxes();
  auto grid = std::make_shared<SceneHeightGrid>(s);
  EXPECT_EQ(grid->num_fine_grids(), 2);
  EXPECT_GT(grid->num_rays(), 0);
  const HeightmapSampler sampler(grid, HeightmapConfig{});  // 16x16 at 0.1 m
  ASSERT_EQ(sampler.size(), 256);
  const double spacing = sampler.config().spacing;
  int checked = 0;
  for (const Vector3d& root : {Vector3d(1.2, 0.1, 0.9), Vector3d(-0.6, 0.3, 1.0)}) {
    for (const double heading : {0.0, 0.7, M_PI / 2, -2.0}) {
      std::vector<float> hm(sampler.size());
      sampler.SampleOne(root, heading, hm.data());
      for (int k = 0; k < sampler.size(); ++k) {
        const Vector2d o = sampler.offsets()[k];
        const double x = root.x() + std::cos(heading) * o.x() - std::sin(heading) * o.y();
        const double y = root.y() + std::sin(heading) * o.x() + std::cos(heading) * o.y();
        // Heights are relative to the root; within one grid spacing of an edge either side's
        // height is acceptable.
        const double got = hm[k] + root.z();
        if (EdgeDistance(x, y) > spacing) {
          EXPECT_NEAR(got, Analytic(x, y), 1e-5) << x << ", " << y;
          ++checked;
        } else {
          const bool either = std::abs(got - Analytic(x, y)) < 1e-5 || std::abs(got - 0.8) < 1e-5 ||
                              std::abs(got - 0.4) < 1e-5 || std::abs(got) < 1e-5;
          EXPECT_TRUE(either) << got;
        }
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(HeightGridTest, HeightmapRotatesWithHeading) {
  // A long thin box along +x from the origin.
  const Scene s = testing::BoxScene({0.2, -0.1, 0}, {2, 0.1, 0.5});
  auto grid = std::make_shared<SceneHeightGrid>(s);
  const HeightmapSampler sampler(grid, HeightmapConfig::Centered(9, 0.2));
  const Vector3d root(0, 0, 0.9);
  std::vector<float> a(81), b(81);
  sampler.SampleOne(root, 0.0, a.data());
  sampler.SampleOne(root, M_PI / 2, b.data());
  // Offsets: (i, j) -> (0.2 i - 0.8, 0.2 j - 0.8), k = 9 j + i.
  auto at = [](const std::vector<float>& v, int i, int j) { return v[9 * j + i]; };
  EXPECT_NEAR(at(a, 8, 4), 0.5 - 0.9, 1e-6);  // ahead: on the box
  EXPECT_NEAR(at(a, 4, 8), -0.9, 1e-6);       // left: floor
  // Facing +y, the box lies to the right (local -y), nothing ahead.
  EXPECT_NEAR(at(b, 8, 4), -0.9, 1e-6);
  EXPECT_NEAR(at(b, 4, 0), 0.5 - 0.9, 1e-6);
}

TEST(HeightGridTest, BatchSamplingMatchesSingleAtAnyThreadCount) {
  const Scene house = BuiltinHouse();
  auto grid = std::make_shared<SceneHeightGrid>(house);
  const HeightmapSampler sampler(grid, HeightmapConfig{});
  const int n = 37;
  std::vector<double> roots(3 * n), headings(n);
  Rng rng(9);
  for (int e = 0; e < n; ++e) {
    roots[3 * e] = rng.Uniform(0, 10);
    roots[3 * e + 1] = rng.Uniform(0, 10);
    roots[3 * e + 2] = rng.Uniform(0.5, 1.0);
    headings[e] = rng.Uniform(-M_PI, M_PI);
  }
  std::vector<float> one(n * sampler.size()), two(n * sampler.size()), single(sampler.size());
  sampler.Sample(n, roots.data(), headings.data(), one.data(), 1);
  sampler.Sample(n, roots.data(), headings.data(), two.data(), 2);
  EXPECT_EQ(one, two);
  sampler.SampleOne({roots[30], roots[31], roots[32]}, headings[10], single.data());
  EXPECT_TRUE(std::equal(single.begin(), single.end(), one.begin() + 10 * sampler.size()));
  // The precomputed grid agrees with direct ray casts away from edges.
  const RayCaster rc(house);
  int agree = 0, total = 0;
  for (int i = 0; i < 2000; ++i) {
    const double x = rng.Uniform(0, 10), y = rng.Uniform(0, 10);
    ++total;
    agree += std::abs(grid->Height(x, y) - rc.HeightAt(x, y)) < 1e-4;
  }
  EXPECT_GT(agree, 0.97 * total);
}

// Fuzzer finding (tools/fuzz.sh env_state): a snapshot with a body 2.6e10 m away cast that
// distance to an int cell index (UB; the asan job's UBSan reports it). Far away, infinite or
// NaN points are off the grid: height 0.
TEST(HeightGridTest, FarAndNonFinitePointsAreOffTheGrid) {
  const SceneHeightGrid grid(testing::BoxScene({0, 0, 0}, {1, 1, 0.3}));
  EXPECT_NEAR(grid.Height(0, 0), 0.3, 1e-4);
  const double inf = std::numeric_limits<double>::infinity();
  for (const double far : {2.6e10, -2.6e10, 1e300, inf, -inf, std::nan("")}) {
    EXPECT_EQ(grid.Height(far, 0), 0.f) << far;
    EXPECT_EQ(grid.Height(0, far), 0.f) << far;
  }
}

TEST(HeightGridTest, UniHsiLayoutAndHeading) {
  const HeightmapConfig c = HeightmapConfig::UniHsi();
  auto grid = std::make_shared<SceneHeightGrid>(testing::BoxScene({0, 0, 0}, {1, 1, 0.3}));
  const HeightmapSampler sampler(grid, c);
  ASSERT_EQ(sampler.size(), 81);
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 9; ++i)
      EXPECT_TRUE(sampler.offsets()[9 * j + i].isApprox(Vector2d(0.2 * i - 0.4, 0.2 * j - 0.8)));
  std::vector<float> hm(81);
  sampler.SampleOne({0.3, 0.5, 0.9}, 0.0, hm.data());
  EXPECT_NEAR(hm[9 * 4 + 2], 0.3, 1e-6);  // absolute z: (0.3, 0.5) is on the block
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.8, Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.3, Vector3d::UnitY()));
  EXPECT_NEAR(HeadingOf(q), 0.8, 1e-12);
  HeightmapConfig bad;
  bad.spacing = -1;
  EXPECT_THROW(HeightmapSampler(grid, bad), Error);
}

}  // namespace
}  // namespace sims::scene
