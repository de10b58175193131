#include "sims/task/getup/getup.h"

#include <cmath>
#include <limits>

#include "sims/core/error.h"
#include "sims/sim/features.h"
#include "sims/task/sit/sit.h"

namespace sims::task {

namespace {
// ASE's 150 fall steps at 60 Hz, at our 120 Hz physics.
constexpr int kFallPhysicsSteps = 300;
constexpr double kFallStartHeight = 1.0;
constexpr double kUprightCos = 0.8;
}  // namespace

std::vector<sim::HumanoidPose> GenerateFallStates(int count, uint64_t seed) {
  const sim::Humanoid h(sim::BuildModel());
  const mjModel* m = h.model();
  sim::MjDataPtr data = sim::MakeData(m);
  mjData* d = data.get();
  std::vector<sim::HumanoidPose> out;
  Rng rng(seed);
  for (int attempt = 0; static_cast<int>(out.size()) < count && attempt < 4 * count; ++attempt) {
    mj_resetData(m, d);
    sim::HumanoidPose p;
    p.root_pos = Eigen::Vector3d(0, 0, kFallStartHeight);
    Eigen::Vector4d q(rng.Normal(), rng.Normal(), rng.Normal(), rng.Normal());
    q.normalize();
    p.root_rot = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    sim::WritePose(h, p, d);
    float action[sim::kNumDofs];
    double targets[sim::kNumDofs];
    for (float& a : action) a = static_cast<float>(rng.Uniform(-0.5, 0.5));
    h.ActionToTargets(action, targets);
    for (int j = 0; j < sim::kNumDofs; ++j) d->ctrl[h.actuator_id(j)] = targets[j];
    for (int s = 0; s < kFallPhysicsSteps; ++s) mj_step(m, d);
    sim::ReadPose(h, d, &p);
    bool finite = p.root_pos.allFinite() && p.dof_pos.allFinite() && p.dof_vel.allFinite();
    if (!finite) continue;
    p.root_pos.x() = 0;
    p.root_pos.y() = 0;
    out.push_back(p);
  }
  SIMS_CHECK_MSG(!out.empty(), "fall-state generation diverged");
  return out;
}

GetUpSkill::GetUpSkill(const SkillConfig& config, const SkillContext& context, bool sit_first)
    : ObjectSkill(config, context), sit_first_(sit_first) {
  const int n = context.num_envs;
  phase_.assign(n, sit_first ? kSitPhase : kFeetPhase);
  sit_hold_.assign(n, 0);
  fall_start_.assign(n, 0);
  stand_.assign(n, Eigen::Vector2d::Zero());
  reference_clips_.clear();
  if (context.motions) reference_clips_ = context.motions->Find(sit_first ? "sit" : "getup");
  if (!sit_first) {
    // The states depend only on the fixed seed: generate them once per process.
    static const std::vector<sim::HumanoidPose> states =
        GenerateFallStates(kNumFallStates, 0xFA11u);
    fall_states_ = states;
  }
  // The feet goal's height: foot origins of the standing default pose.
  sim::MjDataPtr scratch = sim::MakeData(context.humanoid->model());
  sim::BodyStates b;
  sim::ForwardKinematics(*context.humanoid, sim::HumanoidPose{}, scratch.get(), &b);
  foot_height_ = 0.5 * (b.pos[sim::kLeftFoot].z() + b.pos[sim::kRightFoot].z());
  CollectObjects(sit_first ? "object with a 'seat surface' part"
                           : "seat or bed (a 'seat surface' or 'mattress' part)");
}

bool GetUpSkill::Accepts(const ObjectGeometry& g) const {
  return g.seat >= 0 || (!sit_first_ && g.mattress >= 0);
}

uint32_t GetUpSkill::contact_body_mask() const {
  if (sit_first_) return ObjectSkill::contact_body_mask();
  using namespace sim;
  return (1u << kLeftFoot) | (1u << kRightFoot) | (1u << kLeftHand) | (1u << kRightHand) |
         (1u << kPelvis) | (1u << kLeftThigh) | (1u << kRightThigh);
}

bool GetUpSkill::Standing(const sim::BodyStates& b) {
  return b.pos[sim::kPelvis].z() >= kStandingPelvisHeight &&
         (b.rot[sim::kPelvis] * Eigen::Vector3d::UnitZ()).z() >= kUprightCos;
}

double GetUpSkill::RiseReward(double z, double up_z, const Eigen::Vector2d& stand,
                              const Eigen::Vector2d& pelvis_xy) {
  const double dz = std::max(sim::kDefaultRootHeight - z, 0.0);
  return 0.6 * std::exp(-10.0 * dz * dz) + 0.2 * std::max(up_z, 0.0) +
         0.2 * std::exp(-2.0 * (stand - pelvis_xy).squaredNorm());
}

Eigen::Vector3d GetUpSkill::FootTarget(const Eigen::Vector2d& stand,
                                       const Eigen::Vector3d& p) const {
  Eigen::Vector2d q = p.head<2>() - stand;
  if (q.norm() > kStandDiskRadius) q *= kStandDiskRadius / q.norm();
  return Eigen::Vector3d(stand.x() + q.x(), stand.y() + q.y(), foot_height_);
}

bool GetUpSkill::ReferenceInit(int i, Rng& rng, sim::InitialState* init) {
  fall_start_[i] = 0;
  ClipPlacement placement;
  const double lateral = SeatLateral(geometry(i), rng);
  const int clip = ChooseFurnitureClip(reference_clips_, geometry(i), lateral, rng, &placement);
  if (clip < 0) return false;
  const auto& c = context_.motions->clip(clip);
  double t = 0;
  if (sit_first_)
    t = context_.motions->SampleTime(clip, rng, config_.reference_init_max_fraction);
  else if (c.meta().skill == "getup")
    t = rng.Uniform(0.0, 0.25 * c.duration());  // still seated / lying
  else
    t = rng.Uniform(0.75 * c.duration(), c.duration());  // sit/lie clips end seated / lying
  PlaceReference(i, clip, t, placement, init);
  return true;
}

void GetUpSkill::DefaultInit(int i, Rng& rng, sim::InitialState* init) {
  if (sit_first_) {
    fall_start_[i] = 0;
    ObjectSkill::DefaultInit(i, rng, init);
    return;
  }
  fall_start_[i] = 1;
  const int k = static_cast<int>(rng.UniformInt(static_cast<int64_t>(fall_states_.size())));
  ClipPlacement placement;
  placement.offset = SpawnPoint(i, geometry(i), rng);
  placement.yaw = rng.Uniform(-M_PI, M_PI);
  init->pose = placement.Apply(fall_states_[k]);
  init->history.clear();
  init->reference = false;
  init->termination_grace_steps = kFallGraceSteps;
  const auto& clips = ReferenceClips();
  style_[i] = clips.empty() ? -1 : clips[rng.UniformInt(static_cast<int64_t>(clips.size()))];
}

void GetUpSkill::SetGetUpGoals(int i, const sim::BodyStates& b, double* feet_sq, double* feet_max) {
  ClearGoals(i);
  SetGoal(i, sim::kCjPelvis, {stand_[i].x(), stand_[i].y(), sim::kDefaultRootHeight});
  *feet_sq = 0;
  *feet_max = 0;
  if (phase_[i] != kFeetPhase) return;
  for (int j : {sim::kCjLeftFoot, sim::kCjRightFoot}) {
    const Eigen::Vector3d x = sim::ContactJointPosition(b, j);
    const Eigen::Vector3d g = FootTarget(stand_[i], x);
    SetGoal(i, j, g);
    *feet_sq += (g - x).squaredNorm();
    *feet_max = std::max(*feet_max, (g - x).norm());
  }
}

bool GetUpSkill::BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) {
  if (!ObjectSkill::BeginInstruction(view, target)) return false;
  const int i = view.env_id;
  sit_hold_[i] = 0;
  fall_start_[i] = target.object < 0;  // a fall: stand up where the character lies
  StartGetUp(i, *view.bodies);
  if (target.has_point) {
    stand_[i] = target.point.head<2>();
    double sq = 0, mx = 0;
    SetGetUpGoals(i, *view.bodies, &sq, &mx);
  }
  error_[i] = std::max(kStandingPelvisHeight - view.bodies->pos[sim::kPelvis].z(), 0.0);
  return true;
}

