// Get-up: from sitting on a seat, lying on a bed or lying fallen on the floor to standing.
//
// Starts: reference init from get-up clips (their seated/lying first quarter) placed on the
// env's seat or bed by the clips' stored furniture parameters, otherwise one of a fixed set of
// fall states (ASE getup: a random root orientation and random actions U[−0.5, 0.5] held for
// 300 physics steps at 120 Hz, i.e. ASE's 150 steps at 60 Hz) placed around the object, with
// kFallGraceSteps steps during which falls do not terminate.
//
// Goal and reward (in [0, 1]):
//   feet phase: the contact goal is both feet on the floor disk of kStandDiskRadius around the
//     stand point s (the object's free floor point nearest to the pelvis; the start point for
//     fall states); r = 0.5·contact reward (contact_reward.h) with anchor s and g_j the nearest
//     disk points of the feet. The phase ends when both feet are within
//     contact_success_threshold of the disk.
//   rise phase: r = 0.5 + 0.5·(0.6·exp(−10·max(h* − z_pelvis, 0)²) + 0.2·max(up_z, 0)
//     + 0.2·exp(−2·‖s − x_pelvis‖²)), h* the standing pelvis height, up_z the pelvis up axis.
// The observation always carries the pelvis goal (s at standing height), plus the feet goals
// in the feet phase. Success: standing (pelvis ≥ kStandingPelvisHeight, up_z ≥ 0.8); the
// episode ends without failure once it has held for success_hold_steps.
//
// "sit_getup" trains sit and get-up together: the episode starts like sit (sit.h reward and
// goal); once sitting has held for success_hold_steps the goal switches to get-up (feet phase)
// within the same episode.
#pragma once

#include "sims/task/object_skill.h"

namespace sims::task {

/// Standing: pelvis at least this high (m).
inline constexpr double kStandingPelvisHeight = 0.8;
/// Falls do not terminate during the first steps after a fall-state start (ASE: 60).
inline constexpr int kFallGraceSteps = 60;
/// Number of precomputed fall states.
inline constexpr int kNumFallStates = 32;
/// Radius of the floor disk the feet must reach (m).
inline constexpr double kStandDiskRadius = 0.3;

/// The get-up skill (and its sit-then-get-up variant).
class GetUpSkill : public ObjectSkill {
 public:
  /// Phases of an episode.
  enum Phase : int { kSitPhase = 0, kFeetPhase = 1, kRisePhase = 2 };

  /// `sit_first` selects the sit_getup variant.
  GetUpSkill(const SkillConfig& config, const SkillContext& context, bool sit_first);

  std::string name() const override { return sit_first_ ? "sit_getup" : "getup"; }
  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;
  /// Gets up from the current state (seat, bed or floor after a fall); target.point, when
  /// set, is the stand point, else the object's stand point nearest the pelvis.
  bool BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) override;
  /// Feet, hands, pelvis and thighs (get-up pushes off with the hands); sit_getup adds the head.
  uint32_t contact_body_mask() const override;

  /// Current phase of env i.
  int phase(int env_id) const { return phase_[env_id]; }
  /// Stand point of env i (world xy).
  const Eigen::Vector2d& stand_point(int env_id) const { return stand_[env_id]; }
  /// Whether env i's episode started from a fall state.
  bool fall_start(int env_id) const { return fall_start_[env_id] != 0; }
  /// The precomputed fall states (root xy at the origin).
  const std::vector<sim::HumanoidPose>& fall_states() const { return fall_states_; }
  /// Standing test.
  static bool Standing(const sim::BodyStates& b);
  /// The rise-phase reward term in [0, 1] (see the file comment).
  static double RiseReward(double pelvis_z, double up_z, const Eigen::Vector2d& stand,
                           const Eigen::Vector2d& pelvis_xy);
  /// Nearest point of the floor disk around `stand` to a foot at p (at foot rest height).
  Eigen::Vector3d FootTarget(const Eigen::Vector2d& stand, const Eigen::Vector3d& p) const;

 protected:
  bool Accepts(const ObjectGeometry& g) const override;
  bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) override;
  void DefaultInit(int env_id, Rng& rng, sim::InitialState* init) override;
  void SaveTaskState(int env_id, std::vector<double>* out) const override;
  void LoadTaskState(int env_id, StateReader* r) override;

 private:
  void StartGetUp(int env_id, const sim::BodyStates& b);
  void SetGetUpGoals(int env_id, const sim::BodyStates& b, double* feet_sq, double* feet_max);

  bool sit_first_;
  double foot_height_ = 0.0;
  std::vector<sim::HumanoidPose> fall_states_;
  std::vector<int> phase_, sit_hold_;
  std::vector<uint8_t> fall_start_;
  std::vector<Eigen::Vector2d> stand_;
};

/// Generates `count` fall states with seed `seed` (see the file comment); root xy is zero.
std::vector<sim::HumanoidPose> GenerateFallStates(int count, uint64_t seed);

/// Registry entry for getup.
SkillInfo GetUpSkillInfo();
/// Registry entry for sit_getup (sit, then get up, in one episode).
SkillInfo SitGetUpSkillInfo();

}  // namespace sims::task
