// Shared machinery of the skills that interact with furniture (sit, lie, reach, get-up,
// unified). All environments share one MuJoCo model, so an object skill trains in a "training
// ground": `num_objects` procedural pieces of the skill's categories (random dimensions, or
// disjoint held-out ranges for evaluation) placed far apart on a grid with random yaw. At each
// reset an env picks one object and the character starts either from a motion clip placed
// consistently with that object (the clip's stored seat/bed/target parameters), at a time
// before the clip reaches the task's contact, or standing at a random heading and distance
// around it (a per-env curriculum can widen that distance as the env succeeds). Other envs may
// use the same object at the same time: every env has its own mjData.
//
// As InterScene and TokenHSI do, each episode has a fixed world target (the pelvis point on a
// seat, the hand point on a shelf) and a far anchor (a stand point in front of the object) that
// the approach reward leads to; skills that observe the object add a 29-value "task" segment in
// the pelvis heading frame: target − pelvis (3), the object's 8 box corners − pelvis (24) and
// the object's facing (+x) direction (2).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sims/scene/mesh.h"
#include "sims/task/contact_reward.h"
#include "sims/task/skill.h"

namespace sims::task {

struct HandoffState;

/// Spacing of the training-ground grid (m): far enough that envs never see a neighbour.
inline constexpr double kTrainingGroundSpacing = 12.0;
/// Seat/bed heights of a clip and an object may differ this much for reference init (m).
inline constexpr double kMaxClipHeightMismatch = 0.05;
/// Width of the object observation (target 3, box corners 24, facing 2).
inline constexpr int kObjectObsDim = 29;
/// Gap between an object's footprint and a stand point in front of it (m).
inline constexpr double kStandDistance = 0.45;
/// A clip is "in contact" once its success distance is below this multiple of the success
/// threshold; reference starts stay before that.
inline constexpr double kPreContactMargin = 1.5;
/// Clips with less than this much motion before contact (s) start no episodes (idle clips).
inline constexpr double kMinPreContactTime = 0.3;

/// Builds a training ground: `config.object.num_objects` (≥ 1) pieces cycling through
/// `config.object.object_categories` (or `default_categories` when empty) with random dimensions
/// (held-out ranges when config.object.held_out_objects), on a grid with kTrainingGroundSpacing.
scene::Scene BuildTrainingGround(const SkillConfig& config, Rng& rng,
                                 const std::vector<std::string>& default_categories);

/// What an object skill knows about one scene object (all in the object frame unless noted).
/// The part a seat clip puts the pelvis on and the one a bed clip lies on (scene/builtin.h).
inline constexpr std::string_view kSeatPart = "seat surface";
inline constexpr std::string_view kMattressPart = "mattress";

/// One part of an object, in the object frame.
struct ObjectPart {
  int index = -1;     ///< Index in scene::Object::parts.
  std::string name;   ///< Its name (scene/builtin.h lists the built-in furniture's parts).
  scene::Aabb local;  ///< Bounds in the object frame.
};

struct ObjectGeometry {
  int object = -1;                                         ///< Scene object index.
  std::string category;                                    ///< Scene category (chair, stool, ...).
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();  ///< Pose (yaw-only for furniture).
  double yaw = 0;                                          ///< Heading of the object's +x.
  scene::Aabb local;                                       ///< Bounds in the object frame.
  Eigen::Vector2d center = Eigen::Vector2d::Zero();        ///< World xy of the footprint centre.
  double radius = 0;                          ///< Footprint bounding-circle radius (m).
  std::vector<ObjectPart> parts;              ///< Every part, in the object's order.
  std::vector<Eigen::Vector3d> stand_points;  ///< Free floor points around it (z = 0), front first.

  /// The first part named `name` ("seat surface", "mattress", ...), or nullptr: a skill names
  /// the parts it binds to, so a new kind of part needs no change here.
  const ObjectPart* part(std::string_view name) const;
  /// Index (into the object's parts) of the first part named `name`, or −1.
  int part_index(std::string_view name) const;
  /// Indices of every part named `name` (a bed's pillows).
  std::vector<int> part_indices(std::string_view name) const;
  /// Object-frame bounds of the first part named `name`; the part must exist (aborts).
  const scene::Aabb& part_local(std::string_view name) const;