void GetUpSkill::StartGetUp(int i, const sim::BodyStates& b) {
  const Eigen::Vector2d pelvis = b.pos[sim::kPelvis].head<2>();
  stand_[i] = pelvis;
  const ObjectGeometry& g = geometry(i);
  if (!fall_start_[i] && !g.stand_points.empty()) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& s : g.stand_points)
      if ((s.head<2>() - pelvis).squaredNorm() < best)
        best = (s.head<2>() - pelvis).squaredNorm(), stand_[i] = s.head<2>();
  }
  phase_[i] = kFeetPhase;
  hold_[i] = 0;
  double sq = 0, mx = 0;
  SetGetUpGoals(i, b, &sq, &mx);
}

void GetUpSkill::OnReset(const sim::EnvView& view, Rng&) {
  const int i = view.env_id;
  sit_hold_[i] = 0;
  if (sit_first_) {
    phase_[i] = kSitPhase;
    const ObjectGeometry& g = geometry(i);
    ClearGoals(i);
    const Eigen::Vector3d x = sim::ContactJointPosition(*view.bodies, sim::kCjPelvis);
    const Eigen::Vector3d seat = NearestOnPart(*context_.scene, g.object, g.seat, x);
    SetGoal(i, sim::kCjPelvis, seat);
    error_[i] = (seat - x).norm();
    return;
  }
  StartGetUp(i, *view.bodies);
  error_[i] = std::max(kStandingPelvisHeight - view.bodies->pos[sim::kPelvis].z(), 0.0);
}

