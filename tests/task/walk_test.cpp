#include "sims/task/walk/walk.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "task/task_test_util.h"

namespace sims::task {
namespace {

TEST(WalkRewardTest, MatchesTheStatedFormula) {
  const Eigen::Vector2d zero(0, 0), x(1, 0);
  // At the target and still: 0.4·1 + 0.5 + 0.1·1.
  EXPECT_NEAR(WalkSkill::Reward(zero, zero, zero, zero, x, 1.0), 1.0, 1e-12);
  // 2 m away, moving straight at it at the target speed, facing it.
  const Eigen::Vector2d target(2, 0);
  const double r_far = 0.6 * std::exp(-0.5 * 4) + 0.2 * 1.0 + 0.2 * 1.0;
  EXPECT_NEAR(WalkSkill::Reward(target, zero, x, x, x, 1.0), 0.4 * std::exp(-40.0) + 0.5 * r_far,
              1e-12);
  // Facing sideways and standing: the speed and facing terms vanish (standing still is not
  // moving towards it).
  const double r_far2 = 0.6 * std::exp(-2.0);
  EXPECT_NEAR(WalkSkill::Reward(target, zero, zero, zero, Eigen::Vector2d(0, 1), 1.0),
              0.4 * std::exp(-40.0) + 0.5 * r_far2, 1e-12);
  // Walking away, facing away: neither the speed nor the facing term pays.
  const double r_far3 = 0.6 * std::exp(-2.0);
  EXPECT_NEAR(WalkSkill::Reward(target, zero, -x, -x, -x, 1.0),
              0.4 * std::exp(-40.0) + 0.5 * r_far3, 1e-12);
  // Facing half-way towards it: the facing term is cos 60° = 0.5, not its square.
  const Eigen::Vector2d half(0.5, std::sqrt(3.0) / 2);
  const double r_far4 = 0.6 * std::exp(-2.0) + 0.2 * 0.5;
  EXPECT_NEAR(WalkSkill::Reward(target, zero, zero, zero, half, 1.0),
              0.4 * std::exp(-40.0) + 0.5 * r_far4, 1e-12);
}

TEST(SkillRegistryTest, UnknownSkillListsKnownOnes) {
  try {
    FindSkill("fly");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("walk"), std::string::npos);
  }
}

class WalkEnvTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SkillConfig c;
    c.walk.target_min_distance = 3;
    c.walk.target_max_distance = 5;
    setup_ = CreateSkill(c, 4, 1);
    sim::EnvConfig ec;
    ec.num_envs = 4;
    ec.threads = 2;
    ec.seed = 3;
    env_ = std::make_unique<sim::BatchedEnv>(setup_.context.humanoid, ec, setup_.skill);
  }
  SkillSetup setup_;
  std::unique_ptr<sim::BatchedEnv> env_;
};

TEST_F(WalkEnvTest, ObservationLayoutAndGoals) {
  EXPECT_EQ(env_->obs_dim(), 223 + 60 + 256 + 64);
  auto* walk = dynamic_cast<WalkSkill*>(setup_.skill.get());
  ASSERT_NE(walk, nullptr);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(walk->goal_mask(i), 1u << humanoid::kCjPelvis);
    const double d = (walk->target(i) - env_->pose(i).root_pos.head<2>()).norm();
    EXPECT_GE(d, 3 - 1e-9);
    EXPECT_LE(d, 5 + 1e-9);
    const float* o = env_->observations() + i * env_->obs_dim() + 223;
    // Pelvis goal: horizontal distance preserved in the heading frame, mask set.
    EXPECT_NEAR(std::hypot(o[0], o[1]), d, 1e-4);
    EXPECT_EQ(o[3], 1.0f);
    EXPECT_EQ(o[7], 0.0f);
    // Flat floor: every heightmap value is −root height.
    for (int k = 0; k < 256; ++k) EXPECT_NEAR(o[60 + k], -env_->pose(i).root_pos.z(), 1e-4);
  }
}

TEST_F(WalkEnvTest, SnapshotRestoresTargets) {
  std::vector<float> act(4 * 28, 0.0f);
  for (int t = 0; t < 10; ++t) env_->Step(act.data());
  const std::string snap = env_->SaveState();
  auto other = CreateSkill(setup_.skill->config(), 4, 77);
  sim::EnvConfig ec = env_->config();
  ec.seed = 99;
  sim::BatchedEnv env2(other.context.humanoid, ec, other.skill);
  env2.LoadState(snap);
  for (int t = 0; t < 20; ++t) {
    env_->Step(act.data());
    env2.Step(act.data());
  }
  EXPECT_EQ(0, std::memcmp(env_->observations(), env2.observations(),
                           sizeof(float) * 4 * env_->obs_dim()));
}

