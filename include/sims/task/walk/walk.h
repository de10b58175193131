// Walk: the reference skill. Copy this folder to write a new one (README "Add a skill").
//
// Goal: the pelvis reaches a target point on free floor, moving at about target_speed, facing
// the way it goes, and then stands still (SIMS supplementary):
//   d² = ‖x* − x_root‖² (xy)
//   far (d² > 0.5):  r = 0.4·r_near + 0.5·r_far
//   near:            r = 0.4·r_near + 0.5 + 0.1·r_still
//   r_far  = 0.6·exp(−0.5·d²) + 0.2·exp(−2·(v* − d*·ẋ)²)·[d*·ẋ > 0] + 0.2·max(0, d*·d_facing)
//   r_near = exp(−10·d²),  r_still = exp(−2·‖ẋ_t − ẋ_{t−1}‖²)
// with d* the unit direction to the target, ẋ the root's horizontal velocity and d_facing the
// heading direction. With style_pose_weight w > 0 (style-conditioned training) the result is
// (1 − w)·r + w·exp(−style_pose_scale·mean_j (q̃_j − q̄_j)²), q̄ the style clip's mean joint
// angles and q̃ the character's, averaged over ~style_pose_time s. Success: within
// walk_success_radius; after success has held for success_hold_steps a new target is drawn so one
// episode practises several approaches.
//
// Among furniture (walk_rooms > 0, walk_params.h): each env walks in its own random furnished
// room, the episode's goal is free floor reachable by A*, and the pelvis goal the policy sees and
// the reward above measure is a carrot walk_path_lookahead ahead on the A* path (the FSM's
// pure pursuit), so training sees the targets stories give. Success is the final goal within
// walk_success_radius; touching furniture or a wall (any body but the feet, or a foot above
// the floor) ends the episode as a failure.
#pragma once

#include <memory>

#include "sims/scene/navigation.h"
#include "sims/task/skill.h"

namespace sims::task {

/// The per-env data of the walk skill, after the base SkillState in a snapshot. The skill object
/// itself is the model (settings, clip postures) and is shared by all envs.
struct WalkState {
  /// One angle per hinge (rad).
  using JointAngles = Eigen::Matrix<double, humanoid::kNumDofs, 1>;

  Eigen::Vector2d target = Eigen::Vector2d::Zero();  ///< Pelvis target (world xy).
  Eigen::Vector2d goal =
      Eigen::Vector2d::Zero();  ///< Where the walk ends (= target on open floor).
  /// The A* path to the goal (walks among furniture only).
  scene::PathFollower path{Eigen::Vector2d::Zero(), {}};
  Eigen::Vector2d prev_velocity = Eigen::Vector2d::Zero();  ///< Root velocity one step ago (xy).
  int hold = 0;                                             ///< Consecutive steps success has held.
  /// The episode started in front of furniture (walk_furniture_start_share; reporting only,
  /// not in snapshots).
  bool furniture_start = false;
  /// Later targets (after a success) come from this per-env stream, seeded at reset, so that the
  /// hook needs no access to the env's RNG inside Step().
  Rng target_rng{0};
  /// Running-average joint angles q̃ (used, and snapshotted, only when style_pose_weight > 0).
  JointAngles pose_average = JointAngles::Zero();

  /// Lists the fields but the pose average, which WalkSkill adds when the posture term is on.
  void Serialize(StateArchive* a);
};

/// The walk skill (pelvis target on the floor).
class WalkSkill : public Skill {
 public:
  /// One angle per hinge (rad).
  using JointAngles = WalkState::JointAngles;

