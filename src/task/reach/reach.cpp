#include "sims/task/reach/reach.h"

#include <cmath>

#include "sims/core/error.h"
#include "sims/humanoid/features.h"
#include "sims/humanoid/model_builder.h"

namespace sims::task {

namespace {
// Targets lie within this depth of the object's front face (m).
constexpr double kFrontDepth = 0.12;
// A reach clip fits a target when their heights differ by less than this (m); the clips sit at
// 0.45, 1.05 and 1.7 m.
constexpr double kClipTargetTolerance = 0.25;
}  // namespace

std::vector<std::string> ReachCategories() {
  return {"table", "desk", "cabinet", "shelf", "wardrobe"};
}

ReachSkill::ReachSkill(const SkillConfig& config, const SkillContext& context)
    : ObjectSkill(config, context) {
  reference_clips_.clear();
  if (context.motions) reference_clips_ = context.motions->Find("reach");
  PrepareReferenceClips();
  hand_.assign(context.num_envs, humanoid::kCjRightHand);
  CollectObjects("object with front surfaces between 0.25 and 1.95 m");
  for (const auto& g : objects_) candidates_.push_back(FrontPoints(g));
}

ReachSkill::Bands ReachSkill::FrontPoints(const ObjectGeometry& g) const {
  Bands bands;
  const scene::Object& o = context_.scene->objects[g.object];
  const Eigen::Isometry3d X_OW = g.X_WO.inverse();
  for (const auto& part : o.parts) {
    for (const auto& p : part.points) {
      const Eigen::Vector3d l = X_OW * p;
      if (l.x() < g.local.max.x() - kFrontDepth) continue;
      for (int b = 0; b < 3; ++b)
        if (p.z() >= kReachBandEdges[b] && p.z() < kReachBandEdges[b + 1]) bands[b].push_back(p);
    }
  }
  return bands;
}

bool ReachSkill::Accepts(const ObjectGeometry& g) const {
  const Bands b = FrontPoints(g);
  return !b[0].empty() || !b[1].empty() || !b[2].empty();
}

double ReachSkill::ClipContactTime(int clip) const {
  // The first frame at which the clip's hand is within the success distance (with margin)
  // of the clip's stored target.
  const motion::MotionClip& c = context_.motions->clip(clip);
  const auto& prm = c.meta().params;
  if (!prm.count("target_x") || !prm.count("target_y") || !prm.count("target_z"))
    return c.duration();
  const Eigen::Vector3d goal(prm.at("target_x"), prm.at("target_y"), prm.at("target_z"));
  const int hand = prm.at("target_y") > 0 ? humanoid::kCjLeftHand : humanoid::kCjRightHand;
  const double reach = kPreContactMargin * config_.object.contact_success_threshold;
  humanoid::MjDataPtr scratch = humanoid::MakeData(context_.humanoid->model());
  humanoid::BodyStates b;
  for (int f = 0; f < c.num_frames(); ++f) {
    humanoid::ForwardKinematics(*context_.humanoid, c.FramePose(f), scratch.get(), &b);
    if ((humanoid::ContactJointPosition(b, hand) - goal).norm() < reach) return f / c.fps();
  }
  return c.duration();
}

void ReachSkill::SetTarget(int i, int hand_joint, const Eigen::Vector3d& target) {
  SIMS_CHECK(hand_joint == humanoid::kCjLeftHand || hand_joint == humanoid::kCjRightHand);
  hand_[i] = hand_joint;
  // The far anchor: in front of the object's front face, level with the target.
  const ObjectGeometry& g = geometry(i);
  const Eigen::Vector3d l = g.X_WO.inverse() * target;
  const Eigen::Vector3d anchor =
      g.ToWorld(Eigen::Vector3d(g.local.max.x() + kStandDistance, l.y(), 0.0));
  SetEpisodeTarget(i, target, anchor.head<2>());
  env_[i].hold = 0;
  ClearGoals(i);
  SetGoal(i, hand_joint, target);
}

bool ReachSkill::BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) {
  if (!ObjectSkill::BeginInstruction(view, target)) return false;
  const int i = view.env_id;
  const int hand = target.hand >= 0 ? target.hand : hand_[i];
  if (target.has_point) {
    SetTarget(i, hand, target.point);
    return true;
  }
  const Bands& bands = candidates_[env_[i].object];
  int band = target.height == "low" ? 0 : target.height == "high" ? 2 : 1;
  if (bands[band].empty()) band = !bands[1].empty() ? 1 : !bands[0].empty() ? 0 : 2;
  if (bands[band].empty()) return false;
  const Eigen::Vector3d pelvis = view.pose->root_pos;
  const Eigen::Vector3d* best = &bands[band].front();
  for (const auto& p : bands[band])
    if ((p - pelvis).head<2>().squaredNorm() < (*best - pelvis).head<2>().squaredNorm()) best = &p;
  SetTarget(i, hand, *best);
  return true;
}

