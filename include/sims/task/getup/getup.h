// Get-up: from sitting on a seat, lying on a bed or lying on the floor to standing.
//
// Starts (hybrid, reference_init_prob):
//   reference: a get-up clip's first getup_reference_max_fraction (by default and in evaluation
//     the first quarter: still seated / lying). Furniture clips are placed
//     on the env's seat or bed by their stored furniture parameters; floor clips (clips with no
//     furniture parameters: supine or prone on the floor) at a free floor point clear of the
//     furniture, a getup_floor_clip_share of the reference starts, with the fall states' grace.
//   hand-off: a handoff_share of the reference starts from handoff_states, where the sit and
//     lie policies ended their episodes (task/handoff.h, ObjectSkill's hand-off starts),
//     placed on the env's object when one fits (else a clip start); stories start get-ups there.
//   default: one of getup_fall_states precomputed fall states (ASE getup: a random root
//     orientation and random actions U[−0.5, 0.5] held for 300 physics steps at 120 Hz, i.e.
//     ASE's 150 steps at 60 Hz), placed where every body lies on free floor, with
//     getup_fall_grace_steps steps during which falls do not terminate.
// ASE's recovery episodes (a fall-terminated env keeps going for a grace period) are an env
// option: EnvConfig::recovery_episode_prob.
//
// Goal and reward (in [0, 1]):
//   feet phase: the contact goal is both feet on the floor disk of kStandDiskRadius around the
//     stand point s (on furniture: the feet's midpoint when both feet rest on the floor, as a
//     seated character's do, so the rise happens over the feet; else the object's free floor
//     point nearest to the pelvis; on the floor: the start point); r = w·contact reward
//     (contact_reward.h, w = kFeetPhaseWeight) with anchor s and g_j the nearest disk points of the
//     feet. The phase ends when both feet are within contact_success_threshold of the disk.
//   rise phase: r = w + (1 − w)·((1 − c)·RiseReward + c·[standing clear]) (c = kClearWeight),
//     RiseReward = U·H·(0.6 + 0.4·B) + 0.15·S,
//     H = 0.4·exp(−20·dp²) + 0.3·exp(−8·dh²) + 0.15·exp(−2·dh²), dp = max(h*_p − z_pelvis, 0),
//     dh = max(h*_h − z_head, 0), U = 0.6 + 0.2·max(up_pelvis, 0) + 0.2·max(up_torso, 0),
//     B = exp(−10·‖m − f‖²) with m the mean of the pelvis, torso and head (xy) and f the feet's
//     midpoint, S = exp(−k·‖s − x_pelvis‖²) (k = 2, or getup_furniture_stand_sharpness
//     beside furniture); h*_p, h*_h the standing pelvis and head heights,
//     up the bodies' up axes (z components). History: a pelvis-only reward had a stable
//     half-way optimum (pelvis at 0.68 m, torso folded, head at pelvis height; first
//     campaign, 0 % success), hence the head and upright factors. The next form (0.5 + 0.5·
//     (0.3·exp(−10·dp²) + 0.3·exp(−4·dh²) + up and stand terms)) paid 0.77 for sitting still
//     and 0.83 for a crouch against 1.0 for standing, while a failed rise ends the episode: the
//     policy rose to a crouch or fell, 0/100 in evaluation (chunk 4). Recorded seat trials
//     (eval_policy --record) then showed how it fell: legs straightened, feet pushed 0.3 m
//     forward, trunk tipped back, head 0.5 m behind the pelvis and down within 0.7 s; B pays
//     for rising over the feet instead (the clips' seat-off has the weight over the feet).
//     Sitting now pays ~0.37 and the crouch ~0.55; the wide head kernel still grades a lying
//     head. The clear term: standing touching the seat paid as much as standing clear, and
//     success only ends the episode (its value bootstrapped), so nothing paid for finishing:
//     from risen seat starts the policy left the hold uncounted, stepped about and fell (a
//     third of the episodes) or ended bent over (third session's probe, getup TRAINING.md).
// The observation always carries the pelvis goal (s at standing height), plus the feet goals
// in the feet phase. Success (StandingClear): standing upright (pelvis and head high enough,
// pelvis and torso up axes within ~37° of vertical) with nothing but the feet touching
// anything, and the feet on the floor (away from the furniture); the episode ends without
// failure once it has held for success_hold_steps.
#pragma once