// z reaches the policy input: a style-conditioned skill puts its episode's clip z in the last
// 64 observation values, a caption's z once set (run time), and zeros when unconditioned.
TEST(WalkStyleTest, StyleVectorReachesTheObservation) {
  for (const bool conditioned : {true, false}) {
    SkillConfig c;
    c.motion.manifest = testing::SyntheticManifest({"walk"});
    c.motion.skills = {"walk"};
    c.style_conditioned = conditioned;
    auto s = testing::MakeSkillEnv(c, 3);
    ASSERT_TRUE(s.setup.context.styles);
    const int at = s.env->obs_dim() - kStyleDim;
    const std::vector<sim::ObsSegment> segs = s.setup.skill->obs_segments();
    ASSERT_EQ(segs.back().name, "z");
    ASSERT_EQ(segs.back().offset, at - humanoid::kSelfObsDim);
    auto z_of = [&](int i) {
      return Eigen::Map<const Eigen::VectorXf>(s.env->observations() + i * s.env->obs_dim() + at,
                                               kStyleDim);
    };
    for (int i = 0; i < 3; ++i) {
      const int style = s.setup.skill->style_id(i);
      ASSERT_GE(style, 0);
      if (conditioned) {
        EXPECT_EQ(z_of(i), s.setup.context.styles->z(style)) << i;
      } else {
        EXPECT_EQ(z_of(i).squaredNorm(), 0.0f) << i;
      }
    }
    Eigen::VectorXf caption = Eigen::VectorXf::LinSpaced(kStyleDim, -1, 1).normalized();
    s.setup.skill->SetStyleVector(1, caption);
    s.env->RefreshTaskObservation(1);
    if (conditioned) {
      EXPECT_EQ(z_of(1), caption);
    } else {
      EXPECT_EQ(z_of(1).squaredNorm(), 0.0f);
    }
    s.setup.skill->SetStyleVector(1, Eigen::VectorXf());
    s.env->RefreshTaskObservation(1);
    if (conditioned) {
      EXPECT_EQ(z_of(1), s.setup.context.styles->z(s.setup.skill->style_id(1)));
    }
  }
}

// With speed_from_style the speed term asks for the episode's style clip's pace (its "speed"
// parameter, clamped); without it, or without a clip, for target_speed.
TEST(WalkStyleTest, SpeedFollowsTheStyleClip) {
  SkillConfig c;
  c.motion.manifest = testing::SyntheticManifest({"walk"});
  c.motion.skills = {"walk"};
  c.style_conditioned = true;
  c.walk.speed_from_style = true;
  c.walk.style_speed_min = 0.7;
  c.walk.style_speed_max = 1.5;
  auto s = testing::MakeSkillEnv(c, 8);
  auto* walk = dynamic_cast<WalkSkill*>(s.setup.skill.get());
  ASSERT_NE(walk, nullptr);
  const auto& lib = *s.setup.context.motions;
  std::set<double> speeds;
  for (int round = 0; round < 4; ++round) {
    for (int i = 0; i < 8; ++i) {
      s.env->ResetEnv(i);
      const int clip = walk->style_id(i);
      ASSERT_GE(clip, 0);
      const double pace = lib.clip(clip).meta().params.at("speed");
      EXPECT_DOUBLE_EQ(walk->target_speed(i), std::clamp(pace, 0.7, 1.5))
          << lib.clip(clip).meta().name;
      speeds.insert(walk->target_speed(i));
    }
  }
  EXPECT_GE(speeds.size(), 3u);  // different styles, different paces
  c.walk.speed_from_style = false;
  auto plain = testing::MakeSkillEnv(c, 2);
  EXPECT_DOUBLE_EQ(dynamic_cast<WalkSkill*>(plain.setup.skill.get())->target_speed(0),
                   c.target_speed);
}

