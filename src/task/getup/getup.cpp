#include "sims/task/getup/getup.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sims/core/error.h"
#include "sims/core/parallel.h"
#include "sims/humanoid/features.h"
#include "sims/task/handoff.h"
#include "sims/task/sit/sit.h"
#include "task/cached.h"

namespace sims::task {

namespace {
// ASE's 150 fall steps at 60 Hz, at our 120 Hz physics.
constexpr int kFallPhysicsSteps = 300;
constexpr double kFallStartHeight = 1.0;
constexpr double kUprightCos = 0.8;
constexpr uint64_t kFallSeed = 0xFA11u;
// Floor clips start lying: their bodies reach about this far from the root (m).
constexpr double kLyingReach = 1.0;
// Free floor kept around the outermost body of a floor start (m).
constexpr double kFloorMargin = 0.3;
// The first quarter of a get-up clip is still seated or lying.
constexpr double kSeatedFraction = 0.25;

std::shared_ptr<const std::vector<FallState>> CachedFallStates(int count) {
  return Cached<std::vector<FallState>>(count,
                                        [&] { return GenerateFallStates(count, kFallSeed); });
}

}  // namespace

std::vector<FallState> GenerateFallStates(int count, uint64_t seed) {
  SIMS_CHECK(count >= 1);
  const humanoid::Humanoid h(humanoid::BuildModel());
  const mjModel* m = h.model();
  std::vector<FallState> out(count);
  std::vector<uint8_t> ok(count, 0);
#pragma omp parallel num_threads(ThreadCount())
  {
    humanoid::MjDataPtr data = humanoid::MakeData(m);
    mjData* d = data.get();
    humanoid::BodyStates b;
#pragma omp for schedule(dynamic)
    for (int k = 0; k < count; ++k) {
      Rng rng(seed + static_cast<uint64_t>(k));
      for (int attempt = 0; attempt < 4 && !ok[k]; ++attempt) {
        mj_resetData(m, d);
        humanoid::HumanoidPose p;
        p.root_pos = Eigen::Vector3d(0, 0, kFallStartHeight);
        Eigen::Vector4d q(rng.Normal(), rng.Normal(), rng.Normal(), rng.Normal());
        q.normalize();
        p.root_rot = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
        humanoid::WritePose(h, p, d);
        float action[humanoid::kNumDofs];
        double targets[humanoid::kNumDofs];
        for (float& a : action) a = static_cast<float>(rng.Uniform(-0.5, 0.5));
        h.ActionToTargets(action, targets);
        for (int j = 0; j < humanoid::kNumDofs; ++j) d->ctrl[h.actuator_id(j)] = targets[j];
        for (int s = 0; s < kFallPhysicsSteps; ++s) mj_step(m, d);
        humanoid::ReadPose(h, d, &p);
        if (!(p.root_pos.allFinite() && p.dof_pos.allFinite() && p.dof_vel.allFinite())) continue;
        humanoid::ReadBodyStates(h, d, &b);
        FallState& f = out[k];
        for (int j = 0; j < humanoid::kNumBodies; ++j)
          f.reach = std::max(f.reach, (b.pos[j] - p.root_pos).head<2>().norm());
        p.root_pos.x() = 0;
        p.root_pos.y() = 0;
        f.pose = p;
        ok[k] = 1;
      }
    }
  }
  std::vector<FallState> kept;
  for (int k = 0; k < count; ++k)
    if (ok[k]) kept.push_back(out[k]);
  SIMS_CHECK_MSG(!kept.empty(), "fall-state generation diverged");
  return kept;
}

void GetUpParams::Validate() const {
  Require(fall_states >= 1, "getup_fall_states", "at least 1 fall state");
  Require(fall_grace_steps >= 0, "getup_fall_grace_steps", "a step count ≥ 0");
  Require(floor_clip_share >= 0 && floor_clip_share <= 1, "getup_floor_clip_share",
          "a share in [0, 1]");
  Require(standing_head_height > standing_pelvis_height && standing_pelvis_height > 0,
          "getup_standing_head_height", "heights with 0 < pelvis < head (m)");
  Require(bed_raise >= 0 && bed_raise <= 0.5, "getup_bed_raise", "a height in [0, 0.5] m");
  Require(reference_max_fraction > 0 && reference_max_fraction <= 1, "getup_reference_max_fraction",
          "a fraction in (0, 1]");
  Require(backplay_end >= 0 && backplay_end <= 1, "getup_backplay_end",
          "a fraction in [0, 1] (0 = no backplay)");
  Require(backplay_step > 0 && backplay_step <= 1, "getup_backplay_step", "a step in (0, 1]");
  Require(furniture_stand_sharpness > 0, "getup_furniture_stand_sharpness",
          "a positive factor (1/m²)");
}

GetUpSkill::GetUpSkill(const SkillConfig& config, const SkillContext& context)
    : ObjectSkill(config, context) {
  const int n = context.num_envs;
  GetUpState initial;
  initial.phase = kFeetPhase;
  initial.start = kFallStart;
  getup_.assign(n, initial);
  reference_clips_.clear();
  if (context.motions) {
    // Clips without furniture parameters get up from the floor.
    for (const int c : context.motions->Find("getup")) {
      const auto& prm = context.motions->clip(c).meta().params;
      (prm.count("furniture_height") ? furniture_clips_ : floor_clips_).push_back(c);
      reference_clips_.push_back(c);
    }
  }
  fall_states_ = CachedFallStates(config.getup.fall_states);
  // The feet goal's height: foot origins of the standing default pose.
  humanoid::MjDataPtr scratch = humanoid::MakeData(context.humanoid->model());
  humanoid::BodyStates b;
  humanoid::ForwardKinematics(*context.humanoid, humanoid::HumanoidPose{}, scratch.get(), &b);
  foot_height_ = 0.5 * (b.pos[humanoid::kLeftFoot].z() + b.pos[humanoid::kRightFoot].z());
  head_height_ = b.pos[humanoid::kHead].z();
  CollectObjects("seat or bed (a 'seat surface' or 'mattress' part)");
}

bool GetUpSkill::Accepts(const ObjectGeometry& g) const {
  return g.part(kSeatPart) || g.part(kMattressPart);
}

uint32_t GetUpSkill::contact_body_mask() const {
  using namespace humanoid;
  return (1u << kLeftFoot) | (1u << kRightFoot) | (1u << kLeftHand) | (1u << kRightHand) |
         (1u << kPelvis) | (1u << kLeftThigh) | (1u << kRightThigh);
}

std::string GetUpSkill::start_label(int env_id) const {
  switch (getup_[env_id].start) {
    case kSeatStart:
      return "seat";
    case kBedStart:
      return "bed";
    case kFloorClipStart:
      return "floor";
    case kHandoffStart:
      return "handoff";
    default:
      return "fall";
  }
}

bool GetUpSkill::Standing(const humanoid::BodyStates& b, const GetUpParams& params) {
  return b.pos[humanoid::kPelvis].z() >= params.standing_pelvis_height &&
         b.pos[humanoid::kHead].z() >= params.standing_head_height &&
         (b.rot[humanoid::kPelvis] * Eigen::Vector3d::UnitZ()).z() >= kUprightCos &&
         (b.rot[humanoid::kTorso] * Eigen::Vector3d::UnitZ()).z() >= kUprightCos;
}

bool GetUpSkill::StandingClear(const sim::EnvView& view) const {
  return Standing(*view.bodies, config_.getup) && OnlyFeetOnTheFloor(view);
}

GetUpSkill::RiseInputs GetUpSkill::RiseInputsOf(const humanoid::BodyStates& b) {
  RiseInputs x;
  x.pelvis_z = b.pos[humanoid::kPelvis].z();
  x.head_z = b.pos[humanoid::kHead].z();
  x.pelvis_up = (b.rot[humanoid::kPelvis] * Eigen::Vector3d::UnitZ()).z();
  x.torso_up = (b.rot[humanoid::kTorso] * Eigen::Vector3d::UnitZ()).z();
  x.pelvis_xy = b.pos[humanoid::kPelvis].head<2>();
  x.upper_xy =
      (b.pos[humanoid::kPelvis] + b.pos[humanoid::kTorso] + b.pos[humanoid::kHead]).head<2>() / 3.0;
  x.feet_xy = 0.5 * (b.pos[humanoid::kLeftFoot] + b.pos[humanoid::kRightFoot]).head<2>();
  return x;
}

double GetUpSkill::RiseReward(const RiseInputs& x, const Eigen::Vector2d& stand, double head_height,
                              double stand_sharpness) {
  const double dp = std::max(humanoid::kDefaultRootHeight - x.pelvis_z, 0.0);
  const double dh = std::max(head_height - x.head_z, 0.0);
  const double height = 0.4 * std::exp(-20.0 * dp * dp) + 0.3 * std::exp(-8.0 * dh * dh) +
                        0.15 * std::exp(-2.0 * dh * dh);
  const double upright = 0.6 + 0.2 * std::max(x.pelvis_up, 0.0) + 0.2 * std::max(x.torso_up, 0.0);
  const double balance = std::exp(-10.0 * (x.upper_xy - x.feet_xy).squaredNorm());
  return upright * height * (0.6 + 0.4 * balance) +
         0.15 * std::exp(-stand_sharpness * (stand - x.pelvis_xy).squaredNorm());
}

Eigen::Vector3d GetUpSkill::FootTarget(const Eigen::Vector2d& stand,
                                       const Eigen::Vector3d& p) const {
  Eigen::Vector2d q = p.head<2>() - stand;
  if (q.norm() > kStandDiskRadius) q *= kStandDiskRadius / q.norm();
  return Eigen::Vector3d(stand.x() + q.x(), stand.y() + q.y(), foot_height_);
}

bool GetUpSkill::ClearFloorPoint(int i, double reach, Rng& rng, Eigen::Vector2d* p) const {
  for (int attempt = 0; attempt < 16; ++attempt) {
    *p = SpawnPoint(i, geometry(i), rng);
    if (FreeFloor(*p, reach + kFloorMargin)) return true;
  }
  return false;
}

bool GetUpSkill::HandoffInit(int i, Rng& rng, sim::InitialState* init) {
  if (!ObjectSkill::HandoffInit(i, rng, init)) return false;
  getup_[i].start = kHandoffStart;
  return true;
}

bool GetUpSkill::ReferenceInit(int i, Rng& rng, sim::InitialState* init) {
  const bool floor = !floor_clips_.empty() &&
                     (furniture_clips_.empty() || rng.Bernoulli(config_.getup.floor_clip_share));
  if (floor) {
    const int clip = floor_clips_[rng.UniformInt(static_cast<int64_t>(floor_clips_.size()))];
    const auto& c = context_.motions->clip(clip);
    const double t = ReferenceTime(i, c.duration(), 1.0, /*floor=*/true, rng);
    Eigen::Vector2d p;
    if (!ClearFloorPoint(i, kLyingReach, rng, &p)) return false;
    const Eigen::Vector2d root = context_.motions->StateAt(clip, t).pose.root_pos.head<2>();
    const ClipPlacement placement = ClipPlacement::Align(p, rng.Uniform(-M_PI, M_PI), root, 0.0);
    PlaceReference(i, clip, t, placement, init);
    // Lying on the floor is a fall to the env: the same grace as a fall state.
    init->termination_grace_steps = config_.getup.fall_grace_steps;
    getup_[i].start = kFloorClipStart;
    return true;
  }
  ClipPlacement placement;
  const double lateral = SeatLateral(geometry(i), rng);
  const bool bed = geometry(i).part(kMattressPart) != nullptr;
  const int clip = ChooseFurnitureClip(furniture_clips_, geometry(i), lateral, rng, &placement,
                                       bed ? config_.getup.bed_raise : kMaxClipHeightMismatch);
  if (clip < 0) return false;
  const double t = ReferenceTime(i, context_.motions->clip(clip).duration(),
                                 placement.dz > kMaxClipHeightMismatch ? kSeatedFraction : 1.0,
                                 /*floor=*/false, rng);
  PlaceReference(i, clip, t, placement, init);
  getup_[i].start = bed ? kBedStart : kSeatStart;
  return true;
}

double GetUpSkill::ReferenceTime(int i, double duration, double max_fraction, bool floor,
                                 Rng& rng) const {
  const auto& p = config_.getup;
  if (p.backplay_end <= 0)
    return rng.Uniform(0.0, std::min(p.reference_max_fraction, max_fraction) * duration);
  // Every clip, a lifted bed's too, since a risen start stands on the floor (FurnitureShare).
  const double end = p.backplay_end;
  const double level = floor ? getup_[i].floor_backplay : getup_[i].backplay;
  return rng.Uniform((1.0 - level) * end * duration, end * duration);
}

void GetUpSkill::SampleInitialState(int i, Rng& rng, sim::InitialState* init) {
  // Learns from the episode that just ended, as the spawn curriculum does (fall-state starts
  // have no clip time and leave the levels alone). Floor clips keep their own level: rising
  // from lying on the floor is far harder than from a seat, and one shared level sat near 1
  // from the seat starts, so floor clips started lying down and never succeeded.
  if (config_.getup.backplay_end > 0 && env_[i].started && env_[i].reference) {
    double& level =
        getup_[i].start == kFloorClipStart ? getup_[i].floor_backplay : getup_[i].backplay;
    level = NextCurriculumLevel(level, env_[i].hold >= config_.success_hold_steps,
                                config_.getup.backplay_step);
  }
  ObjectSkill::SampleInitialState(i, rng, init);
}

double GetUpSkill::curriculum_level(int i) const {
  return config_.getup.backplay_end > 0 ? getup_[i].backplay : ObjectSkill::curriculum_level(i);
}

void GetUpSkill::SetBackplayLevel(int i, double level, bool floor) {
  SIMS_CHECK(level >= 0 && level <= 1);
  (floor ? getup_[i].floor_backplay : getup_[i].backplay) = level;
}

void GetUpSkill::DefaultInit(int i, Rng& rng, sim::InitialState* init) {
  getup_[i].start = kFallStart;
  const auto& states = *fall_states_;
  const FallState& f = states[rng.UniformInt(static_cast<int64_t>(states.size()))];
  ClipPlacement placement;
  // A crowded spot keeps the last draw: the episode is still valid, only harder.
  ClearFloorPoint(i, f.reach, rng, &placement.offset);
  placement.yaw = rng.Uniform(-M_PI, M_PI);
  init->pose = placement.Apply(f.pose);
  init->history.clear();
  init->reference = false;
  init->termination_grace_steps = config_.getup.fall_grace_steps;
  SetStyle(i, DrawReferenceStyle(rng));
}

void GetUpSkill::SetGetUpGoals(int i, const humanoid::BodyStates& b, double* feet_sq,
                               double* feet_max) {
  ClearGoals(i);
  SetGoal(i, humanoid::kCjPelvis,
          {getup_[i].stand.x(), getup_[i].stand.y(), humanoid::kDefaultRootHeight});
  *feet_sq = 0;
  *feet_max = 0;
  if (getup_[i].phase != kFeetPhase) return;
  for (int j : {humanoid::kCjLeftFoot, humanoid::kCjRightFoot}) {
    const Eigen::Vector3d x = humanoid::ContactJointPosition(b, j);
    const Eigen::Vector3d g = FootTarget(getup_[i].stand, x);
    SetGoal(i, j, g);
    *feet_sq += (g - x).squaredNorm();
    *feet_max = std::max(*feet_max, (g - x).norm());
  }
}

bool GetUpSkill::BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) {
  if (!ObjectSkill::BeginInstruction(view, target)) return false;
  const int i = view.env_id;
  getup_[i].start = target.object < 0 ? kFallStart : kSeatStart;  // no object: a fall
  StartGetUp(i, *view.bodies);
  if (target.has_point) {
    getup_[i].stand = target.point.head<2>();
    double sq = 0, mx = 0;
    SetGetUpGoals(i, *view.bodies, &sq, &mx);
  }
  env_[i].error =
      std::max(config_.getup.standing_pelvis_height - view.bodies->pos[humanoid::kPelvis].z(), 0.0);
  return true;
}