#include <string>
#include <vector>

#include "sims/task/handoff.h"
#include "sims/task/object_skill.h"

namespace sims::task {

/// Radius of the floor disk the feet must reach (m).
inline constexpr double kStandDiskRadius = 0.3;
/// Largest feet-phase reward and smallest rise-phase reward: finishing the feet phase never
/// lowers the reward.
inline constexpr double kFeetPhaseWeight = 0.2;
/// Share of the rise-phase reward paid only while standing clear (the success test).
inline constexpr double kClearWeight = 0.2;
/// k of the stand-point term exp(−k·d²) in RiseReward (GetUpParams::furniture_stand_sharpness
/// for stand points beside furniture).
inline constexpr double kStandSharpness = 2.0;

/// A precomputed fall state: the pose (root xy at the origin) and how far its bodies reach
/// from the root horizontally, for placing it clear of furniture.
struct FallState {
  humanoid::HumanoidPose pose;  ///< State after the fall.
  double reach = 0;             ///< Largest horizontal body-origin distance from the root (m).
};

/// The per-env data of the get-up skill (after its ObjectState in a snapshot).
struct GetUpState {
  int phase = 0;                                    ///< GetUpSkill::Phase.
  int start = 0;                                    ///< GetUpSkill::Start.
  Eigen::Vector2d stand = Eigen::Vector2d::Zero();  ///< Stand point (world xy).
  double backplay = 0;                              ///< Furniture backplay level in [0, 1].
  double floor_backplay = 0;                        ///< Floor-clip backplay level in [0, 1].
  bool furniture_stand = false;  ///< The stand point is the object's free floor point.

  /// Lists the fields.
  void Serialize(StateArchive* a);
};

/// The get-up skill.
class GetUpSkill : public ObjectSkill {
 public:
  /// Phases of an episode.
  enum Phase : int { kFeetPhase = 0, kRisePhase = 1 };
  /// How env i's episode started (start_label()).
  /// (kHandoffStart last: snapshots store the number.)
  enum Start : int { kSeatStart = 0, kBedStart, kFloorClipStart, kFallStart, kHandoffStart };

  /// Per-env state for context.num_envs envs; the fall states come from a per-process cache.
  GetUpSkill(const SkillConfig& config, const SkillContext& context);

  std::string name() const override { return "getup"; }
  /// Moves the env's backplay level after a reference episode (getup_backplay_end > 0), then
  /// starts the next episode as every object skill does.
  void SampleInitialState(int env_id, Rng& rng, sim::InitialState* init) override;
  /// The furniture backplay level when backplay runs, else the object skills' spawn level or
  /// NaN.
  double curriculum_level(int env_id) const override;
  void OnReset(const sim::EnvView& view, Rng& rng) override;
  sim::TaskStepResult Step(const sim::EnvView& view) override;
  /// Gets up from the current state (seat, bed or floor after a fall); target.point, when
  /// set, is the stand point, else the object's stand point nearest the pelvis.
  bool BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) override;
  /// Feet, hands, pelvis and thighs (get-up pushes off with the hands).
  uint32_t contact_body_mask() const override;
  /// Already standing clear: a get-up instruction has nothing to do.
  bool Accomplished(const sim::EnvView& view) const override { return StandingClear(view); }
  /// "seat", "bed", "floor" (a floor clip), "fall" (a fall state) or "handoff" (a hand-off
  /// state).
  std::string start_label(int env_id) const override;

