#include "sims/task/sit/sit.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "sims/motion/mirror.h"
#include "sims/scene/contact_targets.h"
#include "sims/sim/features.h"
#include "task/task_test_util.h"

namespace sims::task {
namespace {

using testing::MakeSkillEnv;
using testing::PoseAt;
using testing::ViewOf;

TEST(ContactRewardTest, MatchesTheStatedFormula) {
  const Eigen::Vector2d zero(0, 0), x(1, 0);
  // Near (d² ≤ 0.5): 0.6·r_near + 0.4.
  EXPECT_NEAR(ContactReward(Eigen::Vector2d(0.5, 0.4), zero, zero, x, 1.0, 0.04),
              0.6 * std::exp(-0.4) + 0.4, 1e-12);
  // Far, walking at v* toward the anchor and facing it.
  const Eigen::Vector2d anchor(3, 0);
  const double r_far = 0.5 * std::exp(-0.5 * 9) + 0.4 * 1.0 + 0.1 * 1.0;
  EXPECT_NEAR(ContactReward(anchor, zero, x, x, 1.0, 9.0), 0.6 * std::exp(-90.0) + 0.4 * r_far,
              1e-12);
  // Far, standing and facing sideways: speed error 1, facing term 0.
  const double r_far2 = 0.5 * std::exp(-0.5 * 9) + 0.4 * std::exp(-2.0);
  EXPECT_NEAR(ContactReward(anchor, zero, zero, Eigen::Vector2d(0, 1), 1.0, 0.0),
              0.6 + 0.4 * r_far2, 1e-12);
  // Facing away still counts (the term is squared).
  EXPECT_NEAR(ContactReward(anchor, zero, zero, -x, 1.0, 0.0),
              ContactReward(anchor, zero, zero, x, 1.0, 0.0), 1e-12);
}

SkillConfig SitConfig() {
  SkillConfig c;
  c.skill = "sit";
  c.object.num_objects = 4;
  c.object.object_categories = {"chair", "sofa"};
  c.motion.manifest = testing::SyntheticManifest({"sit"});
  c.motion.skills = {"sit"};
  return c;
}

TEST(SitSkillTest, TrainingGroundAndObservation) {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 0;
  auto s = MakeSkillEnv(c, 4);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  ASSERT_NE(sit, nullptr);
  EXPECT_EQ(s.env->obs_dim(), 223 + 60 + 256 + 64);
  ASSERT_EQ(sit->objects().size(), 4u);
  // Objects sit on the 12 m grid, two of each category.
  const auto& scene = *s.setup.context.scene;
  EXPECT_EQ(scene.objects[0].category, "chair");
  EXPECT_EQ(scene.objects[1].category, "sofa");
  EXPECT_NEAR(sit->objects()[1].center.x(), kTrainingGroundSpacing, 0.3);
  for (int i = 0; i < 4; ++i) {
    // Default init: standing spawn_min..spawn_max beyond the chosen object's footprint.
    const ObjectGeometry& g = sit->geometry(i);
    const double d = (s.env->pose(i).root_pos.head<2>() - g.center).norm();
    EXPECT_GE(d, g.radius + c.object.spawn_min_distance - 1e-9);
    EXPECT_LE(d, g.radius + c.object.spawn_max_distance + 1e-9);
    EXPECT_EQ(sit->goal_mask(i), 1u << sim::kCjPelvis);
    // The pelvis goal is the seat point nearest to the pelvis.
    const Eigen::Vector3d pelvis = s.env->bodies(i).pos[sim::kPelvis];
    const Eigen::Vector3d seat = sit->PelvisTarget(i, pelvis);
    EXPECT_NEAR((sit->goal(i, sim::kCjPelvis) - seat).norm(), 0, 1e-9);
    const float* o = s.env->observations() + i * s.env->obs_dim() + 223;
    EXPECT_NEAR(Eigen::Vector3d(o[0], o[1], o[2]).norm(), (seat - pelvis).norm(), 1e-4);
    EXPECT_EQ(o[3], 1.0f);
  }
}

TEST(SitSkillTest, SeatClipsLandOnTheSeat) {
  // Every sit clip (and its mirror) placed on every object ends with the pelvis just above the
  // seat surface, within the sit success threshold.
  SkillConfig c = SitConfig();
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const auto& lib = *s.setup.context.motions;
  const auto& scene = *s.setup.context.scene;
  sim::MjDataPtr scratch = sim::MakeData(s.setup.context.humanoid->model());
  int checked = 0;
  for (const auto& g : sit->objects()) {
    for (int clip : lib.Find("sit")) {
      Eigen::Vector2d p_clip;
      double yaw_clip = 0, dz = 0;
      ASSERT_TRUE(ClipFurnitureFrame(lib.clip(clip), g, 0.0, &p_clip, &yaw_clip, &dz));
      if (std::abs(dz) > kMaxClipHeightMismatch) continue;
      const auto place =
          ClipPlacement::Align(g.X_WO.translation().head<2>(), g.yaw, p_clip, yaw_clip, dz);
      const auto& clipref = lib.clip(clip);
      sim::BodyStates b;
      sim::ForwardKinematics(*s.setup.context.humanoid,
                             place.Apply(clipref.FramePose(clipref.num_frames() - 1)),
                             scratch.get(), &b);
      const Eigen::Vector3d pelvis = b.pos[sim::kPelvis];
      const Eigen::Vector3d seat =
          scene::NearestPointOnPart(scene.objects[g.object].parts[g.seat], pelvis);
      EXPECT_LT((seat - pelvis).norm(), c.object.contact_success_threshold) << clipref.meta().name;
      EXPECT_GT(pelvis.z(), g.seat_local.max.z()) << clipref.meta().name;
      ++checked;
    }
  }
  EXPECT_GE(checked, 4);
}

TEST(SitSkillTest, ReferenceInitStartsAtTheObject) {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 1.0;
  auto s = MakeSkillEnv(c, 6);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  int reference = 0;
  for (int i = 0; i < 6; ++i) {
    const ObjectGeometry& g = sit->geometry(i);
    const double d = (s.env->pose(i).root_pos.head<2>() - g.center).norm();
    if (d < g.radius + 0.6) ++reference;  // sit clips start 0.2–0.3 m in front of the seat
    EXPECT_GE(sit->style_id(i), 0);
  }
  EXPECT_GE(reference, 4);
}

TEST(SitSkillTest, RewardAndSuccessOnHandMadeStates) {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 0;
  c.object.max_contact_force = 0;  // the standing pose above a seat pushes its legs through it
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const ObjectGeometry& g = sit->geometry(0);
  const Eigen::Vector3d top =
      g.ToWorld(g.seat_local.center()) +
      Eigen::Vector3d(0, 0, 0.5 * (g.seat_local.max.z() - g.seat_local.min.z()));
  for (double h : {0.15, 0.25}) {
    s.env->SetState(0, PoseAt(top + Eigen::Vector3d(0, 0, h), g.yaw));
    const sim::TaskStepResult r = sit->Step(ViewOf(*s.env, 0));
    const double d = s.env->bodies(0).pos[sim::kPelvis].z() - top.z();
    EXPECT_NEAR(d, h, 1e-6);
    EXPECT_NEAR(r.reward, 0.6 * std::exp(-10 * h * h) + 0.4, 1e-5);
    EXPECT_EQ(r.success, h < 0.2);
    EXPECT_NEAR(sit->goal_error(0), h, 1e-6);
    EXPECT_FALSE(r.terminate);
  }
  // 3 m in front of the seat, facing it: the far form.
  const Eigen::Vector3d front = g.ToWorld(Eigen::Vector3d(g.local.max.x() + 3, 0, 0.89));
  s.env->SetState(0, PoseAt(front, g.yaw + M_PI));
  const sim::TaskStepResult r = sit->Step(ViewOf(*s.env, 0));
  const Eigen::Vector3d pelvis = s.env->bodies(0).pos[sim::kPelvis];
  const Eigen::Vector3d seat = sit->PelvisTarget(0, pelvis);
  const Eigen::Vector2d anchor = g.ToWorld(g.seat_local.center()).head<2>();
  const Eigen::Vector2d delta = anchor - pelvis.head<2>();
  const double dir_dot_facing =
      delta.normalized().dot(Eigen::Vector2d(std::cos(g.yaw + M_PI), std::sin(g.yaw + M_PI)));
  const double r_far = 0.5 * std::exp(-0.5 * delta.squaredNorm()) + 0.4 * std::exp(-2.0) +
                       0.1 * dir_dot_facing * dir_dot_facing;
  EXPECT_NEAR(r.reward, 0.6 * std::exp(-10 * (seat - pelvis).squaredNorm()) + 0.4 * r_far, 1e-5);
  EXPECT_FALSE(r.success);
}

TEST(SitSkillTest, SuccessHeldTruncatesAndForceTerminates) {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 0;
  c.success_hold_steps = 3;
  c.object.max_contact_force = 0;
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const ObjectGeometry& g = sit->geometry(0);
  s.env->SetState(0, PoseAt(g.ToWorld(g.seat_local.center()) + Eigen::Vector3d(0, 0, 0.1)));
  for (int k = 1; k <= 3; ++k) {
    const auto r = sit->Step(ViewOf(*s.env, 0));
    EXPECT_TRUE(r.success);
    EXPECT_EQ(r.truncate, k == 3);
    EXPECT_EQ(sit->hold(0), k);
  }
  // In the air no contact force acts; standing on the floor the feet carry the weight.
  s.env->SetState(0, PoseAt(Eigen::Vector3d(g.center.x() + 6, g.center.y(), 2.5)));
  EXPECT_NEAR(ObjectSkill::ContactForce(ViewOf(*s.env, 0)), 0.0, 1e-9);
  sim::HumanoidPose stand = PoseAt(Eigen::Vector3d(g.center.x() + 6, g.center.y(), 0.89));
  s.env->SetState(0, stand);
  std::vector<float> hold(28);
  s.setup.context.humanoid->TargetsToAction(stand.dof_pos.data(), hold.data());
  for (int t = 0; t < 6; ++t) {
    s.env->Step(hold.data());
  }
  const double weight = s.setup.context.humanoid->total_mass() * 9.81;
  const double f = ObjectSkill::ContactForce(ViewOf(*s.env, 0));
  EXPECT_GT(f, 0.3 * weight);
  EXPECT_LT(f, 3.0 * weight);
}

TEST(SitSkillTest, ExcessiveForceTerminates) {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 0;
  c.object.max_contact_force = 1.0;  // any floor contact exceeds 1 N
  auto s = MakeSkillEnv(c, 1);
  std::vector<float> zero(28, 0.0f);
  bool terminated = false;
  for (int t = 0; t < 10 && !terminated; ++t) {
    s.env->Step(zero.data());
    terminated = s.env->terminated()[0] != 0;
  }
  EXPECT_TRUE(terminated);
  EXPECT_EQ(s.env->stats().task_ends, 1);
}

TEST(SitSkillTest, SnapshotRestoresTheEpisode) {
  SkillConfig c = SitConfig();
  auto s = MakeSkillEnv(c, 3);
  std::vector<float> act(3 * 28, 0.1f);
  for (int t = 0; t < 5; ++t) s.env->Step(act.data());
  const std::string snap = s.env->SaveState();
  auto other = MakeSkillEnv(c, 3, 1);
  other.env->LoadState(snap);
  for (int t = 0; t < 10; ++t) {
    s.env->Step(act.data());
    other.env->Step(act.data());
  }
  EXPECT_EQ(0, std::memcmp(s.env->observations(), other.env->observations(),
                           sizeof(float) * 3 * s.env->obs_dim()));
}

TEST(SitSkillTest, SameSeedSameEpisodesAtAnyThreadCount) {
  SkillConfig c = SitConfig();
  auto run = [&](int threads) {
    auto setup = CreateSkill(c, 4, 1);
    sim::EnvConfig ec;
    ec.num_envs = 4;
    ec.threads = threads;
    ec.seed = 3;
    sim::BatchedEnv env(setup.context.humanoid, ec, setup.skill);
    std::vector<float> act(4 * 28, -0.2f);
    for (int t = 0; t < 8; ++t) env.Step(act.data());
    return std::vector<float>(env.observations(), env.observations() + 4 * env.obs_dim());
  };
  EXPECT_EQ(run(1), run(2));
}

}  // namespace
}  // namespace sims::task
