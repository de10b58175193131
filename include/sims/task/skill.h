// Skills are environment task hooks with a shared observation layout, so any skill's policy
// reads the same kinds of inputs:
//   [contact goal: 15 joints × (heading-local target − joint position, valid mask) = 60]
//   [the skill's own task values, task_obs_dim() (object skills: target, box corners, facing)]
//   [egocentric heightmap: H·W heights relative to the root]
//   [style embedding z: 64, zero when the skill is not text-conditioned]
// A skill fills per-env goals; the base class turns them into observations, handles the
// hybrid reference-state initialisation from the motion library, style ids for conditional
// AMP and bit-exact state snapshots. Walk (walk/walk.h) is the fully commented reference skill;
// a skill is one folder (src/task/<skill>/, include/sims/task/<skill>/) plus one registry line.
#pragma once

#include <array>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/core/config.h"
#include "sims/core/skill_vocabulary.h"
#include "sims/motion/motion_library.h"
#include "sims/scene/height_grid.h"
#include "sims/scene/ray_caster.h"
#include "sims/scene/scene.h"
#include "sims/sim/env.h"
#include "sims/task/getup/getup_params.h"
#include "sims/task/object_params.h"
#include "sims/task/sit/sit_params.h"
#include "sims/task/skill_state.h"
#include "sims/task/styles.h"
#include "sims/task/walk/walk_params.h"

namespace sims::task {

inline constexpr int kContactGoalDim = humanoid::kNumContactJoints * 4;  ///< 60.

/// Which clips feed reference-state init and the AMP demo buffer.
struct MotionDataConfig {
  std::string manifest;               ///< Manifest path (relative to the project root ok).
  std::vector<std::string> skills;    ///< Clip skill labels to keep (empty = all).
  std::vector<std::string> emotions;  ///< Clip emotions to keep (empty = all).
  bool mirror = true;                 ///< Add left–right mirrored clips.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(manifest));
    a->Visit(SIMS_NVP(skills));
    a->Visit(SIMS_NVP(emotions));
    a->Visit(SIMS_NVP(mirror));
  }
};

/// A skill's training and task settings: the fields every skill reads, the built-in skills'
/// params structs (declared beside each skill), then a registered skill's params (`params`,
/// see DeclareParams). JSON keys are flat, as policy files store them.
struct SkillConfig {
  std::string skill = "walk";        ///< Registry name.
  MotionDataConfig motion;           ///< Demonstrations.
  scene::HeightmapConfig heightmap;  ///< Egocentric heightmap layout (16×16, 0.1 m).
  bool style_conditioned = false;    ///< Put the clip's z in the observation.
  std::string style_model;  ///< Motion–text model dir: text-aligned z per clip ("" = name codes).
  /// Draw an episode's style emotion first (uniform over the emotions of the skill's clips),
  /// then a clip of it, instead of a clip uniformly: the synthetic walk clips are 32 neutral
  /// and 2 of each other emotion (plus mirrors), so a uniform draw gives each emotion 4 % of
  /// the episodes (DrawStyleClip). The AMP demonstrations are balanced the same way, so a
  /// conditional discriminator sees each emotion's demos as often as its episodes.
  bool balance_emotions = false;
  double reference_init_prob = 0.5;          ///< Hybrid init: P(reference state).
  double reference_init_max_fraction = 1.0;  ///< Reference times in [0, f·duration].
  double target_speed = 1.0;                 ///< v* towards the goal (m/s).
  int success_hold_steps = 15;               ///< Steps success must hold before switching.
  WalkParams walk;                           ///< Walk (walk/walk_params.h).
  ObjectParams object;                       ///< Object skills (object_params.h).
  SitParams sit;                             ///< Sit (sit/sit_params.h).
  GetUpParams getup;                         ///< Get-up (getup/getup_params.h).
  /// The keys of a registered skill's own params (every key the members above do not name),
  /// flat beside the others and checked against the skill's SkillInfo on load; the skill
  /// reads them with SkillParams<P>(). A new skill needs no member here.
  nlohmann::json params = nlohmann::json::object();