  /// Object-frame point → world.
  Eigen::Vector3d ToWorld(const Eigen::Vector3d& p_O) const { return X_WO * p_O; }
};

/// Computes the geometry summary of scene object `index` (stand points from the height grid).
ObjectGeometry DescribeObject(const scene::Scene& scene, int index,
                              const scene::SceneHeightGrid& grid);

/// A rigid yaw + translation (+ height shift) taking clip coordinates to the world.
struct ClipPlacement {
  double yaw = 0;                                    ///< Rotation about +z (rad).
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  ///< Translation (xy).
  double dz = 0;                                     ///< Height shift (m).

  /// The placement taking a frame at (p_clip, yaw_clip) in the clip onto (p_world, yaw_world).
  static ClipPlacement Align(const Eigen::Vector2d& p_world, double yaw_world,
                             const Eigen::Vector2d& p_clip, double yaw_clip, double dz = 0);
  /// Applies the placement to a pose (position, rotation and velocities).
  humanoid::HumanoidPose Apply(const humanoid::HumanoidPose& pose) const;
  /// Applies it to a clip-frame point.
  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const;
};

/// A per-env curriculum level after an episode: + `step` when it succeeded (`done`), − half a
/// step when it did not, within [0, 1], so the level settles where a third of episodes succeed.
double NextCurriculumLevel(double level, bool done, double step);

/// Highest pelvis origin above a seat or mattress top while seated or lying on it (m).
inline constexpr double kPelvisOnFurniture = 0.15;

/// How far the pelvis at height `pelvis_z` is down on the furniture in `clip`: 1 within
/// kPelvisOnFurniture of the clip's furniture top (meta param furniture_height; without one, at
/// the clip's lowest pelvis height), 0 at its highest (standing), linear in between; 1 for a
/// clip whose pelvis height does not change. Reference starts scale the furniture height shift
/// (ClipPlacement::dz) by it.
double FurnitureShare(const motion::MotionClip& clip, double pelvis_z);

/// The object frame of a seat or bed clip (meta params furniture_*; see motion/synthetic.h:
/// the character starts at the origin facing +x, the furniture lies at x < front_x) expressed
/// in clip coordinates, for an object with geometry `g`. Returns false when the clip carries no
/// furniture parameters or the object lacks the part the clip needs (seat or mattress; a lie
/// clip for a sofa, not a bed, needs the seat and lies along it, and fits only a non-zero
/// `lateral_offset` of its head's side). `dz` receives object top − clip furniture height.
bool ClipFurnitureFrame(const motion::MotionClip& clip, const ObjectGeometry& g,
                        double lateral_offset, Eigen::Vector2d* p_clip, double* yaw_clip,
                        double* dz);

/// The per-env data of an object skill (snapshotted in this order).
struct ObjectState {
  int object = 0;    ///< Index into objects() of the env's object.
  int hold = 0;      ///< Steps the success condition has held.
  double error = 0;  ///< Contact error at the last step (m; goal_error()).
  Eigen::Vector3d target_W = Eigen::Vector3d::Zero();  ///< The episode's fixed target (world).
  Eigen::Vector2d anchor_W = Eigen::Vector2d::Zero();  ///< Its far anchor (world xy).
  double level = 1;                                    ///< Spawn-curriculum level in [0, 1].
  bool started = false;                                ///< An episode ran.
  bool reference = false;                              ///< It began from a clip state.
  bool handoff = false;  ///< It began from a hand-off state (ObjectParams::handoff_states).

  /// Lists the fields; `num_objects` bounds `object`.
  void Serialize(StateArchive* a, int num_objects);
};

/// Base class of the object skills (see the file comment).
class ObjectSkill : public Skill {
 public:
  /// Collects the scene objects the skill accepts; throws sims::Error when there are none.
  ObjectSkill(const SkillConfig& config, const SkillContext& context);

