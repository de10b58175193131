#include "sims/task/handoff.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/error.h"

namespace sims::task {
namespace {

// An object at (x, y) turned by yaw with one part `name` of box [lo, hi] (object frame).
ObjectGeometry Furniture(double x, double y, double yaw, const std::string& name,
                         const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  ObjectGeometry g;
  g.object = 0;
  g.yaw = yaw;
  g.X_WO = Eigen::Translation3d(x, y, 0) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  ObjectPart p;
  p.index = 0;
  p.name = name;
  p.local.min = lo;
  p.local.max = hi;
  g.parts.push_back(p);
  g.local = p.local;
  return g;
}

// A pose whose pelvis sits at p_AP from g's anchor, turned by `yaw` relative to the object,
// with some velocity.
humanoid::HumanoidPose PoseOn(const ObjectGeometry& g, const std::string& part,
                              const Eigen::Vector3d& p_AP, double yaw) {
  humanoid::HumanoidPose p;
  p.root_pos = g.X_WO * (HandoffAnchor(part, g.part_local(part)) + p_AP);
  p.root_rot = Eigen::AngleAxisd(g.yaw + yaw, Eigen::Vector3d::UnitZ()) *
               Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY());
  p.root_lin_vel = g.X_WO.linear() * Eigen::Vector3d(0.3, -0.1, 0.05);
  p.root_ang_vel = g.X_WO.linear() * Eigen::Vector3d(0.0, 0.2, 1.0);
  p.dof_pos.setConstant(0.1);
  p.dof_vel.setConstant(-0.2);
  return p;
}

// Where the pelvis of world pose p sits relative to g's anchor, in the object frame.
Eigen::Vector3d RelativeToAnchor(const ObjectGeometry& g, const std::string& part,
                                 const humanoid::HumanoidPose& p) {
  return g.X_WO.inverse() * p.root_pos - HandoffAnchor(part, g.part_local(part));
}

const std::string kSeat(kSeatPart);
const std::string kMattress(kMattressPart);

TEST(HandoffTest, AnchorsAreTheSeatFrontAndTheMattressHead) {
  scene::Aabb box;
  box.min = {-0.2, -0.3, 0.1};
  box.max = {0.4, 0.5, 0.45};
  EXPECT_TRUE(HandoffAnchor(kSeat, box).isApprox(Eigen::Vector3d(0.4, 0.1, 0.45)));
  EXPECT_TRUE(HandoffAnchor(kMattress, box).isApprox(Eigen::Vector3d(-0.2, 0.1, 0.45)));
}

// A slumped seated state recorded on one chair lands on another chair (moved, turned, 2 cm
// higher, 5 cm deeper) at the same place relative to the seat's front edge, turned with it.
TEST(HandoffTest, PlacingKeepsThePoseRelativeToThePartsAnchor) {
  const ObjectGeometry a =
      Furniture(1.0, 2.0, 0.3, kSeat, {-0.25, -0.25, 0.40}, {0.25, 0.25, 0.45});
  const ObjectGeometry b =
      Furniture(-3.0, 0.5, -1.2, kSeat, {-0.35, -0.30, 0.40}, {0.20, 0.30, 0.47});
  const Eigen::Vector3d p_AP(-0.15, 0.05, 0.1);
  const humanoid::HumanoidPose on_a = PoseOn(a, kSeat, p_AP, 0.7);
  const HandoffState s = MakeHandoffState("sit", kSeat, a, on_a, true);
  EXPECT_EQ(s.part, kSeat);
  EXPECT_TRUE(s.part_O.max.isApprox(Eigen::Vector3d(0.25, 0.25, 0.45)));

  const auto on_b = PlaceHandoffState(s, b);
  ASSERT_TRUE(on_b.has_value());
  // Raised with the 2 cm higher seat: the same place on it, the feet 2 cm above the floor.
  EXPECT_TRUE(RelativeToAnchor(b, kSeat, *on_b).isApprox(p_AP, 1e-9))
      << RelativeToAnchor(b, kSeat, *on_b).transpose();
  // The orientation and velocities turn with the object.
  const Eigen::Quaterniond q_a = Eigen::Quaterniond(a.X_WO.linear()).inverse() * on_a.root_rot;
  const Eigen::Quaterniond q_b = Eigen::Quaterniond(b.X_WO.linear()).inverse() * on_b->root_rot;
  EXPECT_NEAR(q_a.angularDistance(q_b), 0.0, 1e-9);
  EXPECT_TRUE((b.X_WO.linear().transpose() * on_b->root_lin_vel)
                  .isApprox(a.X_WO.linear().transpose() * on_a.root_lin_vel, 1e-9));
  EXPECT_TRUE((b.X_WO.linear().transpose() * on_b->root_ang_vel)
                  .isApprox(a.X_WO.linear().transpose() * on_a.root_ang_vel, 1e-9));
  EXPECT_EQ(on_b->dof_pos, on_a.dof_pos);
  EXPECT_EQ(on_b->dof_vel, on_a.dof_vel);

  // A 3 cm lower seat: no shift down (the pelvis hovers 3 cm higher over it, the feet stay on
  // the floor).
  const ObjectGeometry lower =
      Furniture(0.0, 0.0, 0.0, kSeat, {-0.25, -0.25, 0.38}, {0.25, 0.25, 0.42});
  const auto on_lower = PlaceHandoffState(s, lower);
  ASSERT_TRUE(on_lower.has_value());
  EXPECT_TRUE(
      RelativeToAnchor(lower, kSeat, *on_lower).isApprox(p_AP + Eigen::Vector3d(0, 0, 0.03)));

  // What does not fit: 8 cm higher, 20 cm deeper, a narrow seat the pelvis would miss, a bed.
  EXPECT_FALSE(
      PlaceHandoffState(s, Furniture(0, 0, 0, kSeat, {-0.25, -0.25, 0.45}, {0.25, 0.25, 0.53})));
  EXPECT_FALSE(
      PlaceHandoffState(s, Furniture(0, 0, 0, kSeat, {-0.45, -0.25, 0.40}, {0.25, 0.25, 0.45})));
  const HandoffState aside =
      MakeHandoffState("sit", kSeat, a, PoseOn(a, kSeat, {-0.2, 0.2, 0.1}, 0.0), false);
  EXPECT_FALSE(
      PlaceHandoffState(aside, Furniture(0, 0, 0, kSeat, {-0.25, -0.1, 0.40}, {0.25, 0.1, 0.45})));
  EXPECT_FALSE(
      PlaceHandoffState(s, Furniture(0, 0, 0, kMattress, {-1, -0.7, 0.3}, {1, 0.7, 0.45})));
}

// A lying state keeps its place from the bed's head end: on a longer bed the head stays at
// the pillow.
TEST(HandoffTest, LyingStatesKeepTheirPlaceFromTheHeadEnd) {
  const ObjectGeometry a = Furniture(0, 0, 0, kMattress, {-1.0, -0.7, 0.3}, {1.0, 0.7, 0.5});
  const ObjectGeometry b =
      Furniture(2, 2, M_PI / 2, kMattress, {-1.04, -0.8, 0.3}, {1.04, 0.8, 0.5});
  const Eigen::Vector3d p_AP(0.9, 0.1, 0.11);
  const HandoffState s =
      MakeHandoffState("lie", kMattress, a, PoseOn(a, kMattress, p_AP, 1.5), true);
  const auto on_b = PlaceHandoffState(s, b);
  ASSERT_TRUE(on_b.has_value());
  EXPECT_TRUE(RelativeToAnchor(b, kMattress, *on_b).isApprox(p_AP, 1e-9));
}

TEST(HandoffTest, SaveLoadRoundTripAndBadInput) {
  const ObjectGeometry a =
      Furniture(1.0, 2.0, 0.3, kSeat, {-0.25, -0.25, 0.40}, {0.25, 0.25, 0.45});
  std::vector<HandoffState> states = {
      MakeHandoffState("sit", kSeat, a, PoseOn(a, kSeat, {-0.1, 0, 0.1}, 0.2), true),
      MakeHandoffState("sit", kSeat, a, PoseOn(a, kSeat, {0.3, 0, 0.45}, 3.0), false)};
  const auto dir = sims::testing::TempDir("handoff");
  const auto path = dir / "states.json";
  SaveHandoffStates(states, path);
  const std::vector<HandoffState> back = LoadHandoffStates(path);
  ASSERT_EQ(back.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back[k].skill, "sit");
    EXPECT_EQ(back[k].part, kSeat);
    EXPECT_EQ(back[k].success, states[k].success);
    EXPECT_TRUE(back[k].part_O.min.isApprox(states[k].part_O.min, 1e-5));
    EXPECT_LT((back[k].pose.root_pos - states[k].pose.root_pos).norm(), 1e-4);
    EXPECT_LT(back[k].pose.root_rot.angularDistance(states[k].pose.root_rot), 1e-4);
    EXPECT_LT((back[k].pose.dof_vel - states[k].pose.dof_vel).norm(), 1e-4);
    EXPECT_LT((back[k].pose.root_ang_vel - states[k].pose.root_ang_vel).norm(), 1e-4);
  }
  // One state per line.
  std::ifstream in(path);
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 4);

  auto expect_error = [&](const std::string& text, const std::string& field) {
    const auto bad = dir / "bad.json";
    std::ofstream(bad) << text;
    try {
      LoadHandoffStates(bad);
      FAIL() << "accepted " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
  };
  expect_error(R"({"format": "other", "version": 1, "states": []})", "'format'");
  expect_error(R"({"format": "sims-handoff-states", "version": 1, "states": []})", "'states'");
  expect_error(R"({"format": "sims-handoff-states", "version": 1, "states": [{"skill": "sit",
      "part": "seat surface", "part_min": [0, 0, 0], "part_max": [1, 1, 1],
      "root_pos": [0, 0, 1], "root_rot_wxyz": [1, 0, 0, 0], "root_lin_vel": [0, 0, 0],
      "root_ang_vel": [0, 0, 0], "dof_pos": [0, 0]}]})",
               "states[0].dof_pos");
  expect_error(R"({"format": "sims-handoff-states", "version": 1, "states": [{"skill": "sit",
      "part": "", "part_min": [0, 0, 0]}]})",
               "states[0].part");
}

}  // namespace
}  // namespace sims::task
