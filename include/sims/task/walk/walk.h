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
#pragma once

#include "sims/task/skill.h"

namespace sims::task {

/// The walk skill (pelvis target on the floor).
class WalkSkill : public Skill {
 public:
  /// One angle per hinge (rad).
  using JointAngles = Eigen::Matrix<double, sim::kNumDofs, 1>;

  /// Per-env targets are drawn at reset.
  WalkSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "walk"; }
  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;
  /// Walks to target.point (xy), or to the object's centre when only an object is given.
  bool BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) override;
  /// Pelvis-to-target distance (xy).
  double goal_error(const sim::EnvView& view) const override;

  /// Sets env i's target (world xy; z is ignored) — used by the FSM and evaluation.
  void SetTarget(int env_id, const Eigen::Vector2d& target_xy);
  /// Env i's current target.
  Eigen::Vector2d target(int env_id) const { return target_[env_id]; }
  /// The speed env `env_id`'s reward asks for (m/s): target_speed, or its style clip's pace.
  double target_speed(int env_id) const;
  /// The style-posture reward of env `env_id` for averaged joint angles `mean_pose` (1 when no
  /// style clip is drawn): exp(−style_pose_scale·mean_j (q̃_j − q̄_j)²).
  double StylePoseReward(int env_id, const JointAngles& mean_pose) const;
  /// Env `env_id`'s running-average joint angles q̃ (style_pose_weight > 0 only).
  const JointAngles& average_pose(int env_id) const { return pose_average_[env_id]; }
  /// Draws a target on free floor at a distance in [min, max] from `from`.
  Eigen::Vector2d SampleTarget(const Eigen::Vector2d& from, Rng& rng) const;
  /// The walk reward for one state (exposed for tests).
  static double Reward(const Eigen::Vector2d& target, const Eigen::Vector2d& root,
                       const Eigen::Vector2d& velocity, const Eigen::Vector2d& prev_velocity,
                       const Eigen::Vector2d& facing, double target_speed);

 protected:
  std::vector<double> SaveSkillState(int env_id) const override;
  void LoadSkillState(int env_id, const double* data, size_t size) override;

 private:
  std::vector<Eigen::Vector2d> target_, prev_velocity_;
  std::vector<int> hold_;
  // Walk targets for later resampling come from a per-env stream seeded at reset, so the
  // hook needs no access to the env's RNG inside Step().
  std::vector<Rng> target_rng_;
  // Mean joint angles of every library clip (the style clips' postures), when
  // style_pose_weight > 0; shared read-only by all envs.
  std::vector<JointAngles> clip_mean_pose_;
  // Per env: the running-average posture q̃ (empty when style_pose_weight is 0).
  std::vector<JointAngles> pose_average_;
};

/// Registry entry for walk.
SkillInfo WalkSkillInfo();

}  // namespace sims::task