// balance_emotions: episodes' styles come emotion by emotion (each emotion of the skill's
// clips alike), where a uniform clip draw follows the clip counts (mostly neutral walks).
TEST(WalkStyleTest, BalancedEmotionsGiveEachEmotionItsShareOfEpisodes) {
  SkillConfig c;
  c.motion.manifest = testing::SyntheticManifest({"walk"});
  c.motion.skills = {"walk"};
  c.style_conditioned = true;
  auto emotion_shares = [&](bool balance) {
    c.balance_emotions = balance;
    constexpr int kEnvs = 8, kRounds = 150;
    auto s = testing::MakeSkillEnv(c, kEnvs);
    const auto& lib = *s.setup.context.motions;
    std::map<std::string, double> share;
    for (int round = 0; round < kRounds; ++round)
      for (int i = 0; i < kEnvs; ++i) {
        s.env->ResetEnv(i);
        const int clip = s.setup.skill->style_id(i);
        EXPECT_EQ(lib.clip(clip).meta().skill, "walk");
        share[lib.clip(clip).meta().emotion] += 1.0 / (kEnvs * kRounds);
      }
    return share;
  };
  const auto uniform = emotion_shares(false);
  const auto balanced = emotion_shares(true);
  ASSERT_GE(balanced.size(), 6u);
  EXPECT_EQ(balanced.size(), uniform.size());
  EXPECT_GT(uniform.at("neutral"), 0.4) << "most synthetic walk clips are neutral";
  for (const auto& [emotion, share] : balanced)
    EXPECT_NEAR(share, 1.0 / balanced.size(), 0.04) << emotion;
}

// With style_pose_weight the task reward mixes in exp(−scale·mean_j (q̃_j − q̄_j)²), q̄ the
// style clip's mean joint angles and q̃ the character's running-average posture: 1 at the
// clip's mean posture, e^(−scale·δ²) when every joint is δ off, and different clips (styles)
// hold different postures. q̃ starts at the reset pose, moves by control_dt/style_pose_time
// of the gap per step, and survives a snapshot.
TEST(WalkStyleTest, PoseRewardFollowsTheStyleClipsMeanPosture) {
  SkillConfig c;
  c.motion.manifest = testing::SyntheticManifest({"walk"});
  c.motion.skills = {"walk"};
  c.style_conditioned = true;
  c.walk.style_pose_weight = 0.3;
  c.walk.style_pose_scale = 50.0;
  c.walk.style_pose_time = 0.5;
  auto s = testing::MakeSkillEnv(c, 4);
  auto* walk = dynamic_cast<WalkSkill*>(s.setup.skill.get());
  ASSERT_NE(walk, nullptr);
  const auto& lib = *s.setup.context.motions;
  s.env->ResetEnv(0);
  const int clip = walk->style_id(0);
  ASSERT_GE(clip, 0);
  auto clip_mean = [&](int k) {
    WalkSkill::JointAngles m = WalkSkill::JointAngles::Zero();
    for (const auto& f : lib.clip(k).frames()) m += f.dof_pos;
    return WalkSkill::JointAngles(m / lib.clip(k).num_frames());
  };
  const WalkSkill::JointAngles mean = clip_mean(clip);
  EXPECT_NEAR(walk->StylePoseReward(0, mean), 1.0, 1e-12);
  const WalkSkill::JointAngles off = mean + WalkSkill::JointAngles::Constant(0.1);
  EXPECT_NEAR(walk->StylePoseReward(0, off), std::exp(-50.0 * 0.01), 1e-12);
  double worst = 1.0;
  for (int k = 0; k < lib.num_clips(); ++k)
    worst = std::min(worst, walk->StylePoseReward(0, clip_mean(k)));
  EXPECT_LT(worst, 0.5);

  // The running average: the reset pose, then one step of a = dt / time towards the pose.
  for (int i = 0; i < 4; ++i) s.env->ResetEnv(i);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(walk->average_pose(i), s.env->pose(i).dof_pos);
  const WalkSkill::JointAngles before = walk->average_pose(1);
  std::vector<float> act(4 * humanoid::kNumDofs, 0.3f);
  s.env->Step(act.data());
  const double a = s.env->control_dt() / 0.5;
  const WalkSkill::JointAngles expected = before + a * (s.env->pose(1).dof_pos - before);
  EXPECT_LT((walk->average_pose(1) - expected).norm(), 1e-12);
  EXPECT_GT((walk->average_pose(1) - before).norm(), 1e-6);
  for (int t = 0; t < 5; ++t) s.env->Step(act.data());
  const std::string snap = s.env->SaveState();
  auto other = testing::MakeSkillEnv(c, 4);
  other.env->LoadState(snap);
  auto* walk2 = dynamic_cast<WalkSkill*>(other.setup.skill.get());
  for (int i = 0; i < 4; ++i) EXPECT_EQ(walk2->average_pose(i), walk->average_pose(i));

  // Off (the default): no clip postures are kept and the term is 1.
  SkillConfig off_config = c;
  off_config.walk.style_pose_weight = 0.0;
  auto plain = testing::MakeSkillEnv(off_config, 4);
  plain.env->ResetEnv(0);
  EXPECT_EQ(dynamic_cast<WalkSkill*>(plain.setup.skill.get())->StylePoseReward(0, off), 1.0);
  // A snapshot from before the term was on (a resumed campaign) loads; q̃ starts at q̄.
  other.env->LoadState(plain.env->SaveState());
  for (int i = 0; i < 4; ++i) EXPECT_EQ(walk2->average_pose(i), clip_mean(walk2->style_id(i)));
  c.walk.style_pose_weight = 1.5;  // a share outside [0, 1] is a config error
  EXPECT_THROW(c.walk.Validate(), Error);
}

