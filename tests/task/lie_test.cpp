#include "sims/task/lie/lie.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "sims/motion/mirror.h"
#include "sims/scene/contact_targets.h"
#include "sims/task/handoff.h"
#include "task/task_test_util.h"

namespace sims::task {
namespace {

using testing::MakeSkillEnv;
using testing::PoseAt;
using testing::ViewOf;

SkillConfig LieConfig() {
  SkillConfig c;
  c.skill = "lie";
  c.object.num_objects = 2;
  c.object.contact_success_threshold = 0.3;
  c.motion.manifest = testing::SyntheticManifest({"lie"});
  c.motion.skills = {"lie"};
  return c;
}

bool IsSofaClip(const motion::MotionClip& c) {
  const auto& f = c.meta().furniture;
  return std::find(f.begin(), f.end(), "sofa") != f.end();
}

// The clip's last pose placed on object g in the clip frame ClipFurnitureFrame found.
humanoid::HumanoidPose PlacedEnd(const motion::MotionClip& c, const ObjectGeometry& g,
                                 const Eigen::Vector2d& p_clip, double yaw_clip, double dz) {
  const auto place =
      ClipPlacement::Align(g.X_WO.translation().head<2>(), g.yaw, p_clip, yaw_clip, dz);
  return place.Apply(c.FramePose(c.num_frames() - 1));
}

// Distance from p to the nearest of the object's parts `parts`.
double DistanceToParts(const scene::Object& object, const std::vector<int>& parts,
                       const Eigen::Vector3d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (int k : parts) d = std::min(d, (scene::NearestPointOnPart(object.parts[k], p) - p).norm());
  return d;
}

TEST(LieSkillTest, BedClipsLieOnMattressAndPillow) {
  // The lying clips (and their mirrors: head toward the other end, approached from the other
  // side) placed on each bed end with the pelvis on the mattress and the head on a pillow.
  auto s = MakeSkillEnv(LieConfig(), 1);
  auto* lie = dynamic_cast<LieSkill*>(s.setup.skill.get());
  ASSERT_NE(lie, nullptr);
  const auto& lib = *s.setup.context.motions;
  const auto& scene = *s.setup.context.scene;
  humanoid::MjDataPtr scratch = humanoid::MakeData(s.setup.context.humanoid->model());
  int checked = 0;
  for (const auto& g : lie->objects()) {
    ASSERT_FALSE(g.part_indices("pillow").empty());
    for (int clip : lib.Find("lie")) {
      for (bool mirror : {false, true}) {
        const motion::MotionClip c = mirror ? motion::MirrorClip(lib.clip(clip)) : lib.clip(clip);
        if (c.meta().style == "on side") continue;  // lies on its side, head lower
        if (IsSofaClip(c)) {
          Eigen::Vector2d p;
          double yaw = 0, dz = 0;
          EXPECT_FALSE(ClipFurnitureFrame(c, g, 0.0, &p, &yaw, &dz)) << "a sofa clip on a bed";
          continue;
        }
        Eigen::Vector2d p_clip;
        double yaw_clip = 0, dz = 0;
        ASSERT_TRUE(ClipFurnitureFrame(c, g, 0.0, &p_clip, &yaw_clip, &dz));
        humanoid::BodyStates b;
        humanoid::ForwardKinematics(*s.setup.context.humanoid,
                                    PlacedEnd(c, g, p_clip, yaw_clip, dz), scratch.get(), &b);
        const auto& bed = scene.objects[g.object];
        const Eigen::Vector3d pelvis = humanoid::ContactJointPosition(b, humanoid::kCjPelvis);
        const Eigen::Vector3d head = humanoid::ContactJointPosition(b, humanoid::kCjHead);
        EXPECT_LT(DistanceToParts(bed, {g.part_index(kMattressPart)}, pelvis), 0.3)
            << c.meta().name;
        EXPECT_LT(DistanceToParts(bed, g.part_indices("pillow"), head), 0.3) << c.meta().name;
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 4);
}

TEST(LieSkillTest, GoalsRewardAndThreshold) {
  SkillConfig c = LieConfig();
  c.reference_init_prob = 0;
  c.object.max_contact_force = 0;
  auto s = MakeSkillEnv(c, 2);
  auto* lie = dynamic_cast<LieSkill*>(s.setup.skill.get());
  EXPECT_EQ(s.env->obs_dim(), 223 + 60 + kObjectObsDim + 256 + 64);
  EXPECT_EQ(lie->goal_mask(0), (1u << humanoid::kCjPelvis) | (1u << humanoid::kCjHead));
  // The pelvis target: the mattress centre, 0.11 m above its top (the lie clips' pelvis).
  const ObjectGeometry& g = lie->geometry(0);
  const scene::Aabb& mattress = g.part_local(kMattressPart);
  const Eigen::Vector3d target = g.ToWorld(
      Eigen::Vector3d(mattress.center().x(), mattress.center().y(), mattress.max.z() + 0.11));
  EXPECT_NEAR((lie->target(0) - target).norm(), 0, 1e-9);
  // The anchor stands beside the bed's long side (the episode's side).
  const Eigen::Vector3d a_O =
      g.X_WO.inverse() * Eigen::Vector3d(lie->anchor(0).x(), lie->anchor(0).y(), 0);
  EXPECT_NEAR(std::abs(a_O.y()), 0.5 * (g.local.max.y() - g.local.min.y()) + kStandDistance, 0.05);
  // Pelvis 0.25 m above the target; success needs both joints < 0.3 m.
  s.env->SetState(0, PoseAt(target + Eigen::Vector3d(0, 0, 0.25)));
  const auto r = lie->Step(ViewOf(*s.env, 0));
  const auto& b = s.env->bodies(0);
  const Eigen::Vector3d dp =
      lie->goal(0, humanoid::kCjPelvis) - humanoid::ContactJointPosition(b, 0);
  const Eigen::Vector3d dh =
      lie->goal(0, humanoid::kCjHead) - humanoid::ContactJointPosition(b, humanoid::kCjHead);
  EXPECT_NEAR(dp.norm(), 0.25, 1e-6);
  // Over the mattress centre, ~1 m from the anchor beside the bed: the far term is whole (at the
  // target), and half the near term is the wide kernel.
  ASSERT_GT((lie->anchor(0) - s.env->pose(0).root_pos.head<2>()).squaredNorm(), kFarDistanceSq);
  const double sum = dp.squaredNorm() + dh.squaredNorm();
  EXPECT_NEAR(r.reward, 0.7 * (0.5 * std::exp(-10 * sum) + 0.5 * std::exp(-sum)) + 0.3, 1e-5);
  EXPECT_EQ(r.success, dh.norm() < 0.3);
  // The contact error is the mean over both required joints (UniHSI), success needs each one.
  EXPECT_NEAR(lie->goal_error(0), 0.5 * (dp.norm() + dh.norm()), 1e-9);
}

// Stories lie on sofas: a sofa's seat is the surface (long axis y, approached from the front),
// the head goes to the episode's arm; armchairs are too narrow to lie on.
TEST(LieSkillTest, SofasAreLainOnAlongTheSeat) {
  SkillConfig c = LieConfig();
  c.reference_init_prob = 0;
  c.object.object_categories = {"sofa", "armchair"};
  c.object.num_objects = 4;
  auto s = MakeSkillEnv(c, 4);
  auto* lie = dynamic_cast<LieSkill*>(s.setup.skill.get());
  ASSERT_EQ(lie->objects().size(), 2u) << "the two sofas, not the armchairs";
  for (int i = 0; i < 4; ++i) {
    const ObjectGeometry& g = lie->geometry(i);
    ASSERT_EQ(g.part(kMattressPart), nullptr);
    EXPECT_EQ(lie->support_part(g), std::string(kSeatPart));
    const scene::Aabb& seat = g.part_local(kSeatPart);
    EXPECT_GT(seat.max.y() - seat.min.y(), 1.2);
    const Eigen::Vector3d target_O = g.X_WO.inverse() * lie->target(i);
    EXPECT_NEAR(target_O.x(), seat.center().x(), 1e-9);  // y: toward the head's arm (below)
    EXPECT_NEAR(target_O.z(), seat.max.z() + 0.11, 1e-9);
    // The far anchor stands in front of the sofa.
    const Eigen::Vector3d anchor_O =
        g.X_WO.inverse() * Eigen::Vector3d(lie->anchor(i).x(), lie->anchor(i).y(), 0.0);
    EXPECT_NEAR(anchor_O.x(), g.local.max.x() + kStandDistance, 1e-9);
    EXPECT_NEAR(anchor_O.y(), seat.center().y(), 1e-9);
    EXPECT_EQ(lie->goal_mask(i), (1u << humanoid::kCjPelvis) | (1u << humanoid::kCjHead));
  }
  // The sofa lie-downs (and their mirrors, head toward the other arm) fit the side whose arm
  // their head goes to, end with the pelvis on the seat, and their lying pose moved onto the
  // episode's target succeeds (pelvis and head within 0.2 m) on every sofa, wide or narrow.
  const auto& lib = *s.setup.context.motions;
  const auto& scene = *s.setup.context.scene;
  const auto& model = *s.setup.context.humanoid;
  humanoid::MjDataPtr scratch = humanoid::MakeData(model.model());
  int checked = 0;
  for (int i = 0; i < 4; ++i) {
    const ObjectGeometry& g = lie->geometry(i);
    const double side = lie->lateral(i);
    ASSERT_EQ(std::abs(side), 1.0);
    const Eigen::Vector3d target_O = g.X_WO.inverse() * lie->target(i);
    const scene::Aabb& seat = g.part_local(kSeatPart);
    const double half = 0.5 * (seat.max.y() - seat.min.y());
    EXPECT_NEAR(target_O.y() - seat.center().y(), side * std::max(0.0, half - 0.71), 1e-9);
    const auto& sofa = scene.objects[g.object];
    std::vector<int> arms = g.part_indices("left arm");
    for (int k : g.part_indices("right arm")) arms.push_back(k);
    for (int clip : lib.Find("lie")) {
      for (bool mirror : {false, true}) {
        const motion::MotionClip m = mirror ? motion::MirrorClip(lib.clip(clip)) : lib.clip(clip);
        Eigen::Vector2d p_clip;
        double yaw_clip = 0, dz = 0;
        const bool fits = ClipFurnitureFrame(m, g, side, &p_clip, &yaw_clip, &dz);
        EXPECT_EQ(fits, IsSofaClip(m) && m.meta().mirrored == (side < 0)) << m.meta().name;
        if (!fits || std::abs(dz) > kMaxClipHeightMismatch) continue;
        humanoid::HumanoidPose pose = PlacedEnd(m, g, p_clip, yaw_clip, dz);
        humanoid::BodyStates b;
        humanoid::ForwardKinematics(model, pose, scratch.get(), &b);
        Eigen::Vector3d pelvis = humanoid::ContactJointPosition(b, humanoid::kCjPelvis);
        EXPECT_LT(DistanceToParts(sofa, {g.part_index(kSeatPart)}, pelvis), 0.2) << m.meta().name;
        // The same pose lying on the target.
        pose.root_pos += lie->target(i) - pelvis;
        humanoid::ForwardKinematics(model, pose, scratch.get(), &b);
        pelvis = humanoid::ContactJointPosition(b, humanoid::kCjPelvis);
        const Eigen::Vector3d head = humanoid::ContactJointPosition(b, humanoid::kCjHead);
        EXPECT_LT((pelvis - lie->target(i)).norm(), 1e-9);
        EXPECT_LT(DistanceToParts(sofa, arms, head), 0.2)
            << m.meta().name << " on a seat " << 2 * half << " m wide";
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 4);
  c.object.object_categories = {"armchair"};
  try {
    MakeSkillEnv(c, 1);
    FAIL() << "armchairs accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bed or sofa"), std::string::npos) << e.what();
  }
}

// Lie from where sit ends (handoff_states): in stories most lies follow a sit on the same bed
// or sofa. A sit state recorded on each bed starts the episodes on the env's bed at its place
// relative to the mattress's head end, labelled "handoff" (neither a clip nor a default start,
// so the spawn curriculum ignores it), and the label survives a snapshot.
TEST(LieSkillTest, StartsFromSitEndStatesOnTheBed) {
  SkillConfig c = LieConfig();
  c.reference_init_prob = 1.0;
  c.object.spawn_curriculum = true;
  c.success_hold_steps = 2;
  const int n = 4;
  // Seated on the foot end, where sit's bed target is: 0.3 m from the mattress's foot edge.
  std::vector<HandoffState> states;
  std::vector<Eigen::Vector3d> p_AP;
  {
    auto plain = MakeSkillEnv(c, n);
    auto* lie = dynamic_cast<LieSkill*>(plain.setup.skill.get());
    for (const ObjectGeometry& g : lie->objects()) {
      const scene::Aabb& m = g.part_local(kMattressPart);
      const Eigen::Vector3d a = HandoffAnchor(std::string(kMattressPart), m);
      const Eigen::Vector3d p_O(m.max.x() - 0.3, m.center().y(), m.max.z() + 0.1);
      p_AP.push_back(p_O - a);
      states.push_back(MakeHandoffState("sit", std::string(kMattressPart), g,
                                        PoseAt(g.ToWorld(p_O), g.yaw), true));
    }
  }
  const auto dir = sims::testing::TempDir("lie_handoff");
  SaveHandoffStates(states, dir / "sit_on_beds.json");
  c.object.handoff_share = 1.0;
  c.object.handoff_states = {(dir / "sit_on_beds.json").string()};
  auto s = MakeSkillEnv(c, n);
  auto* lie = dynamic_cast<LieSkill*>(s.setup.skill.get());
  ASSERT_EQ(lie->handoff_states().size(), states.size());
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < n; ++i) {
      ASSERT_TRUE(lie->handoff_start(i)) << "env " << i;
      EXPECT_FALSE(lie->reference_start(i));
      EXPECT_EQ(lie->start_label(i), "handoff");
      const ObjectGeometry& g = lie->geometry(i);
      const scene::Aabb& m = g.part_local(kMattressPart);
      const Eigen::Vector3d rel =
          g.X_WO.inverse() * s.env->pose(i).root_pos - HandoffAnchor(std::string(kMattressPart), m);
      // The two beds differ in length by less than the placement's 0.1 m, so either state fits.
      const bool fits = std::any_of(p_AP.begin(), p_AP.end(), [&](const Eigen::Vector3d& q) {
        return std::abs(rel.x() - q.x()) < 1e-4 && std::abs(rel.y() - q.y()) < 1e-4;
      });
      EXPECT_TRUE(fits) << "env " << i << " at " << rel.transpose();
      // Completing a hand-off episode leaves the spawn level where it was.
      s.env->SetState(i, PoseAt(lie->target(i), g.yaw));
      for (int k = 0; k < c.success_hold_steps; ++k) lie->Step(ViewOf(*s.env, i));
      s.env->ResetEnv(i);
      EXPECT_EQ(lie->spawn_level(i), 0.0) << "env " << i;
    }
  }
  // A snapshot keeps the start kind; a clip start restored over it clears the label.
  const std::vector<double> saved = lie->SaveEnvState(0);
  c.object.handoff_share = 0.0;
  auto clips = MakeSkillEnv(c, 1);
  auto* other = dynamic_cast<LieSkill*>(clips.setup.skill.get());
  EXPECT_FALSE(other->handoff_start(0));
  EXPECT_EQ(other->start_label(0), "");
  other->LoadEnvState(0, saved);
  EXPECT_TRUE(other->handoff_start(0));
  EXPECT_FALSE(other->reference_start(0));
  EXPECT_EQ(other->start_label(0), "handoff");
}

}  // namespace
}  // namespace sims::task