  void SampleInitialState(int env_id, Rng& rng, sim::InitialState* init) override;
  int task_obs_dim() const override { return observes_object() ? kObjectObsDim : 0; }
  void ObserveTask(const sim::EnvView& view, float* out) const override;
  /// Pursues scene object target.object (or, without one, the accepted object nearest the
  /// pelvis) from the current state: selects it, draws the task deterministically and sets
  /// the goals as a reset would, without moving the character.
  bool BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) override;
  /// Bodies that may touch furniture: UniHSI's feet, hands, pelvis, thighs and head, plus the
  /// torso (back rests, mattresses).
  uint32_t contact_body_mask() const override;

  /// Geometry of the objects this skill uses (indices into the scene's objects in `object`).
  const std::vector<ObjectGeometry>& objects() const { return objects_; }
  /// Index into objects() of env i's current object.
  int object(int env_id) const { return env_[env_id].object; }
  /// Geometry of env i's current object.
  const ObjectGeometry& geometry(int env_id) const { return objects_[env_[env_id].object]; }
  /// Makes env i use objects()[k] at its following resets (−1 = random again); FSM / eval.
  void SetObjectOverride(int env_id, int k);
  /// Contact error at the last step (m): the distance of the joint success requires, or the
  /// mean over them (lie: pelvis and head; UniHSI's per-pair mean; success needs each one).
  double goal_error(int env_id) const { return env_[env_id].error; }
  /// goal_error(view.env_id).
  double goal_error(const sim::EnvView& view) const override { return env_[view.env_id].error; }
  /// Consecutive steps the success condition has held.
  int hold(int env_id) const { return env_[env_id].hold; }
  /// Env i's fixed episode target (world): where the pelvis or hand should end.
  const Eigen::Vector3d& target(int env_id) const { return env_[env_id].target_W; }
  /// Env i's far anchor (world xy): the stand point the approach reward leads to.
  const Eigen::Vector2d& anchor(int env_id) const { return env_[env_id].anchor_W; }
  /// Env i's spawn-curriculum level in [0, 1] (1 = the full spawn distance range).
  double spawn_level(int env_id) const { return env_[env_id].level; }
  /// Sets env i's spawn level (tests, tools).
  void SetSpawnLevel(int env_id, double level);
  /// The spawn level when the spawn curriculum runs, else NaN.
  double curriculum_level(int env_id) const override;
  /// Whether env i's episode began from a reference (clip) state.
  bool reference_start(int env_id) const { return env_[env_id].reference; }
  /// Whether env i's episode began from a hand-off state (neither a clip nor a default start).
  bool handoff_start(int env_id) const { return env_[env_id].handoff; }
  /// "handoff" for an episode begun from a hand-off state, else "" (skills with labels of
  /// their own override it).
  std::string start_label(int env_id) const override;
  /// The hand-off states (handoff_states; loaded only when handoff_share > 0).
  const std::vector<HandoffState>& handoff_states() const;
  /// Latest start time (s) of reference starts from library clip `clip` (−1: not used).
  double pre_contact_time(int clip) const;
  /// Net contact force on the humanoid (N) after the last physics step of `view`.
  static double ContactForce(const sim::EnvView& view);
  /// The part of object g the skill rests the character on (a seat, a mattress; "" = none):
  /// what an end state of this skill is kept relative to (handoff.h).
  virtual std::string support_part(const ObjectGeometry& /*g*/) const { return ""; }