std::string ReachSkill::start_label(int i) const {
  const double z = target(i).z();
  return z < kReachBandEdges[1] ? "low" : z < kReachBandEdges[2] ? "medium" : "high";
}

void ReachSkill::SampleTask(int i, Rng& rng) {
  const Bands& bands = candidates_[env_[i].object];
  std::vector<int> usable;
  for (int b = 0; b < 3; ++b)
    if (!bands[b].empty()) usable.push_back(b);
  const int b = usable[rng.UniformInt(static_cast<int64_t>(usable.size()))];
  const auto& pts = bands[b];
  const int hand = rng.Bernoulli(0.5) ? humanoid::kCjLeftHand : humanoid::kCjRightHand;
  SetTarget(i, hand, pts[rng.UniformInt(static_cast<int64_t>(pts.size()))]);
}

bool ReachSkill::ReferenceInit(int i, Rng& rng, sim::InitialState* init) {
  const auto* lib = context_.motions.get();
  const bool left = hand_[i] == humanoid::kCjLeftHand;
  std::vector<int> fitting;
  for (int c : reference_clips_) {
    const auto& prm = lib->clip(c).meta().params;
    if (!prm.count("target_x") || !prm.count("target_y") || !prm.count("target_z")) continue;
    if ((prm.at("target_y") > 0) != left) continue;
    if (std::abs(prm.at("target_z") - target(i).z()) > kClipTargetTolerance) continue;
    fitting.push_back(c);
  }
  if (fitting.empty()) return false;
  const int clip = fitting[rng.UniformInt(static_cast<int64_t>(fitting.size()))];
  const auto& prm = lib->clip(clip).meta().params;
  // The clip's character faces +x with its target ahead; in the world it faces the object's
  // front (object −x) with the clip target on the chosen point.
  const ObjectGeometry& g = geometry(i);
  const ClipPlacement placement =
      ClipPlacement::Align(target(i).head<2>(), g.yaw + M_PI,
                           Eigen::Vector2d(prm.at("target_x"), prm.at("target_y")), 0.0);
  if (!FreeFloor(placement.offset, 0.2)) return false;
  PlaceReference(i, clip, PreContactTime(clip, rng), placement, init);
  return true;
}

void ReachSkill::OnReset(const sim::EnvView& view, Rng&) {
  const int i = view.env_id;
  env_[i].error = (target(i) - humanoid::ContactJointPosition(*view.bodies, hand_[i])).norm();
}

sim::TaskStepResult ReachSkill::Step(const sim::EnvView& view) {
  const int i = view.env_id;
  const double d2 =
      (target(i) - humanoid::ContactJointPosition(*view.bodies, hand_[i])).squaredNorm();
  env_[i].error = std::sqrt(d2);
  return ContactRewardStep(view, d2, env_[i].error);
}

void ReachSkill::SerializeTaskState(int i, StateArchive* a) {
  a->Int("hand", &hand_[i], 0, humanoid::kNumContactJoints - 1);
}

SkillInfo ReachSkillInfo() {
  SkillInfo info = BuiltinSkillInfo("reach");
  info.params = ConfigToJson(ObjectParams{});
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    return BuildTrainingGround(c, rng, ReachCategories());
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<ReachSkill>(c, ctx);
  };
  return info;
}

}  // namespace sims::task