  /// Per-env targets are drawn at reset.
  WalkSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "walk"; }
  /// Among furniture: "furniture" for a start in front of a piece of furniture, else "free"
  /// (evaluation reports success per start); "" on open floor.
  std::string start_label(int env_id) const override;
  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;
  /// Walks to target.point (xy), or to the object's centre when only an object is given.
  bool BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) override;
  /// Pelvis-to-goal distance (xy).
  double goal_error(const sim::EnvView& view) const override;
  /// Among furniture, places the character on free floor of env i's room first.
  void SampleInitialState(int env_id, Rng& rng, sim::InitialState* init) override;

  /// Sets env i's target (world xy; z is ignored) — used by the FSM and evaluation.
  void SetTarget(int env_id, const Eigen::Vector2d& target_xy);
  /// Env i's current target (the pelvis goal it is shown and rewarded for).
  Eigen::Vector2d target(int env_id) const { return walk_[env_id].target; }
  /// Env i's goal: where its walk ends (the target itself on open floor).
  Eigen::Vector2d goal(int env_id) const { return walk_[env_id].goal; }
  /// Env i's A* path (walks among furniture).
  const scene::PathFollower& path(int env_id) const { return walk_[env_id].path; }
  /// Env i's room (walks among furniture; -1 on open floor).
  int room(int env_id) const;
  /// The free-space grid of the rooms (nullptr on open floor).
  const scene::FreeSpaceGrid* free_space() const { return free_space_.get(); }
  /// True when the character touches the scene with anything but its feet on the floor.
  static bool Collided(const sim::EnvView& view);
  /// The speed env `env_id`'s reward asks for (m/s): target_speed, or its style clip's pace.
  double target_speed(int env_id) const;
  /// The style-posture reward of env `env_id` for averaged joint angles `mean_pose` (1 when no
  /// style clip is drawn): exp(−style_pose_scale·mean_j (q̃_j − q̄_j)²).
  double StylePoseReward(int env_id, const JointAngles& mean_pose) const;
  /// The foot-sliding reward exp(−foot_slide_scale·Σ_f ‖v_f,xy‖²) over the feet whose origin
  /// is below foot_contact_height (1 when none slides or no foot is down).
  double FootSlideReward(const humanoid::BodyStates& bodies) const;
  /// Env `env_id`'s running-average joint angles q̃ (style_pose_weight > 0 only).
  const JointAngles& average_pose(int env_id) const { return walk_[env_id].pose_average; }
  /// Draws a target on free floor at a distance in [min, max] from `from`.
  Eigen::Vector2d SampleTarget(const Eigen::Vector2d& from, Rng& rng) const;
  /// The walk reward for one state (exposed for tests).
  static double Reward(const Eigen::Vector2d& target, const Eigen::Vector2d& root,
                       const Eigen::Vector2d& velocity, const Eigen::Vector2d& prev_velocity,
                       const Eigen::Vector2d& facing, double target_speed);

 protected:
  void SerializeSkillState(int env_id, StateArchive* archive) override;

 private:
  // Among furniture: a free point of room k, the goal drawn for env i from `from`, and the
  // pelvis goal moved to the path's carrot.
  Eigen::Vector2d FreePointInRoom(int k, Rng& rng) const;
  void SampleRoomGoal(int env_id, const Eigen::Vector2d& from, Rng& rng);
  void FollowPath(int env_id, const Eigen::Vector2d& root);
  // The next goal from `from`: in env i's room along A*, or on open floor.
  void NewGoal(int env_id, const Eigen::Vector2d& from);

  std::vector<WalkState> walk_;  // per env
  // Among furniture: the free-space grid and each room's floor box (min, max corners).
  std::unique_ptr<const scene::FreeSpaceGrid> free_space_;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> room_boxes_;
  // Among furniture: the sides of each room's furniture, where furniture starts stand.
  struct FurnitureSide {
    Eigen::Vector2d p_WM;  // middle of the side (world xy)
    Eigen::Vector2d n_W;   // outward normal
    Eigen::Vector2d t_W;   // along the side
    double half_width = 0;
  };
  static std::vector<FurnitureSide> FurnitureSides(const scene::Scene& scene,
                                                   const std::string& room);
  // A furniture start in room k: pelvis xy and heading (facing the side); false when no draw
  // found standing room.
  bool FurnitureStart(int k, Rng& rng, Eigen::Vector2d* p_WP, double* yaw) const;
  std::vector<std::vector<FurnitureSide>> room_sides_;
  // Whether the style-posture term is on (style_pose_weight > 0 and a motion library).
  bool posture_ = false;
  // Mean joint angles of every library clip (the style clips' postures), when
  // style_pose_weight > 0; shared read-only by all envs.
  std::vector<JointAngles> clip_mean_pose_;
};

/// Registry entry for walk.
SkillInfo WalkSkillInfo();

}  // namespace sims::task
