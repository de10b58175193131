// Rewards and success rules shared by the contact skills.
//
// Object skills (sit, lie, reach, get-up; InterScene/TokenHSI's near/far split):
//   r = 0.7·r_near + 0.3·r_far
//   r_near = exp(−10·Σ_j ‖g_j − x_j‖²) over the skill's goal joints (fixed, object-local goals);
//            a skill whose joints start far from their goals once at the object (lie: pelvis and
//            head ~1 m from a bed's centre line and pillow when seated on its edge) mixes in a
//            wide kernel: (1 − s)·exp(−10·Σ) + s·exp(−Σ), where the narrow one alone is ~0
//   r_far  = 1 within √0.5 m (xy) of the anchor x* (a stand point in front of the object) or, in
//            ObjectSkill::ContactRewardStep, of the target itself (a bed's centre is ~1 m from
//            the stand point beside it: lying there must not cost the far reward), else
//            0.5·exp(−0.5·d²) + 0.4·r_speed + 0.1·max(0, d̂·facing),
//            r_speed = exp(−2·(v* − d̂·ẋ)²) when moving towards x* (d̂·ẋ > 0), 0 otherwise.
//
// UniHSI contact pairs (the UniHSI paper, its unified controller): per joint a contact term
// r_c = exp(−10·d²) (contact) or 1 − exp(−10·d²) (not contact) and a direction term
// r_dir = max(0, dir·normalize(joint − target)) (1 without a direction or for not-contact),
// combined with adaptive weights w_i = (1 − r_i)/(n − Σr + 1e-4); then over the 15 joints
// (joints without a pair count 1), then with a hand-facing term. A step without contacts is a
// walking step toward a stand point: exp(−0.5·|Δp|²), velocity and facing terms, adaptively.
// Kept exactly as UniHSI has it, including its corner: when every term is exactly 1 all weights
// are 0 and so is the sum (a pair needs its joint within millimetres of the target for this,
// which body geometry prevents).
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "sims/humanoid/humanoid.h"

namespace sims::task {

/// Squared xy distance beyond which the contact reward is in its "far" form (m²).
inline constexpr double kFarDistanceSq = 0.5;

/// Weight of r_near in ContactReward (InterScene, TokenHSI).
inline constexpr double kNearWeight = 0.7;

/// The object-skill reward for one state (see the file comment). `contact_sq_sum` is
/// Σ_j ‖g_j − x_j‖² over the skill's goal joints; `facing` is the unit heading direction.
double ContactReward(const Eigen::Vector2d& anchor, const Eigen::Vector2d& root,
                     const Eigen::Vector2d& velocity, const Eigen::Vector2d& facing,
                     double target_speed, double contact_sq_sum);

/// r_near of ContactReward with a share `wide_share` of the wide kernel exp(−Σ) and a share
/// `precise_share` of the precise kernel exp(−100Σ); the shares add up to at most 1.
double NearReward(double contact_sq_sum, double wide_share = 0.0, double precise_share = 0.0);

/// r_far of ContactReward: 1 within √kFarDistanceSq of `anchor`, else the approach terms.
double FarReward(const Eigen::Vector2d& anchor, const Eigen::Vector2d& root,
                 const Eigen::Vector2d& velocity, const Eigen::Vector2d& facing,
                 double target_speed);

/// What a UniHSI pair asks of a joint.
enum class ContactType : int {
  kNone = 0,        ///< "none": not cared about (reward 1, ignored by success).
  kContact = 1,     ///< "contact": touch the target.
  kNotContact = 2,  ///< "not contact": stay away from the target.
};

/// Parses "contact", "not contact" (also "not_contact", "noncontact") and "none"; returns
/// false for anything else.
bool ParseContactType(const std::string& text, ContactType* type);

/// UniHSI's world-frame direction words: up (0,0,1), down, left (0,1,0), right, front
/// (1,0,0), back, none (0). Returns false for unknown words.
bool ParseDirection(const std::string& text, Eigen::Vector3d* direction);

/// Adaptive weights w_i = (1 − r_i)/(n − Σ r + 1e-4) (UniHSI): writes them to `weights` (may
/// be null) and returns Σ w_i·r_i. Weak terms get the most weight; the weights sum to
/// (n − Σr)/(n − Σr + 1e-4) ≈ 1.
double AdaptiveCombine(const double* rewards, int n, double* weights = nullptr);

/// One joint's pair for the UniHSI reward.
struct JointPair {
  ContactType type = ContactType::kNone;                ///< kNone = no pair on this joint.
  Eigen::Vector3d joint = Eigen::Vector3d::Zero();      ///< Joint position (world).
  Eigen::Vector3d target = Eigen::Vector3d::Zero();     ///< Nearest target point (world).
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< Required direction, or zero.
};

/// The reward of one pair and its success distance.
struct PairReward {
  double reward = 1.0;     ///< Adaptive combination of the contact and direction terms.
  double contact = 1.0;    ///< r_c.
  double direction = 1.0;  ///< r_dir.
  double err2 = 0.0;       ///< ‖target − joint‖², +1 when r_dir < 0.5 (blocks success).
};

/// The UniHSI reward of one pair (kNone → reward 1, err2 0).
PairReward ContactPairReward(const JointPair& pair);

/// The UniHSI reward of a whole step.
struct StepReward {
  double reward = 0.0;  ///< Total task reward.
  std::array<double, humanoid::kNumContactJoints>
      err2{};              ///< Per-joint success distance (0 if none).
  double walk_err2 = 0.0;  ///< |stand − root|² (3-d) of a walking step, 0 otherwise.
  bool walking = false;    ///< The step had no pairs.
};

/// UniHSI step reward: the adaptive contact-pair reward, or the walking-step reward toward
/// `stand_point` (3-d, absolute z) when no joint has a pair. `root_velocity` is world-frame.
StepReward UniHsiStepReward(const std::array<JointPair, humanoid::kNumContactJoints>& pairs,
                            const Eigen::Vector3d& root, const Eigen::Vector3d& root_velocity,
                            const Eigen::Vector2d& facing, const Eigen::Vector3d& stand_point,
                            double target_speed = 1.0);

/// UniHSI's step rule after a control step.
struct StepCheck {
  bool triggered = false;  ///< The step is done (loose thresholds, still, no big force).
  bool advance = false;    ///< ... and it passed the tight thresholds: go to the next step.
};

/// Done trigger: every pair holds loosely (contact err² < 0.3, not contact err² ≥ 0.1; walking
/// |Δp|² < 0.1), no excessive force, and the character has been still for more than 10
/// steps. Advance: contact err² < 0.1 and not contact err² ≥ 0.05 (walking: |Δp|² < 0.1).
StepCheck CheckUniHsiStep(const std::array<ContactType, humanoid::kNumContactJoints>& types,
                          const StepReward& reward, bool big_force, int still_steps);

/// UniHSI's stillness test: the largest L1 norm of a body's linear velocity is below 0.6.
inline constexpr double kStillVelocityL1 = 0.6;

/// Contact error of one pair (eval): ‖d‖ for contact, max(0.3 − ‖d‖, 0) for not contact.
double PairContactError(ContactType type, double distance);

}  // namespace sims::task