void GetUpSkill::StartGetUp(int i, const humanoid::BodyStates& b) {
  const Eigen::Vector2d pelvis = b.pos[humanoid::kPelvis].head<2>();
  getup_[i].stand = pelvis;
  getup_[i].furniture_stand = false;
  const ObjectGeometry& g = geometry(i);
  const Eigen::Vector3d& l = b.pos[humanoid::kLeftFoot];
  const Eigen::Vector3d& r = b.pos[humanoid::kRightFoot];
  // Seated with the feet on the floor, the way up is over the feet (the clips rise there): a
  // stand point at the object's stand point, ~0.45 m ahead of the seat, paid the feet for
  // sliding forward first, and the recorded seat trials tipped back with the feet ahead.
  // (A seat clip's feet may hang kMaxClipHeightMismatch above the floor until they settle.)
  const bool feet_down =
      std::max(l.z(), r.z()) < foot_height_ + kFloorContactHeight + kMaxClipHeightMismatch;
  if (!floor_start(i) && feet_down) {
    getup_[i].stand = 0.5 * (l + r).head<2>();
  } else if (!floor_start(i) && !g.stand_points.empty()) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& s : g.stand_points)
      if ((s.head<2>() - pelvis).squaredNorm() < best)
        best = (s.head<2>() - pelvis).squaredNorm(), getup_[i].stand = s.head<2>();
    getup_[i].furniture_stand = true;
  }
  getup_[i].phase = kFeetPhase;
  env_[i].hold = 0;
  double sq = 0, mx = 0;
  SetGetUpGoals(i, b, &sq, &mx);
}