  /// Lists the fields for JSON binding (the params structs' keys inline).
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(skill));
    a->Visit(SIMS_NVP(motion));
    a->Visit(SIMS_NVP(heightmap));
    a->Visit(SIMS_NVP(style_conditioned));
    a->Visit(SIMS_NVP(style_model));
    a->Visit(SIMS_NVP(balance_emotions));
    a->Visit(SIMS_NVP(reference_init_prob));
    a->Visit(SIMS_NVP(reference_init_max_fraction));
    a->Visit(SIMS_NVP(target_speed));
    a->Visit(SIMS_NVP(success_hold_steps));
    walk.Serialize(a);
    object.Serialize(a);
    sit.Serialize(a);
    getup.Serialize(a);
    a->VisitRest(&params);  // last: whatever no member named
  }
  /// Checks ranges (the params structs' too) and that every key of `params` is one the
  /// registered skill declares, with a valid value.
  void Validate() const;
};

/// One of `clips` for an episode's style: uniform over the clips, or with `balance_emotions`
/// an emotion uniform over those of `clips` (clip metadata) and then a clip of it. Both draw
/// from `rng` only (the unbalanced draw exactly as clips[rng.UniformInt(size)]); −1 when empty.
int DrawStyleClip(const motion::MotionLibrary& lib, const std::vector<int>& clips,
                  bool balance_emotions, Rng& rng);

/// Everything a skill instance shares with the environment.
struct SkillContext {
  std::shared_ptr<const humanoid::Humanoid> humanoid;         ///< Model incl. the scene.
  std::shared_ptr<const scene::Scene> scene;                  ///< The scene the env simulates.
  std::shared_ptr<const scene::SceneHeightGrid> height_grid;  ///< Precomputed heights.
  std::shared_ptr<const scene::RayCaster> ray_caster;         ///< Direct queries (free space).
  std::shared_ptr<const motion::MotionLibrary> motions;       ///< Demonstrations (may be null).
  std::shared_ptr<const StyleTable> styles;                   ///< z per clip (may be null).
  int num_envs = 1;                                           ///< Per-env state size.
};

struct ContactStep;

/// The per-env data every skill has (the skill object itself is shared by all envs).
struct SkillState {
  /// Contact goals (world frame) of the 15 contact joints; only those in `mask` are active.
  std::array<Eigen::Vector3d, humanoid::kNumContactJoints> goals;
  uint32_t mask = 0;  ///< Bit j: goal j is active.
  int style = -1;     ///< Library clip whose style z the policy sees (−1 = none).
  /// An explicit z (a caption's embedding) overriding `style`; empty = none. Set by the FSM
  /// at every instruction, so it is not part of a snapshot.
  Eigen::VectorXf style_vector;

  SkillState() { goals.fill(Eigen::Vector3d::Zero()); }
  /// Lists the snapshotted fields; `num_clips` bounds `style`.
  void Serialize(StateArchive* a, long long num_clips) {
    for (Eigen::Vector3d& g : goals) a->Reals("goal", &g);
    a->Int("mask", &mask, 0, (1ll << humanoid::kNumContactJoints) - 1);
    a->Int("style", &style, -1, num_clips - 1);
  }
};

/// What a story instruction asks of a skill in the scene the env simulates (FSM).
struct InstructionTarget {
  int object = -1;                                  ///< Scene object index (−1 = none).
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< Walk/stand target or reach point (world).
  bool has_point = false;                           ///< `point` is set.
  int hand = -1;                                    ///< Reach: kCjLeftHand / kCjRightHand.
  std::string height;                               ///< Reach: "low", "medium" or "high".
  std::shared_ptr<const ContactStep> contact_step;  ///< Unified: one chain-of-contacts step.
};

/// Base class of all skills (see the file comment).
class Skill : public sim::TaskHook {
 public:
  /// Allocates per-env state for ctx.num_envs environments.
  Skill(const SkillConfig& config, const SkillContext& context);
  ~Skill() override;

  /// Registry name.
  virtual std::string name() const = 0;

