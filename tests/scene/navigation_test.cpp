#include "sims/scene/navigation.h"

#include <gtest/gtest.h>

namespace sims::scene {
namespace {

// A wall from y = −3 to y = 2 at x = 0 (0.2 m thick, 1 m tall): the only way from (−2, 0) to
// (2, 0) is around its top end.
scene::Scene WallScene() {
  scene::Scene s;
  scene::Object wall;
  wall.category = "wall";
  wall.instance = "wall_0";
  scene::Part p;
  p.name = "body";
  p.mesh = scene::TriangleMesh::Box({-0.1, -3, 0}, {0.1, 2, 1});
  wall.parts.push_back(p);
  s.objects.push_back(wall);
  scene::Object corner;  // extends the bounds so there is room to go around
  corner.category = "lamp";
  corner.instance = "lamp_0";
  scene::Part q;
  q.name = "body";
  q.mesh = scene::TriangleMesh::Box({-3, 3.6, 0}, {-2.9, 3.7, 1});
  corner.parts.push_back(q);
  s.objects.push_back(corner);
  corner.instance = "lamp_1";
  corner.parts[0].mesh = scene::TriangleMesh::Box({3.4, -3.7, 0}, {3.5, -3.6, 1});
  s.objects.push_back(corner);
  return s;
}

TEST(NavigationTest, PathGoesAroundTheWall) {
  const auto scene = WallScene();
  const scene::SceneHeightGrid heights(scene);
  const FreeSpaceGrid grid(scene, heights);
  EXPECT_FALSE(grid.Free({0, 0}));
  EXPECT_FALSE(grid.Free({0.3, 0})) << "clearance dilates the wall";
  EXPECT_TRUE(grid.Free({-2, 0}));
  EXPECT_FALSE(grid.SegmentFree({-2, 0}, {2, 0}));
  const auto wp = grid.Waypoints({-2, 0}, {2, 0});
  ASSERT_FALSE(wp.empty());
  EXPECT_TRUE(wp.back().isApprox(Eigen::Vector2d(2, 0)));
  Eigen::Vector2d prev(-2, 0);
  double max_y = -1e9;
  for (const auto& p : wp) {
    EXPECT_LE((p - prev).norm(), 1.5 + 1e-9);
    if (&p != &wp.back()) {
      EXPECT_TRUE(grid.SegmentFree(prev, p) || (p - prev).norm() < 0.2);
    }
    max_y = std::max(max_y, p.y());
    prev = p;
  }
  EXPECT_GT(max_y, 2.0) << "the path passes the wall's end";
}

TEST(NavigationTest, UnreachableGoalGivesNoPath) {
  scene::Scene s;
  scene::Object box;
  box.category = "cabinet";
  box.instance = "box";
  scene::Part p;
  p.name = "body";
  p.mesh = scene::TriangleMesh::Box({-1, -1, 0}, {1, 1, 1});
  box.parts.push_back(p);
  s.objects.push_back(box);
  const scene::SceneHeightGrid heights(s);
  NavigationConfig c;
  c.margin = 0.5;
  const FreeSpaceGrid grid(s, heights, c);
  EXPECT_TRUE(grid.FindPath({0, 0}, {1.4, 1.4}).empty()) << "start deep inside the box";
  EXPECT_FALSE(grid.FindPath({-1.4, -1.4}, {1.4, 1.4}).empty());
}

TEST(PathFollowerTest, CarrotLeadsAlongThePathAndStopsAtTheGoal) {
  // An L-shaped path: east 2 m, then north 2 m.
  PathFollower f({0, 0}, {{2, 0}, {2, 2}});
  EXPECT_NEAR(PathLength({0, 0}, {{2, 0}, {2, 2}}), 4.0, 1e-12);
  Eigen::Vector2d c = f.Carrot({0, 0}, 1.0);
  EXPECT_TRUE(c.isApprox(Eigen::Vector2d(1, 0))) << c.transpose();
  // Near the corner the carrot already turns north.
  c = f.Carrot({1.5, 0.1}, 1.0);
  EXPECT_TRUE(c.isApprox(Eigen::Vector2d(2, 0.5))) << c.transpose();
  EXPECT_FALSE(f.IsEnd(c));
  c = f.Carrot({2.0, 1.5}, 1.0);
  EXPECT_TRUE(f.IsEnd(c)) << "within the lookahead of the goal the carrot is the goal";
}

TEST(PathFollowerTest, ProjectionNeverJumpsAcrossAWall) {
  // A U-turn around a wall: out along y = 0, back along y = 1.
  PathFollower f({0, 0}, {{5, 0}, {5, 1}, {0, 1}});
  // At the start, the path's return leg is 1 m away (behind the wall) but far along the path.
  const Eigen::Vector2d c = f.Carrot({0.2, 0.4}, 1.0);
  EXPECT_NEAR(c.y(), 0.0, 1e-12) << "stays on the outbound leg";
  EXPECT_NEAR(c.x(), 1.2, 1e-9);
  // The projection does not go backwards when the character drifts back.
  f.Carrot({3.0, 0.0}, 1.0);
  EXPECT_NEAR(f.Carrot({2.0, 0.0}, 1.0).x(), 4.0, 1e-9);
}

// A snapshot keeps the points and the projection; restoring them resumes the same carrots.
TEST(PathFollowerTest, RestoredProgressResumesTheSameCarrots) {
  PathFollower f({0, 0}, {{5, 0}, {5, 1}, {0, 1}});
  for (const Eigen::Vector2d here :
       {Eigen::Vector2d(2, 0), Eigen::Vector2d(4, 0), Eigen::Vector2d(5, 0.5)})
    f.Carrot(here, 1.0);
  ASSERT_EQ(f.segment(), 1u);
  PathFollower g(f.points().front(), {f.points().begin() + 1, f.points().end()});
  g.Restore(f.segment(), f.progress());
  // From the start of the path the restored follower does not jump back.
  EXPECT_TRUE(g.Carrot({0.0, 0.0}, 1.0).isApprox(f.Carrot({0.0, 0.0}, 1.0)));
  PathFollower h({0, 0}, {{1, 0}});
  h.Restore(7, 3.0);  // out of range: clamped to the last segment's end
  EXPECT_EQ(h.segment(), 0u);
  EXPECT_EQ(h.progress(), 1.0);
}

}  // namespace
}  // namespace sims::scene