void GetUpSkill::OnReset(const sim::EnvView& view, Rng&) {
  const int i = view.env_id;
  StartGetUp(i, *view.bodies);
  env_[i].error =
      std::max(config_.getup.standing_pelvis_height - view.bodies->pos[humanoid::kPelvis].z(), 0.0);
}

sim::TaskStepResult GetUpSkill::Step(const sim::EnvView& view) {
  const int i = view.env_id;
  const humanoid::BodyStates& b = *view.bodies;
  const Eigen::Vector2d root = view.pose->root_pos.head<2>();
  const Eigen::Vector2d vel = view.pose->root_lin_vel.head<2>();
  const Eigen::Vector2d facing = FacingOf(*view.pose);
  double sq = 0, mx = 0;
  SetGetUpGoals(i, b, &sq, &mx);
  double r = 0;
  const bool clear = StandingClear(view);
  if (getup_[i].phase == kFeetPhase) {
    r = kFeetPhaseWeight *
        ContactReward(getup_[i].stand, root, vel, facing, config_.target_speed, sq);
    if (mx < config_.object.contact_success_threshold) {
      getup_[i].phase = kRisePhase;
      SetGetUpGoals(i, b, &sq, &mx);
    }
  } else {
    const double k =
        getup_[i].furniture_stand ? config_.getup.furniture_stand_sharpness : kStandSharpness;
    const double rise = RiseReward(RiseInputsOf(b), getup_[i].stand, head_height_, k);
    r = kFeetPhaseWeight +
        (1.0 - kFeetPhaseWeight) * ((1.0 - kClearWeight) * rise + (clear ? kClearWeight : 0.0));
  }
  env_[i].error =
      std::max(config_.getup.standing_pelvis_height - b.pos[humanoid::kPelvis].z(), 0.0);
  return Finish(view, r, clear);
}