  int obs_dim() const override;
  std::vector<sim::ObsSegment> obs_segments() const override;
  void SampleInitialState(int env_id, Rng& rng, sim::InitialState* init) override;
  void Observe(const sim::EnvView& view, float* out) const override;
  int style_id(int env_id) const override { return state_[env_id].style; }
  std::vector<double> SaveEnvState(int env_id) const override;
  void LoadEnvState(int env_id, const std::vector<double>& state) override;

  /// The goal of contact joint j in env i (world frame) and whether it is active.
  const Eigen::Vector3d& goal(int env_id, int joint) const { return state_[env_id].goals[joint]; }
  /// Bitmask of active contact joints of env i.
  uint32_t goal_mask(int env_id) const { return state_[env_id].mask; }
  /// Sets/clears the goal of contact joint j (world frame).
  void SetGoal(int env_id, int joint, const Eigen::Vector3d& target);
  /// Clears all goals of env i.
  void ClearGoals(int env_id);
  /// Forces the style of env i (FSM: z from a caption); −1 = none.
  void SetStyle(int env_id, int style);
  /// Gives env i an explicit z (e.g. a caption's embedding); empty = back to style ids.
  void SetStyleVector(int env_id, const Eigen::VectorXf& z);
  /// Replaces the style table (text-aligned embeddings from the language module).
  void SetStyleTable(std::shared_ptr<const StyleTable> styles) {
    context_.styles = std::move(styles);
  }
  /// Starts a task mid-episode (the FSM switching skills): sets the goals for `target` from
  /// the character's current state without resetting it. Returns false when the skill cannot
  /// pursue that target (e.g. an object without the part it needs).
  virtual bool BeginInstruction(const sim::EnvView& view, const InstructionTarget& target);
  /// Env view.env_id's contact error (m) for evaluation and story metrics: the distance of the
  /// goal joint success requires (the mean over them where there are several); 0 for a skill
  /// without one.
  virtual double goal_error(const sim::EnvView& view) const;
  /// True when the skill's goal already holds before it acts (get-up: standing clear), so a
  /// story instruction of it ends at once as a success; default false.
  virtual bool Accomplished(const sim::EnvView& /*view*/) const { return false; }
  /// How env `env_id`'s current episode started, for evaluation broken down by start kind
  /// (get-up: "seat", "bed", "floor", "fall"; reach: the target's height band); "" when the
  /// skill has no such kinds.
  virtual std::string start_label(int /*env_id*/) const { return ""; }
  /// Width of the skill's own observation segment "task" after the contact goals (0: none).
  virtual int task_obs_dim() const { return 0; }
  /// Writes task_obs_dim() values for env view.env_id.
  virtual void ObserveTask(const sim::EnvView& view, float* out) const;
  /// The configuration.
  const SkillConfig& config() const { return config_; }
  /// The context.
  const SkillContext& context() const { return context_; }

 protected:
  /// Writes or reads env `env_id`'s own skill state (after the base SkillState in a snapshot).
  /// Reading may throw part way: the caller then restores the whole environment.
  virtual void SerializeSkillState(int env_id, StateArchive* archive);
  /// Clips eligible for reference init of this skill (default: all library clips).
  virtual const std::vector<int>& ReferenceClips() const { return reference_clips_; }
  /// DrawStyleClip over ReferenceClips() with this config's balance (−1 without a library).
  int DrawReferenceStyle(Rng& rng) const;

  SkillConfig config_;
  SkillContext context_;
  std::unique_ptr<scene::HeightmapSampler> heightmap_;
  std::vector<SkillState> state_;  // per env
  std::vector<int> reference_clips_;
};

