// The reference skill. A skill has four jobs, each a TaskHook method:
//   1. SampleInitialState — where the episode starts (the base class does hybrid
//      reference-state init from the motion library; walk keeps that).
//   2. OnReset            — draw the episode's goals once the character is placed.
//   3. Step               — reward, success and termination after each control step.
//   4. Observe            — the base class writes the contact goals, heightmap and z; a skill
//      only keeps its goals up to date with SetGoal().
// Everything per env lives in vectors indexed by env id: the environment calls these methods
// for different envs from different OpenMP threads at once, so a skill must never touch
// another env's slot or any shared mutable state.
#include "sims/task/walk/walk.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sims/core/error.h"
#include "sims/humanoid/features.h"
#include "sims/scene/builtin.h"

namespace sims::task {

namespace {
// The pelvis goal height handed to the contact-goal observation: standing height, so the
// z part of the goal tells a crouching character to stand up while it walks.
constexpr double kStandingPelvisHeight = humanoid::kDefaultRootHeight;
// Walk targets must be on free floor: the precomputed height there (and around it, for the
// body's width) must be at floor level.
constexpr double kFloorTolerance = 0.05;
constexpr double kClearance = 0.3;
// Draws of a free point in a room, and of a reachable goal, before taking the last one.
constexpr int kRoomDraws = 64;
constexpr int kGoalDraws = 32;
// Floor heights up to this count as free floor around a furniture start (m).
constexpr double kFloorClear = 0.05;
}  // namespace

WalkSkill::WalkSkill(const SkillConfig& config, const SkillContext& context)
    : Skill(config, context) {
  const int n = context.num_envs;
  walk_.assign(n, WalkState{});
  // Walk references only walking clips (the library may hold other skills).
  if (context.motions) {
    reference_clips_ = context.motions->Find("walk");
    if (reference_clips_.empty())
      for (int c = 0; c < context.motions->num_clips(); ++c) reference_clips_.push_back(c);
    if (config.walk.style_pose_weight > 0) {
      posture_ = true;
      for (int c = 0; c < context.motions->num_clips(); ++c) {
        const auto& frames = context.motions->clip(c).frames();
        JointAngles mean = JointAngles::Zero();
        for (const auto& f : frames) mean += f.dof_pos;
        clip_mean_pose_.push_back(mean / static_cast<double>(frames.size()));
      }
    }
  }
  if (config.walk.rooms > 0) {
    SIMS_CHECK_MSG(context.scene && context.height_grid && !context.scene->rooms.empty(),
                   "walk_rooms needs the skill's room scene");
    free_space_ =
        std::make_unique<const scene::FreeSpaceGrid>(*context.scene, *context.height_grid);
    for (const scene::Room& r : context.scene->rooms) {
      Eigen::Vector2d lo = r.floor_polygon.front(), hi = lo;
      for (const auto& q : r.floor_polygon) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      room_boxes_.emplace_back(lo, hi);
      room_sides_.push_back(FurnitureSides(*context.scene, r.id));
    }
  }
}

std::vector<WalkSkill::FurnitureSide> WalkSkill::FurnitureSides(const scene::Scene& scene,
                                                                const std::string& room) {
  std::vector<FurnitureSide> sides;
  for (const scene::Object& o : scene.objects) {
    if (o.room != room || !o.is_static) continue;
    const scene::Aabb b = o.LocalBounds();
    if (b.empty()) continue;
    const Eigen::Vector3d c = 0.5 * (b.min + b.max), h = 0.5 * (b.max - b.min);
    for (int axis = 0; axis < 2; ++axis)
      for (double sign : {-1.0, 1.0}) {
        Eigen::Vector3d n_O = Eigen::Vector3d::Zero(), mid_O = c, along_O = Eigen::Vector3d::Zero();
        n_O[axis] = sign;
        mid_O[axis] += sign * h[axis];
        along_O[1 - axis] = 1.0;
        FurnitureSide side;
        side.p_WM = (o.X_WO * mid_O).head<2>();
        side.n_W = (o.X_WO.linear() * n_O).head<2>().normalized();
        side.t_W = (o.X_WO.linear() * along_O).head<2>().normalized();
        side.half_width = h[1 - axis];
        sides.push_back(side);
      }
  }
  return sides;
}

bool WalkSkill::FurnitureStart(int k, Rng& rng, Eigen::Vector2d* p_WP, double* yaw) const {
  const std::vector<FurnitureSide>& sides = room_sides_[k];
  if (sides.empty()) return false;
  const auto& walk = config_.walk;
  for (int draw = 0; draw < kRoomDraws; ++draw) {
    const FurnitureSide& s = sides[rng.UniformInt(static_cast<int64_t>(sides.size()))];
    const double along = rng.Uniform(-1.0, 1.0) * std::max(s.half_width - 0.15, 0.0);
    const double off = rng.Uniform(walk.furniture_start_min, walk.furniture_start_max);
    const Eigen::Vector2d p = s.p_WM + along * s.t_W + off * s.n_W;
    // Standing room: floor around the pelvis (a foot's reach) inside the room, no other piece
    // or wall in it (the side itself is at least furniture_start_min away).
    const auto& [lo, hi] = room_boxes_[k];
    if ((p.array() < lo.array() + kClearance).any() || (p.array() > hi.array() - kClearance).any())
      continue;
    bool clear = true;
    for (double a = 0; a < 2 * M_PI && clear; a += M_PI / 4)
      for (double r : {0.0, 0.12, 0.2}) {
        const Eigen::Vector2d q = p + r * Eigen::Vector2d(std::cos(a), std::sin(a));
        if (context_.height_grid->Height(q.x(), q.y()) > kFloorClear) clear = false;
      }
    if (!clear) continue;
    *p_WP = p;
    *yaw = std::atan2(-s.n_W.y(), -s.n_W.x()) + rng.Uniform(-0.35, 0.35);
    return true;
  }
  return false;
}

std::string WalkSkill::start_label(int i) const {
  if (!free_space_) return "";
  return walk_[i].furniture_start ? "furniture" : "free";
}

int WalkSkill::room(int env_id) const {
  return room_boxes_.empty() ? -1 : env_id % static_cast<int>(room_boxes_.size());
}

Eigen::Vector2d WalkSkill::FreePointInRoom(int k, Rng& rng) const {
  const auto& [lo, hi] = room_boxes_[k];
  for (int draw = 0; draw < kRoomDraws; ++draw) {
    const Eigen::Vector2d p(rng.Uniform(lo.x(), hi.x()), rng.Uniform(lo.y(), hi.y()));
    if (free_space_->Free(p)) return p;
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  return free_space_->NearestFree(centre, 0.5 * (hi - lo).norm()).value_or(centre);
}

void WalkSkill::SampleRoomGoal(int i, const Eigen::Vector2d& from, Rng& rng) {
  Eigen::Vector2d goal = from;
  std::vector<Eigen::Vector2d> waypoints;
  for (int draw = 0; draw < kGoalDraws; ++draw) {
    const Eigen::Vector2d p = FreePointInRoom(room(i), rng);
    const double d = (p - from).norm();
    if (d < config_.walk.target_min_distance || d > config_.walk.target_max_distance) continue;
    auto w = free_space_->Waypoints(from, p);
    if (w.empty()) continue;
    goal = p;
    waypoints = std::move(w);
    break;
  }
  // A room without a reachable goal in range keeps the character where it is: a trivial but
  // valid episode.
  if (waypoints.empty()) waypoints = {goal};
  WalkState& st = walk_[i];
  st.goal = goal;
  st.hold = 0;
  st.path = scene::PathFollower(from, std::move(waypoints));
  FollowPath(i, from);
}

void WalkSkill::FollowPath(int i, const Eigen::Vector2d& root) {
  WalkState& st = walk_[i];
  st.target = st.path.Carrot(root, config_.walk.path_lookahead);
  ClearGoals(i);
  SetGoal(i, humanoid::kCjPelvis, {st.target.x(), st.target.y(), kStandingPelvisHeight});
}

void WalkSkill::SampleInitialState(int i, Rng& rng, sim::InitialState* init) {
  Eigen::Vector2d p;
  double yaw = 0;
  if (free_space_ && config_.walk.furniture_start_share > 0 &&
      rng.Bernoulli(config_.walk.furniture_start_share) && FurnitureStart(room(i), rng, &p, &yaw)) {
    // Standing still, as a finished sit-up, reach or get-up leaves the character: no walking
    // clip state (one would stride into the furniture).
    init->pose.root_pos.x() = p.x();
    init->pose.root_pos.y() = p.y();
    init->pose.root_rot = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
    state_[i].style = DrawReferenceStyle(rng);  // -1 without clips, as the default init
    walk_[i].furniture_start = true;
    return;
  }
  walk_[i].furniture_start = false;
  if (free_space_) {
    const Eigen::Vector2d p = FreePointInRoom(room(i), rng);
    init->pose.root_pos.x() = p.x();
    init->pose.root_pos.y() = p.y();
  }
  Skill::SampleInitialState(i, rng, init);
}

bool WalkSkill::Collided(const sim::EnvView& view) { return !OnlyFeetOnTheFloor(view); }

Eigen::Vector2d WalkSkill::SampleTarget(const Eigen::Vector2d& from, Rng& rng) const {
  const auto& grid = *context_.height_grid;
  Eigen::Vector2d best = from;
  for (int attempt = 0; attempt < 32; ++attempt) {
    const double r =
        rng.Uniform(config_.walk.target_min_distance, config_.walk.target_max_distance);
    const double a = rng.Uniform(-M_PI, M_PI);
    const Eigen::Vector2d p = from + r * Eigen::Vector2d(std::cos(a), std::sin(a));
    best = p;
    bool free = grid.Height(p.x(), p.y()) < kFloorTolerance;
    for (int k = 0; k < 8 && free; ++k) {
      const double b = k * M_PI / 4;
      free = grid.Height(p.x() + kClearance * std::cos(b), p.y() + kClearance * std::sin(b)) <
             kFloorTolerance;
    }
    if (free) return p;
  }
  return best;  // a cluttered scene: the last draw is still a valid, if hard, target
}

void WalkSkill::SetTarget(int env_id, const Eigen::Vector2d& target_xy) {
  walk_[env_id].target = target_xy;
  walk_[env_id].goal = target_xy;
  // Among furniture the next step would move the goal back onto the old path.
  if (free_space_) walk_[env_id].path = scene::PathFollower(target_xy, {});
  walk_[env_id].hold = 0;
  ClearGoals(env_id);
  SetGoal(env_id, humanoid::kCjPelvis, {target_xy.x(), target_xy.y(), kStandingPelvisHeight});
}

void WalkSkill::OnReset(const sim::EnvView& view, Rng& rng) {
  const int i = view.env_id;
  // Seed the env's private target stream from the env RNG so resets stay reproducible.
  walk_[i].target_rng = Rng(rng.NextU64());
  const Eigen::Vector2d root = view.pose->root_pos.head<2>();
  walk_[i].prev_velocity = view.pose->root_lin_vel.head<2>();
  if (posture_) walk_[i].pose_average = view.pose->dof_pos;
  NewGoal(i, root);
}

void WalkSkill::NewGoal(int i, const Eigen::Vector2d& from) {
  if (free_space_)
    SampleRoomGoal(i, from, walk_[i].target_rng);
  else
    SetTarget(i, SampleTarget(from, walk_[i].target_rng));
}

bool WalkSkill::BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) {
  Eigen::Vector2d p;
  if (target.has_point) {
    p = target.point.head<2>();
  } else if (target.object >= 0 && context_.scene &&
             target.object < static_cast<int>(context_.scene->objects.size())) {
    p = context_.scene->objects[target.object].Bounds().center().head<2>();
  } else {
    return false;
  }
  walk_[view.env_id].prev_velocity = view.pose->root_lin_vel.head<2>();
  SetTarget(view.env_id, p);
  return true;
}

double WalkSkill::target_speed(int env_id) const {
  const int clip = style_id(env_id);
  if (!config_.walk.speed_from_style || !context_.motions || clip < 0 ||
      clip >= context_.motions->num_clips())
    return config_.target_speed;
  const auto& params = context_.motions->clip(clip).meta().params;
  const auto it = params.find("speed");
  if (it == params.end()) return config_.target_speed;
  return std::clamp(it->second, config_.walk.style_speed_min, config_.walk.style_speed_max);
}

double WalkSkill::StylePoseReward(int env_id, const JointAngles& mean_pose) const {
  const int clip = style_id(env_id);
  if (clip < 0 || clip >= static_cast<int>(clip_mean_pose_.size())) return 1.0;
  const double mse = (mean_pose - clip_mean_pose_[clip]).squaredNorm() / humanoid::kNumDofs;
  return std::exp(-config_.walk.style_pose_scale * mse);
}

double WalkSkill::goal_error(const sim::EnvView& view) const {
  return (walk_[view.env_id].goal - view.pose->root_pos.head<2>()).norm();
}

double WalkSkill::Reward(const Eigen::Vector2d& target, const Eigen::Vector2d& root,
                         const Eigen::Vector2d& velocity, const Eigen::Vector2d& prev_velocity,
                         const Eigen::Vector2d& facing, double target_speed) {
  const Eigen::Vector2d delta = target - root;
  const double d2 = delta.squaredNorm();
  const double r_near = std::exp(-10.0 * d2);
  if (d2 > 0.5) {
    const Eigen::Vector2d dir = delta / std::sqrt(d2);
    // Moving or facing away earns nothing (a squared cosine would pay facing away too).
    const double v = dir.dot(velocity);
    const double speed_err = target_speed - v;
    const double r_speed = v > 0 ? std::exp(-2.0 * speed_err * speed_err) : 0.0;
    const double r_far =
        0.6 * std::exp(-0.5 * d2) + 0.2 * r_speed + 0.2 * std::max(0.0, dir.dot(facing));
    return 0.4 * r_near + 0.5 * r_far;
  }
  const double r_still = std::exp(-2.0 * (velocity - prev_velocity).squaredNorm());
  return 0.4 * r_near + 0.5 + 0.1 * r_still;
}

sim::TaskStepResult WalkSkill::Step(const sim::EnvView& view) {
  const int i = view.env_id;
  const Eigen::Vector2d root = view.pose->root_pos.head<2>();
  const Eigen::Vector2d vel = view.pose->root_lin_vel.head<2>();
  const double heading = humanoid::HeadingAngle(view.pose->root_rot);
  const Eigen::Vector2d facing(std::cos(heading), std::sin(heading));

  sim::TaskStepResult r;
  double reward =
      Reward(walk_[i].target, root, vel, walk_[i].prev_velocity, facing, target_speed(i));
  const double w = config_.walk.style_pose_weight;
  const double w_slide = config_.walk.foot_slide_weight;
  double r_pose = reward;  // without style clips the posture share stays with r_walk
  if (w > 0 && posture_) {
    const double a = std::min(1.0, view.control_dt / config_.walk.style_pose_time);
    walk_[i].pose_average += a * (view.pose->dof_pos - walk_[i].pose_average);
    r_pose = StylePoseReward(i, walk_[i].pose_average);
  }
  const double r_slide = w_slide > 0 ? FootSlideReward(*view.bodies) : 0.0;
  reward = (1 - w - w_slide) * reward + w * r_pose + w_slide * r_slide;
  r.reward = static_cast<float>(reward);
  walk_[i].prev_velocity = vel;
  if (free_space_ && Collided(view)) {
    r.terminate = true;
    walk_[i].hold = 0;
    return r;
  }
  r.success = (walk_[i].goal - root).norm() < config_.walk.success_radius;
  walk_[i].hold = r.success ? walk_[i].hold + 1 : 0;
  r.completed = walk_[i].hold >= config_.success_hold_steps;
  if (r.completed && config_.walk.resample_target_on_success) {
    NewGoal(i, root);
  } else if (free_space_) {
    FollowPath(i, root);  // the next observation's pelvis goal
  }
  return r;
}

void WalkState::Serialize(StateArchive* a) {
  a->Reals("target", &target);
  a->Reals("prev_velocity", &prev_velocity);
  a->Int("hold", &hold, 0, std::numeric_limits<int>::max());
  a->RngState("target_rng", &target_rng);
}

void WalkSkill::SerializeSkillState(int env_id, StateArchive* a) {
  WalkState& st = walk_[env_id];
  st.Serialize(a);
  if (free_space_) {
    a->Reals("goal", &st.goal);
    std::vector<Eigen::Vector2d> points = st.path.points();
    int64_t n = static_cast<int64_t>(points.size());
    a->Int("path_points", &n, 1, free_space_->nx() * static_cast<int64_t>(free_space_->ny()) + 2);
    points.resize(n);
    for (auto& q : points) a->Reals("path_point", &q);
    int64_t segment = static_cast<int64_t>(st.path.segment());
    double progress = st.path.progress();
    a->Int("path_segment", &segment, 0, n - 1);
    a->Real("path_progress", &progress);
    if (a->loading()) {
      st.path = scene::PathFollower(points.front(), {points.begin() + 1, points.end()});
      st.path.Restore(static_cast<size_t>(segment), progress);
    }
  } else if (a->loading()) {
    st.goal = st.target;  // on open floor the goal is the target
  }
  if (!posture_) return;
  if (!a->loading() || a->left() > 0) {
    a->Reals("pose_average", &st.pose_average);
  } else {
    // A snapshot taken before the posture term was switched on (a resumed campaign) has no
    // average: it starts at the style clip's mean and catches up within style_pose_time.
    const int clip = style_id(env_id);
    const bool known = clip >= 0 && clip < static_cast<int>(clip_mean_pose_.size());
    st.pose_average = known ? clip_mean_pose_[clip] : JointAngles::Zero();
  }
}

void WalkParams::Validate() const {
  Require(target_min_distance >= 0 && target_max_distance >= target_min_distance,
          "target_max_distance", "a distance ≥ target_min_distance ≥ 0");
  Require(success_radius > 0, "walk_success_radius", "a positive radius (m)");
  Require(style_speed_min > 0 && style_speed_max >= style_speed_min, "style_speed_max",
          "speeds with 0 < style_speed_min ≤ style_speed_max (m/s)");
  Require(style_pose_weight >= 0 && style_pose_weight <= 1, "style_pose_weight",
          "a share in [0, 1]");
  Require(style_pose_scale > 0, "style_pose_scale", "a positive scale (1/rad²)");
  Require(style_pose_time > 0, "style_pose_time", "a positive time constant (s)");
  Require(rooms >= 0 && rooms <= 64, "walk_rooms", "a room count in [0, 64] (0: open floor)");
  Require(path_lookahead > 0, "walk_path_lookahead", "a positive distance (m)");
  Require(foot_slide_weight >= 0 && foot_slide_weight + style_pose_weight <= 1, "foot_slide_weight",
          "a share in [0, 1 − style_pose_weight]");
  Require(foot_slide_scale > 0, "foot_slide_scale", "a positive scale (s²/m²)");
  Require(foot_contact_height > 0, "foot_contact_height", "a positive height (m)");
  Require(furniture_start_share >= 0 && furniture_start_share <= 1, "walk_furniture_start_share",
          "a share in [0, 1]");
  Require(furniture_start_min > 0 && furniture_start_max >= furniture_start_min,
          "walk_furniture_start_max", "distances with 0 < walk_furniture_start_min ≤ max (m)");
}

double WalkSkill::FootSlideReward(const humanoid::BodyStates& b) const {
  double sum = 0;
  for (int foot : {humanoid::kLeftFoot, humanoid::kRightFoot})
    if (b.pos[foot].z() < config_.walk.foot_contact_height)
      sum += b.lin_vel[foot].head<2>().squaredNorm();
  return std::exp(-config_.walk.foot_slide_scale * sum);
}

// The registry entry: vocabulary traits (core/skill_vocabulary.cpp), params, scene, factory.
SkillInfo WalkSkillInfo() {
  SkillInfo info = BuiltinSkillInfo("walk");
  info.params = ConfigToJson(WalkParams{});
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    if (c.walk.rooms > 0) return scene::RandomRooms(c.walk.rooms, rng, c.object.held_out_objects);
    scene::Scene s;
    s.name = "flat_ground";
    return s;
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<WalkSkill>(c, ctx);
  };
  // Evaluation: one fixed target 3–5 m away per episode.
  info.configure_eval = [](SkillConfig* c) {
    c->walk.target_min_distance = 3.0;
    c->walk.target_max_distance = 5.0;
    c->walk.resample_target_on_success = false;
  };
  return info;
}

}  // namespace sims::task