void GetUpState::Serialize(StateArchive* a) {
  a->Int("phase", &phase, GetUpSkill::kFeetPhase, GetUpSkill::kRisePhase);
  a->Int("start", &start, GetUpSkill::kSeatStart, GetUpSkill::kHandoffStart);
  a->Reals("stand", &stand);
  // Snapshots from before backplay (or before the floor level) end early: missing levels are 0.
  const std::pair<const char*, double*> levels[] = {{"backplay", &backplay},
                                                    {"floor_backplay", &floor_backplay}};
  for (const auto& [key, level] : levels) {
    if (!a->loading() || a->left() > 0)
      a->Real(key, level);
    else
      *level = 0;
    *level = std::clamp(*level, 0.0, 1.0);
  }
  // And from before the furniture stand flag: a seat's or the floor's stand point.
  if (!a->loading() || a->left() > 0)
    a->Flag("furniture_stand", &furniture_stand);
  else
    furniture_stand = false;
}

void GetUpSkill::SerializeTaskState(int i, StateArchive* a) { getup_[i].Serialize(a); }

SkillInfo GetUpSkillInfo() {
  SkillInfo info = BuiltinSkillInfo("getup");
  info.params = ConfigToJson(ObjectParams{});
  info.params.update(ConfigToJson(GetUpParams{}));
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    std::vector<std::string> cats = SeatCategories();
    cats.push_back("bed");
    return BuildTrainingGround(c, rng, cats);
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<GetUpSkill>(c, ctx);
  };
  // Evaluation starts seated or lying, whatever share of the rise training started from.
  info.configure_eval = [](SkillConfig* c) {
    c->getup.reference_max_fraction = kSeatedFraction;
    c->getup.backplay_end = 0;
  };
  return info;
}

}  // namespace sims::task
