#include "sims/task/skill.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"
#include "sims/humanoid/features.h"
#include "sims/sim/scene_physics.h"
#include "sims/task/getup/getup.h"
#include "sims/task/lie/lie.h"
#include "sims/task/reach/reach.h"
#include "sims/task/sit/sit.h"
#include "sims/task/unified/unified.h"
#include "sims/task/walk/walk.h"

namespace sims::task {

void SkillConfig::Validate() const {
  Require(reference_init_prob >= 0 && reference_init_prob <= 1, "reference_init_prob",
          "a probability in [0, 1]");
  Require(reference_init_max_fraction > 0 && reference_init_max_fraction <= 1,
          "reference_init_max_fraction", "a fraction in (0, 1]");
  Require(target_speed >= 0, "target_speed", "a non-negative speed (m/s)");
  Require(success_hold_steps >= 1, "success_hold_steps", "at least 1 step");
  walk.Validate();
  object.Validate();
  getup.Validate();
  if (params.empty()) return;
  const SkillInfo* info = nullptr;
  for (const auto& s : GetSkills())
    if (s.name() == skill) info = &s;
  for (auto it = params.begin(); it != params.end(); ++it) {
    if (info && info->params.contains(it.key())) continue;
    std::set<std::string> keys;
    const nlohmann::json named = ConfigToJson(SkillConfig{});  // items() does not own it
    for (const auto& [key, value] : named.items()) keys.insert(key);
    if (info)
      for (const auto& [key, value] : info->params.items()) keys.insert(key);
    std::string known;
    for (const auto& key : keys) known += (known.empty() ? "" : ", ") + key;
    throw FieldError(it.key(), "a known field (one of: " + known + ")", "an unknown field");
  }
  if (info->check_params) info->check_params(params);
}

void ResolveSkillParams(SkillConfig* config) {
  const nlohmann::json named = ConfigToJson(SkillConfig{});
  for (const auto& s : GetSkills()) {
    if (s.name() != config->skill) continue;
    for (auto it = s.params.begin(); it != s.params.end(); ++it)
      if (!named.contains(it.key()) && !config->params.contains(it.key()))
        config->params[it.key()] = it.value();
  }
}

Skill::Skill(const SkillConfig& config, const SkillContext& context)
    : config_(config), context_(context) {
  SIMS_CHECK(context_.humanoid && context_.height_grid && context_.num_envs > 0);
  heightmap_ = std::make_unique<scene::HeightmapSampler>(context_.height_grid, config_.heightmap);
  state_.resize(context_.num_envs);
  if (context_.motions)
    for (int c = 0; c < context_.motions->num_clips(); ++c) reference_clips_.push_back(c);
}

Skill::~Skill() = default;

int Skill::obs_dim() const {
  return kContactGoalDim + task_obs_dim() + heightmap_->size() + kStyleDim;
}

std::vector<sim::ObsSegment> Skill::obs_segments() const {
  using Kind = sim::ObsSegment::Kind;
  std::vector<sim::ObsSegment> out = {{"contact_goal", Kind::kVector, 0, kContactGoalDim, 0, 0}};
  int at = kContactGoalDim;
  if (task_obs_dim() > 0) {
    out.push_back({"task", Kind::kVector, at, task_obs_dim(), 0, 0});
    at += task_obs_dim();
  }
  out.push_back({"heightmap", Kind::kHeightmap, at, heightmap_->size(), config_.heightmap.size_y,
                 config_.heightmap.size_x});
  at += heightmap_->size();
  out.push_back({"z", Kind::kStyle, at, kStyleDim, 0, 0});
  return out;
}

void Skill::ObserveTask(const sim::EnvView&, float*) const {}

void Skill::SetGoal(int env_id, int joint, const Eigen::Vector3d& target) {
  state_[env_id].goals[joint] = target;
  state_[env_id].mask |= 1u << joint;
}

void Skill::ClearGoals(int env_id) { state_[env_id].mask = 0; }

uint32_t OffFloorContacts(const humanoid::Humanoid& h, const mjData* d) {
  uint32_t mask = 0;
  for (int c = 0; c < d->ncon; ++c) {
    const int b1 = h.geom_body(d->contact[c].geom1);
    const int b2 = h.geom_body(d->contact[c].geom2);
    if ((b1 >= 0) == (b2 >= 0)) continue;  // self-contact or scene-scene
    const int b = b1 >= 0 ? b1 : b2;
    const bool foot = b == humanoid::kLeftFoot || b == humanoid::kRightFoot;
    if (!foot || d->contact[c].pos[2] > kFloorContactHeight) mask |= 1u << b;
  }
  return mask;
}

bool OnlyFeetOnTheFloor(const sim::EnvView& view) {
  return OffFloorContacts(*view.humanoid, view.data) == 0;
}

void Skill::SetStyle(int env_id, int style) { state_[env_id].style = style; }

void Skill::SetStyleVector(int env_id, const Eigen::VectorXf& z) {
  SIMS_CHECK(z.size() == 0 || z.size() == kStyleDim);
  state_[env_id].style_vector = z;
}

bool Skill::BeginInstruction(const sim::EnvView&, const InstructionTarget&) { return false; }

double Skill::goal_error(const sim::EnvView&) const { return 0.0; }

int DrawStyleClip(const motion::MotionLibrary& lib, const std::vector<int>& clips,
                  bool balance_emotions, Rng& rng) {
  if (clips.empty()) return -1;
  if (!balance_emotions) return clips[rng.UniformInt(static_cast<int64_t>(clips.size()))];
  std::vector<std::string> emotions;
  for (int c : clips) emotions.push_back(lib.clip(c).meta().emotion);
  std::sort(emotions.begin(), emotions.end());
  emotions.erase(std::unique(emotions.begin(), emotions.end()), emotions.end());
  const std::string& e = emotions[rng.UniformInt(static_cast<int64_t>(emotions.size()))];
  std::vector<int> of_e;
  for (int c : clips)
    if (lib.clip(c).meta().emotion == e) of_e.push_back(c);
  return of_e[rng.UniformInt(static_cast<int64_t>(of_e.size()))];
}

int Skill::DrawReferenceStyle(Rng& rng) const {
  if (!context_.motions) return -1;
  return DrawStyleClip(*context_.motions, ReferenceClips(), config_.balance_emotions, rng);
}

void Skill::SampleInitialState(int env_id, Rng& rng, sim::InitialState* init) {
  const auto& clips = ReferenceClips();
  const auto* lib = context_.motions.get();
  if (lib && !clips.empty() && rng.Bernoulli(config_.reference_init_prob)) {
    // Reference-state init: a clip of this skill at a random time, placed where the env's
    // default put the character (position and heading), with its AMP history.
    const int clip = DrawReferenceStyle(rng);
    const double t = lib->SampleTime(clip, rng, config_.reference_init_max_fraction);
    motion::ReferenceState ref = lib->StateAt(clip, t);
    const double yaw =
        humanoid::HeadingAngle(init->pose.root_rot) - humanoid::HeadingAngle(ref.pose.root_rot);
    const Eigen::Quaterniond dq(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    const Eigen::Vector3d anchor(ref.pose.root_pos.x(), ref.pose.root_pos.y(), 0);
    const Eigen::Vector3d place(init->pose.root_pos.x(), init->pose.root_pos.y(), 0);
    auto move = [&](humanoid::HumanoidPose p) {
      p.root_pos = place + dq * (p.root_pos - anchor);
      p.root_rot = dq * p.root_rot;
      p.root_lin_vel = dq * p.root_lin_vel;
      p.root_ang_vel = dq * p.root_ang_vel;
      return p;
    };
    init->pose = move(ref.pose);
    init->history.clear();
    for (const auto& h : ref.history) init->history.push_back(move(h));
    init->reference = true;
    state_[env_id].style = clip;
  } else if (lib && !clips.empty()) {
    // Default init still pursues some clip's style (SIMS conditions every episode on a z).
    state_[env_id].style = DrawReferenceStyle(rng);
  } else {
    state_[env_id].style = -1;
  }
}

void Skill::Observe(const sim::EnvView& view, float* out) const {
  const int i = view.env_id;
  const humanoid::BodyStates& b = *view.bodies;
  const Eigen::Quaterniond h_inv = humanoid::HeadingInverse(b.rot[humanoid::kPelvis]);
  float* o = out;
  for (int j = 0; j < humanoid::kNumContactJoints; ++j, o += 4) {
    if (state_[i].mask & (1u << j)) {
      const Eigen::Vector3d d = h_inv * (state_[i].goals[j] - humanoid::ContactJointPosition(b, j));
      o[0] = static_cast<float>(d.x());
      o[1] = static_cast<float>(d.y());
      o[2] = static_cast<float>(d.z());
      o[3] = 1.0f;
    } else {
      o[0] = o[1] = o[2] = o[3] = 0.0f;
    }
  }
  ObserveTask(view, o);
  o += task_obs_dim();
  heightmap_->SampleOne(b.pos[humanoid::kPelvis], humanoid::HeadingAngle(b.rot[humanoid::kPelvis]),
                        o);
  o += heightmap_->size();
  const Eigen::VectorXf* z = nullptr;
  if (config_.style_conditioned) {
    const SkillState& st = state_[i];
    if (st.style_vector.size() == kStyleDim)
      z = &st.style_vector;
    else if (context_.styles && st.style >= 0 && st.style < context_.styles->size())
      z = &context_.styles->z(st.style);
  }
  for (int k = 0; k < kStyleDim; ++k) o[k] = z ? (*z)[k] : 0.0f;
}

std::vector<double> Skill::SaveEnvState(int env_id) const {
  std::vector<double> out;
  StateArchive a(&out);
  // Writing only reads the fields: one non-const Serialize serves both directions.
  auto* self = const_cast<Skill*>(this);
  self->state_[env_id].Serialize(&a, context_.motions ? context_.motions->num_clips() : 0);
  self->SerializeSkillState(env_id, &a);
  return out;
}

void Skill::LoadEnvState(int env_id, const std::vector<double>& s) {
  StateReader r(name() + " skill state", s.data(), s.size());
  StateArchive a(&r);
  SkillState st = state_[env_id];
  st.Serialize(&a, context_.motions ? context_.motions->num_clips() : 0);
  // The derived state may depend on the base (walk: the style clip's posture), so the base is
  // in place first; a throw later leaves a half-read env, which BatchedEnv::LoadState undoes.
  state_[env_id] = st;
  SerializeSkillState(env_id, &a);
  r.ExpectEnd();
}

void Skill::SerializeSkillState(int, StateArchive*) {}

namespace {

// The built-in skills, one line each (skill_test checks that every built-in vocabulary entry
// has one).
std::deque<SkillInfo>& Registry() {
  static std::deque<SkillInfo> skills = {
      WalkSkillInfo(),  SitSkillInfo(),   LieSkillInfo(),
      ReachSkillInfo(), GetUpSkillInfo(), UnifiedSkillInfo(),
  };
  return skills;
}

}  // namespace

const std::deque<SkillInfo>& GetSkills() { return Registry(); }

const SkillInfo& FindSkill(const std::string& name) {
  std::string known;
  for (const auto& s : GetSkills()) {
    if (s.name() == name) return s;
    known += (known.empty() ? "" : ", ") + s.name();
  }
  ThrowInputError("skill", "skill", "one of: " + known, "'" + name + "'");
}

const SkillInfo& RegisterSkill(SkillInfo info) {
  auto& registry = Registry();
  if (!info.create || !info.build_scene)
    ThrowInputError("skill registry", info.name(), "a skill with create and build_scene",
                    "a missing function");
  RegisterSkillTraits(info.traits);  // throws when the name is taken
  registry.push_back(std::move(info));
  return registry.back();
}

SkillInfo BuiltinSkillInfo(const std::string& name) {
  SkillInfo info;
  info.traits = SkillTraitsOf(name);
  return info;
}

SkillSetup CreateSkill(const SkillConfig& config, int num_envs, uint64_t seed,
                       std::shared_ptr<const scene::Scene> scene_override,
                       const sim::EnvConfig* env) {
  ValidateConfig(config, "skill config");
  const SkillInfo& info = FindSkill(config.skill);
  SkillSetup setup;
  SkillContext& ctx = setup.context;
  ctx.num_envs = num_envs;
  Rng scene_rng(seed ^ 0x5EED5CE4Eull);
  ctx.scene = scene_override
                  ? scene_override
                  : std::make_shared<const scene::Scene>(info.build_scene(config, scene_rng));
  ctx.humanoid = std::make_shared<const humanoid::Humanoid>(
      humanoid::BuildModel(sim::CompileSceneGeometry(*ctx.scene)));
  ctx.ray_caster = std::make_shared<const scene::RayCaster>(*ctx.scene);
  ctx.height_grid = std::make_shared<const scene::SceneHeightGrid>(*ctx.scene, *ctx.ray_caster,
                                                                   scene::HeightGridConfig{});
  if (!config.motion.manifest.empty()) {
    std::filesystem::path manifest = config.motion.manifest;
    if (manifest.is_relative() && !std::filesystem::exists(manifest))
      manifest = ProjectRoot() / manifest;
    motion::MotionLibraryOptions opt;
    opt.mirror = config.motion.mirror;
    opt.skills = config.motion.skills;
    opt.emotions = config.motion.emotions;
    const sim::EnvConfig env_config = env ? *env : sim::EnvConfig{};
    opt.control_dt = ctx.humanoid->model()->opt.timestep * env_config.substeps;
    opt.amp_steps = env_config.amp_history;
    opt.root_height_obs = env_config.root_height_obs;
    opt.local_root_obs = env_config.local_root_obs;
    ctx.motions = std::make_shared<const motion::MotionLibrary>(
        motion::MotionLibrary::Load(manifest, ctx.humanoid, opt));
    ctx.styles = std::make_shared<const StyleTable>(StyleTable::FromClipNames(*ctx.motions));
    spdlog::info("skill {}: {} clips ({:.1f} s) from {}", config.skill, ctx.motions->num_clips(),
                 ctx.motions->total_duration(), manifest.string());
  }
  setup.skill = info.create(config, ctx);
  return setup;
}

}  // namespace sims::task