 protected:
  /// Whether scene object `g` suits the skill.
  virtual bool Accepts(const ObjectGeometry& g) const = 0;
  /// Whether the policy observes the object (the "task" segment).
  virtual bool observes_object() const { return false; }
  /// First time (s) at which clip `clip` (in its own frame) meets the task's contact, for the
  /// pre-contact reference window; default: never (the whole clip).
  virtual double ClipContactTime(int clip) const;
  /// Measures ClipContactTime for the reference clips and keeps those with at least
  /// kMinPreContactTime before contact; derived constructors call it once their clips are set.
  void PrepareReferenceClips();
  /// Fixes env i's episode target and far anchor (world).
  void SetEpisodeTarget(int env_id, const Eigen::Vector3d& target_W,
                        const Eigen::Vector2d& anchor_W);
  /// A reference time of clip `clip` before its contact (and within the max fraction).
  double PreContactTime(int clip, Rng& rng) const;
  /// Fills objects() with the accepted scene objects (of config.object.object_categories when set);
  /// derived constructors call it last. Throws sims::Error naming the scene when none fits.
  void CollectObjects(const std::string& what);
  /// Index in objects() of scene object `scene_object`, or −1 when the skill does not use it.
  int SlotOf(int scene_object) const;
  /// Draws the episode's task on the env's object (runs before the initial state).
  virtual void SampleTask(int env_id, Rng& rng);
  /// Reference-state init consistent with the env's object; false = no suitable clip.
  virtual bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init);
  /// A hand-off state placed on the env's object (a few draws; false when none fits it).
  virtual bool HandoffInit(int env_id, Rng& rng, sim::InitialState* init);
  /// Standing at a random heading, spawn_min..spawn_max beyond the object's footprint.
  virtual void DefaultInit(int env_id, Rng& rng, sim::InitialState* init);
  /// Writes or reads the derived skill's own per-env state (after the ObjectState).
  virtual void SerializeTaskState(int env_id, StateArchive* archive);

  void SerializeSkillState(int env_id, StateArchive* archive) final;

  /// A free floor point beyond object g's footprint, within the spawn arc and env i's
  /// curriculum range of spawn distances.
  Eigen::Vector2d SpawnPoint(int env_id, const ObjectGeometry& g, Rng& rng) const;
  /// True when the floor disk of `radius` around p is free (height grid).
  bool FreeFloor(const Eigen::Vector2d& p, double radius) const;
  /// True when something other than object g stands within 0.15 m of p (height grid).
  bool BlockedByClutter(const ObjectGeometry& g, const Eigen::Vector2d& p_W) const;
  /// Fills `init` from clip `clip` at time t placed by `placement` (pose + AMP history).
  void PlaceReference(int env_id, int clip, double t, const ClipPlacement& placement,
                      sim::InitialState* init);
  /// Seat/bed clips of `skills` whose furniture fits object g, for reference init: returns
  /// a clip index (−1 if none) and its placement (`lateral` m along a wide seat). The object may
  /// be up to kMaxClipHeightMismatch lower and up to `max_raise` higher than the clip's; clips
  /// made for the object's category are preferred when one fits.
  int ChooseFurnitureClip(const std::vector<int>& clips, const ObjectGeometry& g, double lateral,
                          Rng& rng, ClipPlacement* placement,
                          double max_raise = kMaxClipHeightMismatch) const;
  /// Reference init from `reference_clips_` placed on env i's furniture (sit, lie) at
  /// `lateral` m along the seat.
  bool FurnitureClipInit(int env_id, double lateral, Rng& rng, sim::InitialState* init);
  /// Contact reward towards the env's far anchor (r_far = 1 at the anchor or the target) with
  /// Σ‖g_j − x_j‖² = goal_sum, a `wide_share` (plus the config's) of the wide near kernel and
  /// the config's precise share (NearReward), and success when the measured distance d is
  /// within the threshold. The caller keeps the env's contact error (goal_error()).
  sim::TaskStepResult ContactRewardStep(const sim::EnvView& view, double goal_sum, double d,
                                        double wide_share = 0.0);
  /// Ends a step: success counter, success-held truncation, excessive-force termination.
  sim::TaskStepResult Finish(const sim::EnvView& view, double reward, bool success);

  std::vector<ObjectGeometry> objects_;
  std::vector<ObjectState> env_;     // per env
  std::vector<int> override_;        // per env: SetObjectOverride (a setting, not snapshotted)
  std::vector<double> pre_contact_;  // per library clip (−1: not a reference clip)
  std::shared_ptr<const std::vector<HandoffState>> handoff_;  // shared by instances (cache)
};

/// A random position (m) along a wide seat (sofas) so envs do not all use the middle; 0 for
/// seats with room for one and objects without a seat.
double SeatLateral(const ObjectGeometry& g, Rng& rng);

/// Heading direction (unit, xy) of a pose.
Eigen::Vector2d FacingOf(const humanoid::HumanoidPose& pose);

/// The part's surface point nearest to p (exact, over its triangles).
Eigen::Vector3d NearestOnPart(const scene::Scene& scene, int object, int part,
                              const Eigen::Vector3d& p);

}  // namespace sims::task