sim::TaskStepResult GetUpSkill::Step(const sim::EnvView& view) {
  const int i = view.env_id;
  const sim::BodyStates& b = *view.bodies;
  const Eigen::Vector2d root = view.pose->root_pos.head<2>();
  const Eigen::Vector2d vel = view.pose->root_lin_vel.head<2>();
  const Eigen::Vector2d facing = FacingOf(*view.pose);
  if (phase_[i] == kSitPhase) {
    const ObjectGeometry& g = geometry(i);
    const Eigen::Vector3d x = sim::ContactJointPosition(b, sim::kCjPelvis);
    const Eigen::Vector3d seat = NearestOnPart(*context_.scene, g.object, g.seat, x);
    ClearGoals(i);
    SetGoal(i, sim::kCjPelvis, seat);
    const double d = (seat - x).norm();
    error_[i] = d;
    const Eigen::Vector2d anchor = g.ToWorld(g.seat_local.center()).head<2>();
    const double r = ContactReward(anchor, root, vel, facing, config_.target_speed, d * d);
    sit_hold_[i] = d < config_.object.contact_success_threshold ? sit_hold_[i] + 1 : 0;
    if (sit_hold_[i] >= config_.success_hold_steps) StartGetUp(i, b);
    return Finish(view, r, false);
  }
  double sq = 0, mx = 0;
  SetGetUpGoals(i, b, &sq, &mx);
  double r = 0;
  if (phase_[i] == kFeetPhase) {
    r = 0.5 * ContactReward(stand_[i], root, vel, facing, config_.target_speed, sq);
    if (mx < config_.object.contact_success_threshold) {
      phase_[i] = kRisePhase;
      SetGetUpGoals(i, b, &sq, &mx);
    }
  } else {
    const double up_z = (b.rot[sim::kPelvis] * Eigen::Vector3d::UnitZ()).z();
    r = 0.5 +
        0.5 * RiseReward(b.pos[sim::kPelvis].z(), up_z, stand_[i], b.pos[sim::kPelvis].head<2>());
  }
  error_[i] = std::max(kStandingPelvisHeight - b.pos[sim::kPelvis].z(), 0.0);
  return Finish(view, r, Standing(b));
}

void GetUpSkill::SaveTaskState(int i, std::vector<double>* out) const {
  out->insert(out->end(), {static_cast<double>(phase_[i]), static_cast<double>(sit_hold_[i]),
                           static_cast<double>(fall_start_[i]), stand_[i].x(), stand_[i].y()});
}

void GetUpSkill::LoadTaskState(int i, StateReader* r) {
  phase_[i] = static_cast<int>(r->Int("phase", kSitPhase, kRisePhase));
  sit_hold_[i] = static_cast<int>(r->Int("sit_hold", 0, std::numeric_limits<int>::max()));
  fall_start_[i] = r->Flag("fall_start");
  stand_[i].x() = r->Real("stand");
  stand_[i].y() = r->Real("stand");
}

SkillInfo GetUpSkillInfo() {
  SkillInfo info = BuiltinSkillInfo("getup");
  info.params = ConfigToJson(ObjectParams{});
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    std::vector<std::string> cats = SeatCategories();
    cats.push_back("bed");
    return BuildTrainingGround(c, rng, cats);
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<GetUpSkill>(c, ctx, false);
  };
  return info;
}

SkillInfo SitGetUpSkillInfo() {
  SkillInfo info = BuiltinSkillInfo("sit_getup");
  info.params = ConfigToJson(ObjectParams{});
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    return BuildTrainingGround(c, rng, SeatCategories());
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<GetUpSkill>(c, ctx, true);
  };
  return info;
}

}  // namespace sims::task
