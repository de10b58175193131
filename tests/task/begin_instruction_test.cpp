// Starting skills mid-episode (the FSM path): goals come from the named object without any
// reset of the character.
#include <gtest/gtest.h>

#include "sims/scene/builtin.h"
#include "sims/task/getup/getup.h"
#include "sims/task/reach/reach.h"
#include "sims/task/sit/sit.h"

namespace sims::task {
namespace {

struct Fixture {
  explicit Fixture(const std::string& skill, const std::string& scene_name) {
    SkillConfig c;
    c.skill = skill;
    setup = CreateSkill(c, 1, 0, std::make_shared<scene::Scene>(scene::BuiltinScene(scene_name)));
    sim::EnvConfig ec;
    ec.num_envs = 1;
    ec.threads = 1;
    env = std::make_unique<sim::BatchedEnv>(setup.context.humanoid, ec, setup.skill);
  }
  sim::EnvView View() { return env->View(0); }
  SkillSetup setup;
  std::unique_ptr<sim::BatchedEnv> env;
};

TEST(BeginInstructionTest, SitTargetsTheNamedSeat) {
  Fixture f("sit", "chair");
  const Eigen::Vector3d before = f.env->pose(0).root_pos;
  InstructionTarget t;
  t.object = 0;
  ASSERT_TRUE(f.setup.skill->BeginInstruction(f.View(), t));
  EXPECT_TRUE(f.env->pose(0).root_pos.isApprox(before)) << "no reset";
  EXPECT_TRUE(f.setup.skill->goal_mask(0) & (1u << humanoid::kCjPelvis));
  const auto seat = f.setup.context.scene->objects[0].FindPart("seat surface")->mesh.Bounds();
  const Eigen::Vector3d g = f.setup.skill->goal(0, humanoid::kCjPelvis);
  EXPECT_GE(g.z(), seat.max.z() - 0.05);
  EXPECT_LE((g.head<2>() - seat.center().head<2>()).norm(), seat.size().head<2>().norm());
  t.object = 99;
  EXPECT_FALSE(f.setup.skill->BeginInstruction(f.View(), t)) << "not an object of this scene";
}

// Stories sit on beds: the mattress's foot end (+x, away from the headboard) is the seat
// front, the target behind it at the seated height, the stand point in front of it.
TEST(BeginInstructionTest, SitOnABedTargetsTheFootEndOfTheMattress) {
  Fixture f("sit", "bed");
  InstructionTarget t;
  t.object = 0;
  ASSERT_TRUE(f.setup.skill->BeginInstruction(f.View(), t));
  const auto mattress = f.setup.context.scene->objects[0].FindPart("mattress")->mesh.Bounds();
  const Eigen::Vector3d g = f.setup.skill->goal(0, humanoid::kCjPelvis);
  const SkillConfig& c = f.setup.skill->config();
  EXPECT_NEAR(g.x(), mattress.max.x() - c.sit.target_behind_edge, 1e-6);
  EXPECT_NEAR(g.y(), mattress.center().y(), 1e-6);
  EXPECT_NEAR(g.z(), mattress.max.z() + c.sit.pelvis_height, 1e-6);
  auto* sit = dynamic_cast<SitSkill*>(f.setup.skill.get());
  ASSERT_NE(sit, nullptr);
  EXPECT_GT(sit->anchor(0).x(), mattress.max.x()) << "the stand point is in front of the foot end";
}

TEST(BeginInstructionTest, ReachUsesCaptionHandAndHeight) {
  Fixture f("reach", "shelf");
  auto* reach = dynamic_cast<ReachSkill*>(f.setup.skill.get());
  ASSERT_NE(reach, nullptr);
  InstructionTarget t;
  t.object = 0;
  t.hand = humanoid::kCjLeftHand;
  t.height = "high";
  ASSERT_TRUE(reach->BeginInstruction(f.View(), t));
  EXPECT_EQ(reach->hand(0), humanoid::kCjLeftHand);
  const double high = reach->target(0).z();
  t.height = "low";
  ASSERT_TRUE(reach->BeginInstruction(f.View(), t));
  EXPECT_LT(reach->target(0).z(), high);
}

TEST(BeginInstructionTest, GetUpStandsAtTheGivenPoint) {
  Fixture f("getup", "chair");
  auto* up = dynamic_cast<GetUpSkill*>(f.setup.skill.get());
  ASSERT_NE(up, nullptr);
  InstructionTarget t;
  t.point = {2.5, 1.0, 0};
  t.has_point = true;
  ASSERT_TRUE(up->BeginInstruction(f.View(), t)) << "no object: the nearest seat is used";
  EXPECT_TRUE(up->stand_point(0).isApprox(Eigen::Vector2d(2.5, 1.0)));
}

}  // namespace
}  // namespace sims::task
