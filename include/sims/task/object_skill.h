// Shared machinery of the skills that interact with furniture (sit, lie, reach, get-up,
// unified). All environments share one MuJoCo model, so an object skill trains in a "training
// ground": `num_objects` procedural pieces of the skill's categories (random dimensions, or
// disjoint held-out ranges for evaluation) placed far apart on a grid with random yaw. At each
// reset an env picks one object and the character starts either from a motion clip placed
// consistently with that object (the clip's stored seat/bed/target parameters) or standing
// at a random heading and distance around it. Other envs may use the same object at the same
// time: every env has its own mjData.
#pragma once

#include <string>
#include <vector>

#include "sims/scene/mesh.h"
#include "sims/task/contact_reward.h"
#include "sims/task/skill.h"

namespace sims::task {

/// Spacing of the training-ground grid (m): far enough that envs never see a neighbour.
inline constexpr double kTrainingGroundSpacing = 12.0;
/// Seat/bed heights of a clip and an object may differ this much for reference init (m).
inline constexpr double kMaxClipHeightMismatch = 0.05;

/// Builds a training ground: `config.object.num_objects` (≥ 1) pieces cycling through
/// `config.object.object_categories` (or `default_categories` when empty) with random dimensions
/// (held-out ranges when config.object.held_out_objects), on a grid with kTrainingGroundSpacing.
scene::Scene BuildTrainingGround(const SkillConfig& config, Rng& rng,
                                 const std::vector<std::string>& default_categories);

/// What an object skill knows about one scene object (all in the object frame unless noted).
struct ObjectGeometry {
  int object = -1;                                         ///< Scene object index.
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();  ///< Pose (yaw-only for furniture).
  double yaw = 0;                                          ///< Heading of the object's +x.
  scene::Aabb local;                                       ///< Bounds in the object frame.
  Eigen::Vector2d center = Eigen::Vector2d::Zero();        ///< World xy of the footprint centre.
  double radius = 0;                          ///< Footprint bounding-circle radius (m).
  int seat = -1;                              ///< Part index of "seat surface" (or −1).
  int back = -1;                              ///< "back".
  int left_arm = -1;                          ///< "left arm".
  int right_arm = -1;                         ///< "right arm".
  int mattress = -1;                          ///< "mattress".
  std::vector<int> pillows;                   ///< "pillow" parts.
  scene::Aabb seat_local;                     ///< Seat part bounds in the object frame.
  scene::Aabb mattress_local;                 ///< Mattress part bounds in the object frame.
  std::vector<Eigen::Vector3d> stand_points;  ///< Free floor points around it (z = 0), front first.

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
  sim::HumanoidPose Apply(const sim::HumanoidPose& pose) const;
  /// Applies it to a clip-frame point.
  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const;
};

/// The object frame of a seat or bed clip (meta params furniture_*; see motion/synthetic.h:
/// the character starts at the origin facing +x, the furniture lies at x < front_x) expressed
/// in clip coordinates, for an object with geometry `g`. Returns false when the clip carries no
/// furniture parameters or the object lacks the part the clip needs (seat or mattress). `dz`
/// receives object top − clip furniture height.
bool ClipFurnitureFrame(const motion::MotionClip& clip, const ObjectGeometry& g,
                        double lateral_offset, Eigen::Vector2d* p_clip, double* yaw_clip,
                        double* dz);

/// Base class of the object skills (see the file comment).
class ObjectSkill : public Skill {
 public:
  /// Collects the scene objects the skill accepts; throws sims::Error when there are none.
  ObjectSkill(const SkillConfig& config, const SkillContext& context);