// The foot-sliding term: exp(−scale·Σ‖v_xy‖²) over the feet below the contact height, and its
// share of the step reward (the same state with the term off gives r_walk).
TEST(WalkRewardTest, FootSlideTermPaysFeetThatStayPut) {
  SkillConfig c;
  c.walk.foot_slide_weight = 0.25;
  c.walk.foot_slide_scale = 5.0;
  auto s = testing::MakeSkillEnv(c, 1);
  auto* walk = dynamic_cast<WalkSkill*>(s.setup.skill.get());
  humanoid::BodyStates b = s.env->bodies(0);
  b.pos[humanoid::kLeftFoot].z() = 0.05;
  b.lin_vel[humanoid::kLeftFoot] = Eigen::Vector3d(0.3, 0.4, 1.0);  // down: 0.25 m²/s² counts
  b.pos[humanoid::kRightFoot].z() = 0.2;
  b.lin_vel[humanoid::kRightFoot] = Eigen::Vector3d(2.0, 0, 0);  // in the air: ignored
  EXPECT_NEAR(walk->FootSlideReward(b), std::exp(-5.0 * 0.25), 1e-12);
  b.pos[humanoid::kRightFoot].z() = 0.07;
  EXPECT_NEAR(walk->FootSlideReward(b), std::exp(-5.0 * 4.25), 1e-12);

  SkillConfig off = c;
  off.walk.foot_slide_weight = 0;
  auto plain = testing::MakeSkillEnv(off, 1);
  // Standing, the whole body gliding at 0.6 m/s: both feet down and sliding.
  humanoid::HumanoidPose glide = testing::PoseAt(Eigen::Vector3d(0, 0, 0.89));
  glide.root_lin_vel = Eigen::Vector3d(0.6, 0, 0);
  s.env->SetState(0, glide);
  plain.env->SetState(0, glide);
  const double r_walk = plain.setup.skill->Step(testing::ViewOf(*plain.env, 0)).reward;
  const double r = walk->Step(testing::ViewOf(*s.env, 0)).reward;
  EXPECT_NEAR(r, 0.75 * r_walk + 0.25 * walk->FootSlideReward(s.env->bodies(0)), 1e-6);
  EXPECT_NEAR(walk->FootSlideReward(s.env->bodies(0)), std::exp(-5.0 * 2 * 0.36), 1e-6);
  c.walk.style_pose_weight = 0.8;  // 0.8 + 0.25 > 1
  EXPECT_THROW(c.walk.Validate(), Error);
}