  /// Current phase of env i.
  int phase(int env_id) const { return getup_[env_id].phase; }
  /// How env i's episode started.
  Start start(int env_id) const { return static_cast<Start>(getup_[env_id].start); }
  /// Stand point of env i (world xy).
  const Eigen::Vector2d& stand_point(int env_id) const { return getup_[env_id].stand; }
  /// True when env i's stand point is its object's free floor point (see GetUpState).
  bool furniture_stand(int env_id) const { return getup_[env_id].furniture_stand; }
  /// Env i's backplay level in [0, 1] for furniture clips (getup_backplay_end).
  double backplay_level(int env_id) const { return getup_[env_id].backplay; }
  /// Env i's backplay level in [0, 1] for floor clips.
  double floor_backplay_level(int env_id) const { return getup_[env_id].floor_backplay; }
  /// Sets env i's furniture (or floor-clip) backplay level (tests, tools).
  void SetBackplayLevel(int env_id, double level, bool floor = false);
  /// Whether env i's episode started on the floor (a fall state or a floor clip).
  bool floor_start(int env_id) const {
    return getup_[env_id].start == kFloorClipStart || getup_[env_id].start == kFallStart;
  }
  /// The precomputed fall states.
  const std::vector<FallState>& fall_states() const { return *fall_states_; }
  /// Standing upright (pelvis and head heights of `params`, pelvis and torso up axes).
  static bool Standing(const humanoid::BodyStates& b, const GetUpParams& params);
  /// Standing, only the feet touching anything and every contact on the floor (the success).
  bool StandingClear(const sim::EnvView& view) const;
  /// What the rise-phase reward reads from the character.
  struct RiseInputs {
    double pelvis_z = 0;                                  ///< Pelvis height (m).
    double head_z = 0;                                    ///< Head height (m).
    double pelvis_up = 0;                                 ///< z component of the pelvis up axis.
    double torso_up = 0;                                  ///< z component of the torso up axis.
    Eigen::Vector2d pelvis_xy = Eigen::Vector2d::Zero();  ///< Pelvis (world xy).
    /// Mean of the pelvis, torso and head origins (world xy): where the upper body's weight is.
    Eigen::Vector2d upper_xy = Eigen::Vector2d::Zero();
    Eigen::Vector2d feet_xy = Eigen::Vector2d::Zero();  ///< Midpoint of the feet (world xy).
  };
  /// The rise inputs of body states b.
  static RiseInputs RiseInputsOf(const humanoid::BodyStates& b);
  /// The rise-phase reward term in [0, 1] (see the file comment); `head_height` is the
  /// standing head height.
  static double RiseReward(const RiseInputs& x, const Eigen::Vector2d& stand, double head_height,
                           double stand_sharpness = kStandSharpness);
  /// Head height of the default (standing) pose (m).
  double default_head_height() const { return head_height_; }
  /// Nearest point of the floor disk around `stand` to a foot at p (at foot rest height).
  Eigen::Vector3d FootTarget(const Eigen::Vector2d& stand, const Eigen::Vector3d& p) const;

 protected:
  bool Accepts(const ObjectGeometry& g) const override;
  bool ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) override;
  /// ObjectSkill's, labelled kHandoffStart.
  bool HandoffInit(int env_id, Rng& rng, sim::InitialState* init) override;
  void DefaultInit(int env_id, Rng& rng, sim::InitialState* init) override;
  void SerializeTaskState(int env_id, StateArchive* archive) override;

 private:
  void StartGetUp(int env_id, const humanoid::BodyStates& b);
  // A reference start time (s) in a clip of `duration` s for env i: the backplay window of the
  // floor or furniture level when backplay runs, else the first reference_max_fraction but at
  // most `max_fraction`.
  double ReferenceTime(int env_id, double duration, double max_fraction, bool floor,
                       Rng& rng) const;
  void SetGetUpGoals(int env_id, const humanoid::BodyStates& b, double* feet_sq, double* feet_max);
  // A free floor point for a body reaching `reach` m from its root, tried near env i's object
  // (the spawn ring); false when none of the draws was clear.
  bool ClearFloorPoint(int env_id, double reach, Rng& rng, Eigen::Vector2d* p) const;

  double foot_height_ = 0.0;
  double head_height_ = 0.0;
  std::shared_ptr<const std::vector<FallState>> fall_states_;
  std::vector<int> furniture_clips_, floor_clips_;  // library indices
  std::vector<GetUpState> getup_;                   // per env
};

/// Generates `count` fall states from `seed` (see the file comment): state k draws from
/// Rng(seed + k), so the set is the same at any thread count. Root xy is zero.
std::vector<FallState> GenerateFallStates(int count, uint64_t seed);

/// Registry entry for getup.
SkillInfo GetUpSkillInfo();

}  // namespace sims::task