/// A registered skill: its vocabulary entry (name, verbs, traits) bound to its code.
struct SkillInfo {
  SkillTraits traits;  ///< What other modules know about it (core/skill_vocabulary.h).
  /// Its own config keys with their defaults (the params structs it reads, as JSON).
  nlohmann::json params = nlohmann::json::object();
  /// Checks SkillConfig::params (throws FieldError naming the key); DeclareParams() sets it.
  std::function<void(const nlohmann::json&)> check_params;
  /// Builds the scene the skill trains in (empty floor for walk, procedural objects else).
  std::function<scene::Scene(const SkillConfig&, Rng&)> build_scene;
  /// Creates the skill.
  std::function<std::shared_ptr<Skill>(const SkillConfig&, const SkillContext&)> create;
  /// Turns a trained config into the evaluation one (eval_policy); empty = unchanged.
  std::function<void(SkillConfig*)> configure_eval;

  /// Registry key.
  const std::string& name() const { return traits.name; }
};

/// Declares P (a config struct with Serialize and optionally Validate, keys prefixed with the
/// skill's name) as params of a registered skill: its keys and defaults join info->params, and
/// a config's values for them are type- and range-checked on load. Call once per struct.
template <class P>
void DeclareParams(SkillInfo* info) {
  info->params.update(ConfigToJson(P{}));
  info->check_params = [previous = std::move(info->check_params)](const nlohmann::json& j) {
    if (previous) previous(j);
    P p;
    JsonReadArchive::Read(j, &p, /*allow_unknown=*/true);  // keys of the skill's other structs
  };
}

/// A registered skill's params struct P: the config's `params` over P's defaults. Throws
/// sims::Error naming the skill for a value that was never validated (a config built in code).
template <class P>
P SkillParams(const SkillConfig& config) {
  P p;
  try {
    JsonReadArchive::Read(config.params, &p, /*allow_unknown=*/true);
  } catch (const FieldError& e) {
    ThrowInputError("skill '" + config.skill + "' params", e.field(), e.expected(), e.got());
  }
  return p;
}

/// Adds the defaults of the registered skill's declared params that `config` does not set to
/// config->params, so the config a run writes lists every value it used.
void ResolveSkillParams(SkillConfig* config);

/// The explicit skill registry (mujoco_mpc style GetTasks()): the built-in skills, then the
/// registered ones. References stay valid.
const std::deque<SkillInfo>& GetSkills();
/// Contacts above this height are not on the floor (m): a foot there stands on furniture.
inline constexpr double kFloorContactHeight = 0.05;
/// True when the character touches the scene with nothing but its feet, and those only on the
/// floor (contact points at most kFloorContactHeight high).
bool OnlyFeetOnTheFloor(const sim::EnvView& view);
/// The bodies (bit b = humanoid body b) touching the scene other than a foot on the floor:
/// what keeps OnlyFeetOnTheFloor false (0 when it holds).
uint32_t OffFloorContacts(const humanoid::Humanoid& h, const mjData* d);

/// Registry lookup; throws sims::Error listing the known names.
const SkillInfo& FindSkill(const std::string& name);
/// Adds a skill (tests, plugins) to the registry and its traits to the skill vocabulary; from
/// then on train, eval and the FSM run it by name. Throws when the name is taken. Not
/// thread-safe: register before anything runs.
const SkillInfo& RegisterSkill(SkillInfo info);
/// A SkillInfo holding the vocabulary entry `name`; a built-in skill's folder adds its code.
SkillInfo BuiltinSkillInfo(const std::string& name);

/// A ready-to-run skill: model, scene, grids, motions and the hook.
struct SkillSetup {
  SkillContext context;          ///< Shared pieces.
  std::shared_ptr<Skill> skill;  ///< The task hook.
};

/// Builds the skill's scene, compiles the MuJoCo model, casts the height grid, loads the
/// motion library (if a manifest is set) and creates the skill for `num_envs` environments.
/// `scene` overrides the skill's own training scene when given. `env`, when given, is the
/// environment the skill will run in: the library's AMP features (history spacing, steps, root
/// observations) follow it, so demonstrations and reference-start histories match what the
/// environment computes; without it they follow EnvConfig's defaults.
SkillSetup CreateSkill(const SkillConfig& config, int num_envs, uint64_t seed,
                       std::shared_ptr<const scene::Scene> scene = nullptr,
                       const sim::EnvConfig* env = nullptr);

}  // namespace sims::task