  void SampleInitialState(int env_id, Rng& rng, sim::InitialState* init) override;
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
  int object(int env_id) const { return object_[env_id]; }
  /// Geometry of env i's current object.
  const ObjectGeometry& geometry(int env_id) const { return objects_[object_[env_id]]; }
  /// Makes env i use objects()[k] at its following resets (−1 = random again); FSM / eval.
  void SetObjectOverride(int env_id, int k);
  /// The distance the success test compares with its threshold at the last step (m).
  double goal_error(int env_id) const { return error_[env_id]; }
  /// goal_error(view.env_id).
  double goal_error(const sim::EnvView& view) const override { return error_[view.env_id]; }
  /// Consecutive steps the success condition has held.
  int hold(int env_id) const { return hold_[env_id]; }
  /// Net contact force on the humanoid (N) after the last physics step of `view`.
  static double ContactForce(const sim::EnvView& view);

 protected:
  /// Whether scene object `g` suits the skill.
  virtual bool Accepts(const ObjectGeometry& g) const = 0;
  /// Fills objects() with the accepted scene objects (of config.object.object_categories when set);
  /// derived constructors call it last. Throws sims::Error naming the scene when none fits.
  void CollectObjects(const std::string& what);
  /// Index in objects() of scene object `scene_object`, or −1 when the skill does not use it.
  int SlotOf(int scene_object) const;
  /// Draws the episode's task on the env's object (runs before the initial state).
  virtual void SampleTask(int env_id, Rng& rng);
  /// Reference-state init consistent with the env's object; false = no suitable clip.
  virtual bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init);
  /// Standing at a random heading, spawn_min..spawn_max beyond the object's footprint.
  virtual void DefaultInit(int env_id, Rng& rng, sim::InitialState* init);
  /// Per-env state of the derived skill for snapshots.
  virtual void SaveTaskState(int env_id, std::vector<double>* out) const;
  /// Restores SaveTaskState() output; returns the number of values consumed.
  virtual size_t LoadTaskState(int env_id, const double* data, size_t size);

  std::vector<double> SaveSkillState(int env_id) const final;
  void LoadSkillState(int env_id, const double* data, size_t size) final;

  /// A free floor point spawn_min..spawn_max beyond object g's footprint.
  Eigen::Vector2d SpawnPoint(const ObjectGeometry& g, Rng& rng) const;
  /// True when the floor disk of `radius` around p is free (height grid).
  bool FreeFloor(const Eigen::Vector2d& p, double radius) const;
  /// Fills `init` from clip `clip` at time t placed by `placement` (pose + AMP history).
  void PlaceReference(int env_id, int clip, double t, const ClipPlacement& placement,
                      sim::InitialState* init);
  /// Seat/bed clips of `skills` whose furniture fits object g, for reference init: returns
  /// a clip index (−1 if none) and its placement (random lateral offset on wide seats).
  int ChooseFurnitureClip(const std::vector<int>& clips, const ObjectGeometry& g, Rng& rng,
                          ClipPlacement* placement) const;
  /// Reference init from `reference_clips_` placed on env i's furniture (sit, lie).
  bool FurnitureClipInit(int env_id, Rng& rng, sim::InitialState* init);
  /// Contact reward towards `anchor_local` (object frame) with Σ‖g_j − x_j‖² = goal_sum, and
  /// success when the measured distance d is within the threshold.
  sim::TaskStepResult ContactRewardStep(const sim::EnvView& view,
                                        const Eigen::Vector3d& anchor_local, double goal_sum,
                                        double d);
  /// Ends a step: success counter, success-held truncation, excessive-force termination.
  sim::TaskStepResult Finish(const sim::EnvView& view, double reward, bool success);

  std::vector<ObjectGeometry> objects_;
  std::vector<int> object_, hold_, override_;
  std::vector<double> error_;
};

/// Heading direction (unit, xy) of a pose.
Eigen::Vector2d FacingOf(const sim::HumanoidPose& pose);

/// The part's surface point nearest to p (exact, over its triangles).
Eigen::Vector3d NearestOnPart(const scene::Scene& scene, int object, int part,
                              const Eigen::Vector3d& p);

}  // namespace sims::task