// Walks among furniture: every env starts on free floor of its own room, its goal is free floor
// of that room within range and reachable along free A* legs, the pelvis goal is the carrot on
// that path, and touching a wall ends the episode as a failure.
TEST(WalkRoomsTest, StartsGoalsAndPathsStayInTheEnvsRoom) {
  SkillConfig c;
  c.walk.rooms = 2;
  c.walk.target_min_distance = 1.5;
  c.walk.target_max_distance = 4.5;
  c.walk.success_radius = 0.3;
  auto s = testing::MakeSkillEnv(c, 4);
  auto* walk = dynamic_cast<WalkSkill*>(s.setup.skill.get());
  ASSERT_NE(walk, nullptr);
  const scene::Scene& sc = *s.setup.context.scene;
  ASSERT_EQ(sc.rooms.size(), 2u);
  ASSERT_NE(walk->free_space(), nullptr);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(walk->room(i), i % 2);
    const scene::Room& room = sc.rooms[walk->room(i)];
    const Eigen::Vector2d root = s.env->pose(i).root_pos.head<2>();
    EXPECT_TRUE(room.Contains(root)) << i;
    EXPECT_TRUE(walk->free_space()->Free(root)) << i;
    EXPECT_TRUE(room.Contains(walk->goal(i))) << i;
    EXPECT_TRUE(walk->free_space()->Free(walk->goal(i))) << i;
    const double d = (walk->goal(i) - root).norm();
    EXPECT_GE(d, 1.5 - 1e-9);
    EXPECT_LE(d, 4.5 + 1e-9);
    const auto& points = walk->path(i).points();
    EXPECT_TRUE(points.back().isApprox(walk->goal(i)));
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t k = 1; k < points.size(); ++k) {
      EXPECT_TRUE(walk->free_space()->SegmentFree(points[k - 1], points[k])) << i << " leg " << k;
      const Eigen::Vector2d a = points[k - 1], ab = points[k] - a;
      const double t = std::clamp((walk->target(i) - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      nearest = std::min(nearest, (a + t * ab - walk->target(i)).norm());
    }
    // The pelvis goal lies on the path, at most the lookahead from the start.
    EXPECT_LT(nearest, 1e-9) << i;
    EXPECT_LE((walk->target(i) - points.front()).norm(), c.walk.path_lookahead + 1e-9);
    EXPECT_FALSE(WalkSkill::Collided(testing::ViewOf(*s.env, i))) << "standing on free floor";
  }
  // At the goal: success, no termination.
  const Eigen::Vector2d g = walk->goal(0);
  s.env->SetState(0, testing::PoseAt(Eigen::Vector3d(g.x(), g.y(), 0.89)));
  sim::TaskStepResult r = walk->Step(testing::ViewOf(*s.env, 0));
  EXPECT_TRUE(r.success);
  EXPECT_FALSE(r.terminate);
  // Astride the room's west wall: a collision, the episode ends without success.
  const scene::Room& room = sc.rooms[walk->room(0)];
  s.env->SetState(
      0, testing::PoseAt(Eigen::Vector3d(room.floor_polygon[0].x(), room.Centroid().y(), 0.89)));
  EXPECT_TRUE(WalkSkill::Collided(testing::ViewOf(*s.env, 0)));
  r = walk->Step(testing::ViewOf(*s.env, 0));
  EXPECT_TRUE(r.terminate);
  EXPECT_FALSE(r.success);
}

// Furniture starts (walk_furniture_start_share): the character stands in its room with free
// floor around the pelvis, furniture straight ahead within walk_furniture_start_max, touching
// nothing; evaluation tells them from free-floor starts.
TEST(WalkRoomsTest, FurnitureStartsStandFacingFurniture) {
  SkillConfig c;
  c.walk.rooms = 2;
  c.walk.furniture_start_share = 1.0;
  const int n = 12;
  auto s = testing::MakeSkillEnv(c, n);
  auto* walk = dynamic_cast<WalkSkill*>(s.setup.skill.get());
  ASSERT_NE(walk, nullptr);
  const scene::SceneHeightGrid& heights = *s.setup.context.height_grid;
  const auto floor_at = [&](const Eigen::Vector2d& q) { return heights.Height(q.x(), q.y()); };
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < n; ++i) {
      SCOPED_TRACE(i);
      ASSERT_EQ(walk->start_label(i), "furniture");
      const humanoid::BodyStates& b = s.env->bodies(i);
      const Eigen::Vector2d p = b.pos[humanoid::kPelvis].head<2>();
      EXPECT_TRUE(s.setup.context.scene->rooms[walk->room(i)].Contains(p));
      EXPECT_LE(floor_at(p), 0.05);
      const double yaw = humanoid::HeadingAngle(b.rot[humanoid::kPelvis]);
      // Furniture ahead: along some heading within the start's ±0.35 rad jitter.
      bool ahead = false;
      for (double a = -0.4; a <= 0.4 && !ahead; a += 0.05)
        for (double r = 0.1; r <= c.walk.furniture_start_max + 0.02 && !ahead; r += 0.02)
          ahead = floor_at(p + r * Eigen::Vector2d(std::cos(yaw + a), std::sin(yaw + a))) > 0.05;
      EXPECT_TRUE(ahead);
      EXPECT_FALSE(WalkSkill::Collided(testing::ViewOf(*s.env, i))) << "standing clear";
      s.env->ResetEnv(i);
    }
  SkillConfig free = c;
  free.walk.furniture_start_share = 0.0;
  auto f = testing::MakeSkillEnv(free, 2);
  EXPECT_EQ(f.setup.skill->start_label(0), "free");
  SkillConfig open = SkillConfig{};
  auto o = testing::MakeSkillEnv(open, 1);
  EXPECT_EQ(o.setup.skill->start_label(0), "");
  free.walk.furniture_start_min = 0.6;
  free.walk.furniture_start_max = 0.5;
  EXPECT_THROW(free.walk.Validate(), Error);
}

