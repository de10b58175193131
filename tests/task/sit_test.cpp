#include "sims/task/sit/sit.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>

#include <gtest/gtest.h>

#include "sims/humanoid/features.h"
#include "sims/motion/mirror.h"
#include "sims/scene/contact_targets.h"
#include "task/task_test_util.h"

namespace sims::task {
namespace {

using testing::MakeSkillEnv;
using testing::PoseAt;
using testing::ViewOf;

TEST(ContactRewardTest, MatchesTheStatedFormula) {
  const Eigen::Vector2d zero(0, 0), x(1, 0);
  // Within √0.5 m of the anchor: r_far = 1, so 0.7·r_near + 0.3.
  EXPECT_NEAR(ContactReward(Eigen::Vector2d(0.5, 0.4), zero, zero, x, 1.0, 0.04),
              0.7 * std::exp(-0.4) + 0.3, 1e-12);
  // Far, walking at v* toward the anchor and facing it.
  const Eigen::Vector2d anchor(3, 0);
  const double r_far = 0.5 * std::exp(-0.5 * 9) + 0.4 * 1.0 + 0.1 * 1.0;
  EXPECT_NEAR(ContactReward(anchor, zero, x, x, 1.0, 9.0), 0.7 * std::exp(-90.0) + 0.3 * r_far,
              1e-12);
  // Far, standing and facing sideways: standing still earns no speed term, facing 0.
  const double r_far2 = 0.5 * std::exp(-0.5 * 9);
  EXPECT_NEAR(ContactReward(anchor, zero, zero, Eigen::Vector2d(0, 1), 1.0, 0.0),
              0.7 + 0.3 * r_far2, 1e-12);
  // Walking away at v* and facing away: no speed and no facing reward.
  EXPECT_NEAR(ContactReward(anchor, zero, -x, -x, 1.0, 0.0), 0.7 + 0.3 * r_far2, 1e-12);
  // Walking toward it at half speed, facing 60° off: exp(−2·0.25) and cos 60° = 0.5.
  const Eigen::Vector2d half(0.5, std::sqrt(3.0) / 2);
  const double r_far3 = 0.5 * std::exp(-0.5 * 9) + 0.4 * std::exp(-0.5) + 0.1 * 0.5;
  EXPECT_NEAR(ContactReward(anchor, zero, 0.5 * x, half, 1.0, 0.0), 0.7 + 0.3 * r_far3, 1e-12);
  EXPECT_NEAR(FarReward(anchor, zero, 0.5 * x, half, 1.0), r_far3, 1e-12);
  // The near term with a share of the wide kernel: (1 − s)·exp(−10·Σ) + s·exp(−Σ).
  EXPECT_NEAR(NearReward(1.4), std::exp(-14.0), 1e-15);
  EXPECT_NEAR(NearReward(1.4, 0.5), 0.5 * std::exp(-14.0) + 0.5 * std::exp(-1.4), 1e-12);
  EXPECT_NEAR(NearReward(0.0, 0.5), 1.0, 1e-15);
  // ... and of the precise kernel exp(−100·Σ): at 0.2 m it pays 0.018 where exp(−10·Σ) pays 0.67.
  EXPECT_NEAR(NearReward(0.04, 0.0, 0.5), 0.5 * std::exp(-0.4) + 0.5 * std::exp(-4.0), 1e-12);
  EXPECT_NEAR(NearReward(0.04, 0.2, 0.3),
              0.5 * std::exp(-0.4) + 0.2 * std::exp(-0.04) + 0.3 * std::exp(-4.0), 1e-12);
  EXPECT_NEAR(NearReward(0.0, 0.2, 0.8), 1.0, 1e-15);
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

// SitConfig for poses placed by hand: default starts only, and no force termination (a standing
// pose placed above a seat pushes its legs through it).
SkillConfig HandPlacedSitConfig() {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 0;
  c.object.max_contact_force = 0;
  return c;
}

TEST(SitSkillTest, TrainingGroundAndObservation) {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 0;
  auto s = MakeSkillEnv(c, 4);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  ASSERT_NE(sit, nullptr);
  // self 223 | contact goals 60 | task 29 | heightmap 256 | z 64.
  EXPECT_EQ(s.env->obs_dim(), 223 + 60 + kObjectObsDim + 256 + 64);
  const auto segs = sit->obs_segments();
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_EQ(segs[1].name, "task");
  EXPECT_EQ(segs[1].offset, 60);
  EXPECT_EQ(segs[1].size, kObjectObsDim);
  EXPECT_EQ(segs[2].offset, 60 + kObjectObsDim);
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
    EXPECT_EQ(sit->goal_mask(i), 1u << humanoid::kCjPelvis);
    // The pelvis goal is the fixed target: behind the seat's front edge (at most its centre),
    // the seated pelvis height above its top, at the episode's place along the seat.
    const Eigen::Vector3d t_O = g.X_WO.inverse() * sit->target(i);
    const scene::Aabb& seat = g.part_local(kSeatPart);
    EXPECT_NEAR(t_O.x(), std::max(seat.center().x(), seat.max.x() - 0.2), 1e-9);
    EXPECT_NEAR(t_O.y(), seat.center().y() + sit->lateral(i), 1e-9);
    EXPECT_NEAR(t_O.z(), seat.max.z() + 0.085, 1e-9);
    EXPECT_LE(std::abs(sit->lateral(i)), 0.5 * (seat.max.y() - seat.min.y()));
    EXPECT_NEAR((sit->goal(i, humanoid::kCjPelvis) - sit->target(i)).norm(), 0, 1e-12);
    // The far anchor stands kStandDistance in front of the object.
    const Eigen::Vector3d a_O =
        g.X_WO.inverse() * Eigen::Vector3d(sit->anchor(i).x(), sit->anchor(i).y(), 0);
    EXPECT_NEAR(a_O.x(), g.local.max.x() + kStandDistance, 1e-9);
    // Observation: contact goal, then the task segment in the pelvis heading frame.
    const humanoid::BodyStates& b = s.env->bodies(i);
    const Eigen::Vector3d pelvis = b.pos[humanoid::kPelvis];
    const Eigen::Quaterniond h_inv = humanoid::HeadingInverse(b.rot[humanoid::kPelvis]);
    const float* o = s.env->observations() + i * s.env->obs_dim() + 223;
    EXPECT_NEAR(Eigen::Vector3d(o[0], o[1], o[2]).norm(), (sit->target(i) - pelvis).norm(), 1e-4);
    EXPECT_EQ(o[3], 1.0f);
    const float* task = o + 60;
    const Eigen::Vector3d t_H = h_inv * (sit->target(i) - pelvis);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(task[k], t_H[k], 1e-5);
    // Corner 7 is the box's (max x, max y, max z) corner.
    const Eigen::Vector3d c7 = h_inv * (g.ToWorld(g.local.max) - pelvis);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(task[3 + 3 * 7 + k], c7[k], 1e-5);
    const Eigen::Vector3d c0 = h_inv * (g.ToWorld(g.local.min) - pelvis);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(task[3 + k], c0[k], 1e-5);
    // Facing: the object's +x in the heading frame, a unit vector.
    const double yaw_rel = g.yaw - humanoid::HeadingAngle(b.rot[humanoid::kPelvis]);
    EXPECT_NEAR(task[27], std::cos(yaw_rel), 1e-5);
    EXPECT_NEAR(task[28], std::sin(yaw_rel), 1e-5);
  }
}

TEST(SitSkillTest, SeatClipsLandOnTheTarget) {
  // Every sit clip (and its mirror) placed on every object ends with the pelvis on the skill's
  // fixed target, well within the sit success threshold; that is what "error ≤ 0.07 m" asks.
  SkillConfig c = SitConfig();
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const auto& lib = *s.setup.context.motions;
  humanoid::MjDataPtr scratch = humanoid::MakeData(s.setup.context.humanoid->model());
  int checked = 0;
  for (size_t k = 0; k < sit->objects().size(); ++k) {
    const ObjectGeometry& g = sit->objects()[k];
    const scene::Aabb& seat = g.part_local(kSeatPart);
    const Eigen::Vector3d mid = seat.center();
    const Eigen::Vector3d target =
        g.ToWorld({std::max(mid.x(), seat.max.x() - 0.2), mid.y(), seat.max.z() + 0.085});
    for (int clip : lib.Find("sit")) {
      Eigen::Vector2d p_clip;
      double yaw_clip = 0, dz = 0;
      ASSERT_TRUE(ClipFurnitureFrame(lib.clip(clip), g, 0.0, &p_clip, &yaw_clip, &dz));
      if (std::abs(dz) > kMaxClipHeightMismatch) continue;
      const auto place =
          ClipPlacement::Align(g.X_WO.translation().head<2>(), g.yaw, p_clip, yaw_clip, dz);
      const auto& clipref = lib.clip(clip);
      humanoid::BodyStates b;
      humanoid::ForwardKinematics(*s.setup.context.humanoid,
                                  place.Apply(clipref.FramePose(clipref.num_frames() - 1)),
                                  scratch.get(), &b);
      const Eigen::Vector3d pelvis = humanoid::ContactJointPosition(b, humanoid::kCjPelvis);
      EXPECT_LT((target - pelvis).norm(), 0.07) << clipref.meta().name;
      ++checked;
    }
  }
  EXPECT_GE(checked, 4);
}

TEST(SitSkillTest, ReferenceStartsComeBeforeContactAndSkipIdleClips) {
  SkillConfig c = SitConfig();
  c.motion.manifest = testing::SyntheticManifest({"sit", "walk"});
  c.motion.skills = {"sit", "walk"};
  c.reference_init_prob = 1.0;
  c.object.max_contact_force = 0;
  auto s = MakeSkillEnv(c, 8);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const auto& lib = *s.setup.context.motions;
  // Seated idle clips are already in contact: no pre-contact window, no reference starts.
  int idle = 0, moving = 0;
  for (int clip : lib.Find("sit")) {
    const bool seated_idle = lib.clip(clip).meta().name.find("idle") != std::string::npos;
    if (seated_idle) {
      ++idle;
      EXPECT_LT(sit->pre_contact_time(clip), 0) << lib.clip(clip).meta().name;
    } else {
      ++moving;
      EXPECT_GT(sit->pre_contact_time(clip), kMinPreContactTime) << lib.clip(clip).meta().name;
      EXPECT_LT(sit->pre_contact_time(clip), lib.clip(clip).duration());
    }
  }
  EXPECT_GT(idle, 0);
  EXPECT_GT(moving, 0);
  // Many resets: the reference starts are at the object, none already within the success
  // distance of the target, all from sit-down clips.
  int reference = 0;
  for (int round = 0; round < 6; ++round) {
    for (int i = 0; i < 8; ++i) {
      s.env->ResetEnv(i);
      EXPECT_GT(sit->goal_error(i), c.object.contact_success_threshold);
      const int clip = sit->style_id(i);
      ASSERT_GE(clip, 0);
      EXPECT_EQ(lib.clip(clip).meta().skill, "sit");
      if (!sit->reference_start(i)) continue;  // no clip of a fitting seat height
      ++reference;
      // Within the walk-up of an approach clip at most: in front of the object, near it.
      const ObjectGeometry& g = sit->geometry(i);
      const Eigen::Vector2d p = s.env->pose(i).root_pos.head<2>() - g.center;
      EXPECT_LT(p.norm(), g.radius + 3.0);
      EXPECT_GT(p.dot(Eigen::Vector2d(std::cos(g.yaw), std::sin(g.yaw))), 0);
    }
  }
  EXPECT_GE(reference, 24);
}

TEST(SitSkillTest, ReferenceWindowStartsNearContact) {
  // The same resets with and without a 0.4 s window before contact: windowed starts are all
  // close to the seat (at most ~0.4 s of walking/sitting from contact), unwindowed ones are not.
  auto farthest = [](double window) {
    SkillConfig c = SitConfig();
    c.motion.manifest = testing::SyntheticManifest({"sit", "walk"});
    c.motion.skills = {"sit", "walk"};
    c.reference_init_prob = 1.0;
    c.object.max_contact_force = 0;
    c.object.reference_window = window;
    auto s = MakeSkillEnv(c, 8);
    auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
    double worst = 0;
    int reference = 0;
    for (int round = 0; round < 6; ++round) {
      for (int i = 0; i < 8; ++i) {
        s.env->ResetEnv(i);
        if (!sit->reference_start(i)) continue;
        ++reference;
        EXPECT_GT(sit->goal_error(i), c.object.contact_success_threshold);
        worst = std::max(worst, sit->goal_error(i));
      }
    }
    EXPECT_GE(reference, 24);
    return worst;
  };
  const double windowed = farthest(0.4);
  const double whole = farthest(0.0);
  std::cout << "farthest reference start from the target: window 0.4 s " << windowed
            << " m, whole approach " << whole << " m\n";
  EXPECT_LT(windowed, 0.9);
  EXPECT_GT(whole, 1.2);
}

TEST(SitSkillTest, SpawnCurriculumWidensWithSuccess) {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 0;
  c.success_hold_steps = 2;
  c.object.max_contact_force = 0;
  c.object.spawn_curriculum = true;
  c.object.spawn_curriculum_step = 0.25;
  auto s = MakeSkillEnv(c, 2);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  EXPECT_EQ(sit->spawn_level(0), 0.0);
  // Level 0: default starts at exactly spawn_min_distance beyond the footprint.
  for (int k = 0; k < 3; ++k) {
    s.env->ResetEnv(0);
    const ObjectGeometry& g = sit->geometry(0);
    EXPECT_NEAR((s.env->pose(0).root_pos.head<2>() - g.center).norm(),
                g.radius + c.object.spawn_min_distance, 1e-9);
  }
  EXPECT_EQ(sit->spawn_level(0), 0.0);  // failures at level 0 stay at 0
  // A completed episode raises the level by one step, a failed one lowers it by half a step.
  auto complete = [&]() {
    const ObjectGeometry& g = sit->geometry(0);
    s.env->SetState(0, PoseAt(sit->target(0), g.yaw));
    for (int k = 0; k < c.success_hold_steps; ++k) sit->Step(ViewOf(*s.env, 0));
    s.env->ResetEnv(0);
  };
  complete();
  EXPECT_DOUBLE_EQ(sit->spawn_level(0), 0.25);
  complete();
  EXPECT_DOUBLE_EQ(sit->spawn_level(0), 0.5);
  s.env->ResetEnv(0);  // a failed episode
  EXPECT_DOUBLE_EQ(sit->spawn_level(0), 0.375);
  for (int k = 0; k < 20; ++k) {
    s.env->ResetEnv(0);
    const ObjectGeometry& g = sit->geometry(0);
    const double d = (s.env->pose(0).root_pos.head<2>() - g.center).norm() - g.radius;
    const double far =
        c.object.spawn_min_distance +
        sit->spawn_level(0) * (c.object.spawn_max_distance - c.object.spawn_min_distance);
    EXPECT_GE(d, c.object.spawn_min_distance - 1e-9);
    EXPECT_LE(d, far + 1e-9);
  }
  // Without the curriculum every env spawns over the whole range.
  c.object.spawn_curriculum = false;
  auto full = MakeSkillEnv(c, 1);
  EXPECT_EQ(dynamic_cast<SitSkill*>(full.setup.skill.get())->spawn_level(0), 1.0);
}

// spawn_full_range_share: at level 0 a share of default starts still comes from the whole
// range, the rest from spawn_min_distance.
TEST(SitSkillTest, FullRangeShareKeepsLongApproachesAtLevelZero) {
  SkillConfig c = SitConfig();
  c.reference_init_prob = 0;
  c.object.spawn_curriculum = true;
  c.object.spawn_full_range_share = 0.5;
  c.object.spawn_min_distance = 1.0;
  c.object.spawn_max_distance = 4.0;
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  int near = 0, wide = 0;
  for (int k = 0; k < 40; ++k) {
    s.env->ResetEnv(0);
    sit->SetSpawnLevel(0, 0.0);  // whatever the last (failed) episode did to it
    const ObjectGeometry& g = sit->geometry(0);
    const double d = (s.env->pose(0).root_pos.head<2>() - g.center).norm() - g.radius;
    EXPECT_GE(d, 1.0 - 1e-9);
    EXPECT_LE(d, 4.0 + 1e-9);
    (std::abs(d - 1.0) < 1e-9 ? near : wide) += 1;
  }
  EXPECT_GE(near, 10);
  EXPECT_GE(wide, 10);
  c.object.spawn_full_range_share = 1.5;
  EXPECT_THROW(c.object.Validate(), Error);
}

TEST(SitSkillTest, RewardAndSuccessOnHandMadeStates) {
  SkillConfig c = HandPlacedSitConfig();
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const ObjectGeometry& g = sit->geometry(0);
  const Eigen::Vector3d target = sit->target(0);
  // Above the target (within √0.5 m of the anchor: r_far = 1).
  for (double h : {0.15, 0.25}) {
    s.env->SetState(0, PoseAt(target + Eigen::Vector3d(0, 0, h), g.yaw));
    const sim::TaskStepResult r = sit->Step(ViewOf(*s.env, 0));
    const Eigen::Vector3d pelvis = s.env->bodies(0).pos[humanoid::kPelvis];
    EXPECT_NEAR((pelvis - target).norm(), h, 1e-6);
    EXPECT_LT((sit->anchor(0) - pelvis.head<2>()).squaredNorm(), kFarDistanceSq);
    EXPECT_NEAR(r.reward, 0.7 * std::exp(-10 * h * h) + 0.3, 1e-5);
    EXPECT_EQ(r.success, h < 0.2);
    EXPECT_NEAR(sit->goal_error(0), h, 1e-6);
    EXPECT_FALSE(r.terminate);
  }
  // 3 m in front of the seat, facing it: the far form towards the anchor; the target stays put.
  const Eigen::Vector3d front = g.ToWorld(Eigen::Vector3d(g.local.max.x() + 3, 0, 0.89));
  s.env->SetState(0, PoseAt(front, g.yaw + M_PI));
  const sim::TaskStepResult r = sit->Step(ViewOf(*s.env, 0));
  EXPECT_NEAR((sit->target(0) - target).norm(), 0, 1e-12);
  const Eigen::Vector3d pelvis = s.env->bodies(0).pos[humanoid::kPelvis];
  const Eigen::Vector2d delta = sit->anchor(0) - pelvis.head<2>();
  const double facing =
      delta.normalized().dot(Eigen::Vector2d(std::cos(g.yaw + M_PI), std::sin(g.yaw + M_PI)));
  const double r_far =
      0.5 * std::exp(-0.5 * delta.squaredNorm()) + 0.1 * std::max(0.0, facing);  // standing
  EXPECT_NEAR(r.reward, 0.7 * std::exp(-10 * (target - pelvis).squaredNorm()) + 0.3 * r_far, 1e-5);
  EXPECT_FALSE(r.success);
  // Behind the chair the anchor is still in front: the far term points around the object.
  const Eigen::Vector3d behind = g.ToWorld(Eigen::Vector3d(g.local.min.x() - 0.3, 0, 0.89));
  s.env->SetState(0, PoseAt(behind, g.yaw));
  sit->Step(ViewOf(*s.env, 0));
  EXPECT_GT((sit->anchor(0) - s.env->bodies(0).pos[humanoid::kPelvis].head<2>()).squaredNorm(),
            kFarDistanceSq);
}

// precise_near_share moves that share of r_near to exp(−100·Σ): 0.15 m above the target pays
// 0.7·(0.6·exp(−0.225) + 0.4·exp(−2.25)) + 0.3; shares beyond 1 with lie's wide kernel are refused.
TEST(SitSkillTest, PreciseNearShareSharpensTheNearReward) {
  SkillConfig c = HandPlacedSitConfig();
  c.object.precise_near_share = 0.4;
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const Eigen::Vector3d target = sit->target(0);
  s.env->SetState(0, PoseAt(target + Eigen::Vector3d(0, 0, 0.15), sit->geometry(0).yaw));
  const sim::TaskStepResult r = sit->Step(ViewOf(*s.env, 0));
  EXPECT_NEAR(r.reward, 0.7 * (0.6 * std::exp(-0.225) + 0.4 * std::exp(-2.25)) + 0.3, 1e-5);
  EXPECT_TRUE(r.success);

  c.object.precise_near_share = 1.5;
  const std::string share = sims::testing::ErrorOf([&] { c.object.Validate(); });
  EXPECT_NE(share.find("precise_near_share"), std::string::npos) << share;
  EXPECT_NE(share.find("[0, 1]"), std::string::npos) << share;
  SkillConfig lie = c;
  lie.skill = "lie";
  lie.object.object_categories = {"bed"};
  lie.motion.manifest = testing::SyntheticManifest({"lie"});
  lie.motion.skills = {"lie"};
  lie.object.precise_near_share = 0.6;  // lie pays half of r_near from the wide kernel
  const std::string lie_error = sims::testing::ErrorOf([&] { MakeSkillEnv(lie, 1); });
  EXPECT_NE(lie_error.find("precise_near_share"), std::string::npos) << lie_error;
  EXPECT_NE(lie_error.find("0.5"), std::string::npos) << lie_error;
}

// near_facing_share pays that share of r_near only as the pelvis faces the seat's front: 0.15 m
// above the target, facing out pays all of it, sideways or facing the back rest half (share 0.5).
TEST(SitSkillTest, NearFacingShareRewardsFacingTheSeatsFront) {
  SkillConfig c = HandPlacedSitConfig();
  c.object.near_facing_share = 0.5;
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const double yaw = sit->geometry(0).yaw;
  const Eigen::Vector3d above = sit->target(0) + Eigen::Vector3d(0, 0, 0.15);
  const double r_near = std::exp(-10 * 0.15 * 0.15);
  const std::vector<std::pair<double, double>> cases = {
      {0.0, 1.0}, {M_PI / 2, 0.5}, {M_PI, 0.5}, {M_PI / 3, 0.75}};
  for (const auto& [turn, factor] : cases) {
    s.env->SetState(0, PoseAt(above, yaw + turn));
    const sim::TaskStepResult r = sit->Step(ViewOf(*s.env, 0));
    EXPECT_NEAR(r.reward, 0.7 * r_near * factor + 0.3, 1e-5) << "turned " << turn;
    EXPECT_TRUE(r.success);  // success stays positional
  }
  c.object.near_facing_share = -0.1;
  const std::string error = sims::testing::ErrorOf([&] { c.object.Validate(); });
  EXPECT_NE(error.find("near_facing_share"), std::string::npos) << error;
}

// training_scale_min/max widen the training ground's dimensions around the held-out bands:
// chair seats (nominal 0.45 m) reach below 0.76× and above 1.24× but never into the bands.
TEST(SitSkillTest, WideTrainingScaleKeepsOutOfTheHeldOutBands) {
  SkillConfig c = SitConfig();
  c.object.object_categories = {"chair"};
  c.object.num_objects = 60;
  c.object.training_scale_min = 0.7;
  c.object.training_scale_max = 1.3;
  Rng rng(4);
  const scene::Scene ground = BuildTrainingGround(c, rng, {});
  int outside = 0;
  for (const scene::Object& o : ground.objects) {
    const double f = o.FindPart("seat surface")->mesh.Bounds().max.z() / 0.45;
    EXPECT_FALSE((f > 0.76 + 1e-9 && f < 0.86 - 1e-9) || (f > 1.14 + 1e-9 && f < 1.24 - 1e-9))
        << "held-out seat factor " << f;
    outside += f < 0.76 || f > 1.24;
  }
  EXPECT_GT(outside, 5);  // 30 % of the allowed length lies beyond the bands
  c.object.training_scale_max = 1.05;
  const std::string error = sims::testing::ErrorOf([&] { c.object.Validate(); });
  EXPECT_NE(error.find("training_scale_max"), std::string::npos) << error;
  EXPECT_NE(error.find("[1.1, 2]"), std::string::npos) << error;
}

// clutter_share puts a table before each drawn piece, its long side across the front at a gap
// within the range; tables never become targets, and reference starts whose root would stand
// in a table fall back to standing starts on free floor.
TEST(SitSkillTest, ClutterPutsTablesBeforeSeats) {
  SkillConfig c = SitConfig();
  c.object.num_objects = 12;
  c.object.clutter_share = 1;
  c.object.clutter_gap_min = 0.5;
  c.object.clutter_gap_max = 0.8;
  Rng rng(7);
  const scene::Scene ground = BuildTrainingGround(c, rng, {});
  ASSERT_EQ(ground.objects.size(), 24u);
  for (size_t k = 0; k < ground.objects.size(); k += 2) {
    const scene::Object& seat = ground.objects[k];
    const scene::Object& table = ground.objects[k + 1];
    EXPECT_TRUE(table.category == "table" || table.category == "desk") << table.category;
    const scene::Aabb local = seat.LocalBounds();
    scene::Aabb t_S;  // the table's vertices in the seat's frame
    for (const auto& part : table.parts)
      for (const auto& v : part.mesh.vertices) t_S.Extend(seat.X_WO.inverse() * v);
    const double gap = t_S.min.x() - local.max.x();
    EXPECT_GT(gap, 0.5 - 1e-6) << seat.instance;
    EXPECT_LT(gap, 0.8 + 1e-6) << seat.instance;
    EXPECT_GE(t_S.max.y() - t_S.min.y(), t_S.max.x() - t_S.min.x() - 1e-6) << "long side across";
  }

  c.reference_init_prob = 1;
  c.object.num_objects = 4;
  c.object.clutter_gap_min = c.object.clutter_gap_max = 0.45;
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  ASSERT_NE(sit, nullptr);
  for (const ObjectGeometry& g : sit->objects()) EXPECT_NE(g.category, "table");
  EXPECT_EQ(sit->objects().size(), 4u);
  const scene::SceneHeightGrid& grid = *s.setup.context.height_grid;
  int reference = 0, fallback = 0;
  Rng starts(3);
  for (int t = 0; t < 300; ++t) {
    sim::InitialState init;
    sit->SampleInitialState(0, starts, &init);
    const Eigen::Vector3d& p = init.pose.root_pos;
    (init.reference ? reference : fallback)++;
    const ObjectGeometry& g = sit->geometry(0);
    const Eigen::Vector3d p_O = g.X_WO.inverse() * Eigen::Vector3d(p.x(), p.y(), 0);
    const bool over_piece = p_O.x() > g.local.min.x() - 0.05 && p_O.x() < g.local.max.x() + 0.05 &&
                            p_O.y() > g.local.min.y() - 0.05 && p_O.y() < g.local.max.y() + 0.05;
    if (!over_piece) EXPECT_LT(grid.Height(p.x(), p.y()), 0.05) << "start inside the table";
  }
  // Without tables every draw finds a clip; with them the clips that walk in from the front
  // through the table fall back.
  c.object.clutter_share = 0;
  auto plain = MakeSkillEnv(c, 1);
  int plain_fallback = 0;
  Rng plain_starts(3);
  for (int t = 0; t < 300; ++t) {
    sim::InitialState init;
    plain.setup.skill->SampleInitialState(0, plain_starts, &init);
    plain_fallback += !init.reference;
  }
  EXPECT_GT(reference, 150);
  EXPECT_GT(fallback, 5);
  EXPECT_EQ(plain_fallback, 0);
  c.object.clutter_share = 1;

  c.object.object_categories = {"chair", "table"};
  const std::string error = sims::testing::ErrorOf([&] { c.object.Validate(); });
  EXPECT_NE(error.find("object_categories"), std::string::npos) << error;
  EXPECT_NE(error.find("clutter_share"), std::string::npos) << error;
}

TEST(SitSkillTest, SuccessHeldTruncatesAndForceTerminates) {
  SkillConfig c = HandPlacedSitConfig();
  c.success_hold_steps = 3;
  auto s = MakeSkillEnv(c, 1);
  auto* sit = dynamic_cast<SitSkill*>(s.setup.skill.get());
  const ObjectGeometry& g = sit->geometry(0);
  s.env->SetState(0, PoseAt(sit->target(0) + Eigen::Vector3d(0, 0, 0.05)));
  for (int k = 1; k <= 3; ++k) {
    const auto r = sit->Step(ViewOf(*s.env, 0));
    EXPECT_TRUE(r.success);
    EXPECT_EQ(r.truncate, k == 3);
    EXPECT_EQ(r.completed, k == 3);
    EXPECT_EQ(sit->hold(0), k);
  }
  // In the air no contact force acts; standing on the floor the feet carry the weight.
  s.env->SetState(0, PoseAt(Eigen::Vector3d(g.center.x() + 6, g.center.y(), 2.5)));
  EXPECT_NEAR(ObjectSkill::ContactForce(ViewOf(*s.env, 0)), 0.0, 1e-9);
  humanoid::HumanoidPose stand = PoseAt(Eigen::Vector3d(g.center.x() + 6, g.center.y(), 0.89));
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
  // Logged as a force termination, not a fall.
  EXPECT_EQ(s.env->end_reasons()[0], sim::EndReason::kTaskTerminate);
  EXPECT_EQ(s.env->stats().falls, 0);
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

// Fuzzer findings (tools/fuzz.sh env_state): skill-state values from a checkpoint were cast
// unchecked (a style index past the clips, a NaN object index: UBSan float-cast-overflow).
TEST(SitSkillTest, SnapshotValuesAreChecked) {
  SkillConfig c = SitConfig();
  auto s = MakeSkillEnv(c, 1);
  auto& sit = dynamic_cast<SitSkill&>(*s.setup.skill);
  const std::vector<double> good = sit.SaveEnvState(0);
  const size_t base =
      humanoid::kNumContactJoints * 3;  // goals, then mask, style, object, hold, ...
  const auto rejects = [&](size_t at, double value) {
    std::vector<double> bad = good;
    bad.at(at) = value;
    EXPECT_THROW(sit.LoadEnvState(0, bad), Error) << "value " << value << " at " << at;
  };
  rejects(base, std::nan(""));                                   // mask
  rejects(base, 1 << humanoid::kNumContactJoints);               // mask: an unknown joint
  rejects(base + 1, s.setup.context.motions->num_clips());       // style: past the clips
  rejects(base + 1, 0.5);                                        // style: not an index
  rejects(base + 2, std::nan(""));                               // object
  rejects(base + 2, static_cast<double>(sit.objects().size()));  // object: past the scene
  rejects(base + 3, -1);                                         // hold
  rejects(base + 11, 2);                                         // started: not a flag
  rejects(good.size() - 1, std::nan(""));                        // lateral
  std::vector<double> longer = good;
  longer.push_back(0);
  EXPECT_THROW(sit.LoadEnvState(0, longer), Error);
  EXPECT_THROW(sit.LoadEnvState(0, std::vector<double>(good.begin(), good.end() - 1)), Error);
  sit.LoadEnvState(0, good);
  EXPECT_EQ(sit.SaveEnvState(0), good);
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