// The path and goal travel in a snapshot: a restored env continues identically.
TEST(WalkRoomsTest, SnapshotRestoresPaths) {
  SkillConfig c;
  c.walk.rooms = 2;
  c.walk.target_min_distance = 1.5;
  c.walk.target_max_distance = 4.5;
  auto s = testing::MakeSkillEnv(c, 4);
  std::vector<float> act(4 * 28, 0.0f);
  for (int t = 0; t < 10; ++t) s.env->Step(act.data());
  const std::string snap = s.env->SaveState();
  // The same rooms (the scene comes from the skill's seed); its envs elsewhere until restored.
  auto other = testing::MakeSkillEnv(c, 4);
  std::vector<float> push(4 * 28, 0.3f);
  for (int t = 0; t < 5; ++t) other.env->Step(push.data());
  other.env->LoadState(snap);
  for (int t = 0; t < 20; ++t) {
    s.env->Step(act.data());
    other.env->Step(act.data());
  }
  EXPECT_EQ(0, std::memcmp(s.env->observations(), other.env->observations(),
                           sizeof(float) * 4 * s.env->obs_dim()));
}

// The motion library follows the environment the skill runs in: with 60 Hz control, a 3-step
// AMP history and no root height, a reference start's history is spaced by 1/60 s and the
// demonstrations have the env's width and features (with the library's defaults they would
// be 1/30 s apart, 10 steps long and carry a root height the env zeroes).
TEST(WalkSkillTest, MotionLibraryFollowsTheEnvironmentsAmpFeatures) {
  SkillConfig c;
  c.skill = "walk";
  c.motion.manifest = testing::SyntheticManifest({"walk"});
  c.motion.skills = {"walk"};
  c.reference_init_prob = 1.0;
  sim::EnvConfig ec;
  ec.num_envs = 2;
  ec.substeps = 2;
  ec.amp_history = 3;
  ec.root_height_obs = false;
  const SkillSetup setup = CreateSkill(c, ec.num_envs, 1, nullptr, &ec);
  const motion::MotionLibrary& lib = *setup.context.motions;
  EXPECT_NEAR(lib.options().control_dt, 1.0 / 60.0, 1e-12);
  EXPECT_EQ(lib.options().amp_steps, 3);
  EXPECT_FALSE(lib.options().root_height_obs);
  EXPECT_EQ(lib.options().local_root_obs, ec.local_root_obs);
  const motion::ReferenceState r = lib.StateAt(0, 1.0);
  ASSERT_EQ(r.history.size(), 2u);
  const motion::ReferenceState later = lib.StateAt(0, 1.0 + 1.0 / 60.0);
  EXPECT_TRUE(later.history[0].root_pos.isApprox(r.pose.root_pos, 1e-9));
  std::vector<float> window(3 * humanoid::kAmpObsStepDim, 1.0f);
  humanoid::MjDataPtr scratch = humanoid::MakeData(setup.context.humanoid->model());
  lib.AmpWindow(0, 1.0, scratch.get(), window.data());
  for (int k = 0; k < 3; ++k) EXPECT_EQ(window[k * humanoid::kAmpObsStepDim], 0.0f) << k;
  // Without an environment the defaults are EnvConfig's.
  const SkillSetup plain = CreateSkill(c, 2, 1);
  EXPECT_NEAR(plain.context.motions->options().control_dt, 1.0 / 30.0, 1e-12);
  EXPECT_EQ(plain.context.motions->options().amp_steps, sim::EnvConfig{}.amp_history);
}

}  // namespace
}  // namespace sims::task
