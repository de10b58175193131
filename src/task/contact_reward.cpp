#include "sims/task/contact_reward.h"

#include <algorithm>
#include <cmath>

#include "sims/core/error.h"
#include "sims/scene/scene.h"

namespace sims::task {

double ContactReward(const Eigen::Vector2d& anchor, const Eigen::Vector2d& root,
                     const Eigen::Vector2d& velocity, const Eigen::Vector2d& facing,
                     double target_speed, double contact_sq_sum) {
  return kNearWeight * NearReward(contact_sq_sum) +
         (1.0 - kNearWeight) * FarReward(anchor, root, velocity, facing, target_speed);
}

double NearReward(double contact_sq_sum, double wide_share, double precise_share) {
  SIMS_DCHECK(wide_share >= 0 && precise_share >= 0 && wide_share + precise_share <= 1);
  return (1.0 - wide_share - precise_share) * std::exp(-10.0 * contact_sq_sum) +
         wide_share * std::exp(-contact_sq_sum) + precise_share * std::exp(-100.0 * contact_sq_sum);
}

double FarReward(const Eigen::Vector2d& anchor, const Eigen::Vector2d& root,
                 const Eigen::Vector2d& velocity, const Eigen::Vector2d& facing,
                 double target_speed) {
  const Eigen::Vector2d delta = anchor - root;
  const double d2 = delta.squaredNorm();
  if (d2 <= kFarDistanceSq) return 1.0;
  const Eigen::Vector2d dir = delta / std::sqrt(d2);
  // Moving away earns nothing, and neither does facing away (not squared: ±cos alike).
  const double v = dir.dot(velocity);
  const double speed_err = target_speed - v;
  const double r_speed = v > 0 ? std::exp(-2.0 * speed_err * speed_err) : 0.0;
  const double r_face = std::max(0.0, dir.dot(facing));
  return 0.5 * std::exp(-0.5 * d2) + 0.4 * r_speed + 0.1 * r_face;
}

bool ParseContactType(const std::string& text, ContactType* type) {
  const std::string t = scene::NormalizeName(text);
  if (t == "contact") {
    *type = ContactType::kContact;
  } else if (t == "not contact" || t == "noncontact" || t == "no contact") {
    *type = ContactType::kNotContact;
  } else if (t == "none" || t.empty()) {
    *type = ContactType::kNone;
  } else {
    return false;
  }
  return true;
}

bool ParseDirection(const std::string& text, Eigen::Vector3d* d) {
  const std::string t = scene::NormalizeName(text);
  if (t == "up")
    *d = {0, 0, 1};
  else if (t == "down")
    *d = {0, 0, -1};
  else if (t == "left")
    *d = {0, 1, 0};
  else if (t == "right")
    *d = {0, -1, 0};
  else if (t == "front")
    *d = {1, 0, 0};
  else if (t == "back")
    *d = {-1, 0, 0};
  else if (t == "none" || t.empty())
    *d = Eigen::Vector3d::Zero();
  else
    return false;
  return true;
}

double AdaptiveCombine(const double* r, int n, double* weights) {
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += r[i];
  const double denom = n - sum + 1e-4;
  double total = 0;
  for (int i = 0; i < n; ++i) {
    const double w = (1.0 - r[i]) / denom;
    if (weights) weights[i] = w;
    total += w * r[i];
  }
  return total;
}

PairReward ContactPairReward(const JointPair& p) {
  PairReward out;
  if (p.type == ContactType::kNone) return out;
  const Eigen::Vector3d diff = p.joint - p.target;
  const double d2 = diff.squaredNorm();
  const double e = std::exp(-10.0 * d2);
  out.contact = p.type == ContactType::kContact ? e : 1.0 - e;
  out.direction = 1.0;
  if (p.type == ContactType::kContact && p.direction.squaredNorm() > 0) {
    // normalize(joint − target): the side of the target the joint is on.
    const double n = diff.norm();
    const Eigen::Vector3d u = n > 1e-12 ? Eigen::Vector3d(diff / n) : Eigen::Vector3d::Zero();
    out.direction = std::max(0.0, u.dot(p.direction));
  }
  const double r[2] = {out.contact, out.direction};
  out.reward = AdaptiveCombine(r, 2);
  out.err2 = d2 + (out.direction < 0.5 ? 1.0 : 0.0);
  return out;
}

StepReward UniHsiStepReward(const std::array<JointPair, humanoid::kNumContactJoints>& pairs,
                            const Eigen::Vector3d& root, const Eigen::Vector3d& root_velocity,
                            const Eigen::Vector2d& facing, const Eigen::Vector3d& stand_point,
                            double target_speed) {
  StepReward out;
  int valid = 0;
  for (const auto& p : pairs) valid += p.type != ContactType::kNone;
  if (valid == 0) {
    // Walking step toward the stand point.
    out.walking = true;
    const Eigen::Vector3d delta = stand_point - root;
    const double pos_err = delta.squaredNorm();
    out.walk_err2 = pos_err;
    const double r_pos = std::exp(-0.5 * pos_err);
    const double dn = delta.head<2>().norm();
    const Eigen::Vector2d dir =
        dn > 1e-12 ? Eigen::Vector2d(delta.head<2>() / dn) : Eigen::Vector2d::Zero();
    double r_vel = 1.0, r_face = 1.0;
    if (pos_err >= 0.2) {
      const double v_dir = dir.dot(root_velocity.head<2>());
      const double err = target_speed - v_dir;
      r_vel = v_dir <= 0 ? 0.0 : std::exp(-2.0 * err * err);
      r_face = std::max(0.0, dir.dot(facing));
    }
    const double r[3] = {r_pos, r_vel, r_face};
    out.reward = AdaptiveCombine(r, 3);
    return out;
  }
  std::array<double, humanoid::kNumContactJoints> r;
  for (int j = 0; j < humanoid::kNumContactJoints; ++j) {
    const PairReward pr = ContactPairReward(pairs[j]);
    r[j] = pr.reward;
    out.err2[j] = pr.err2;
  }
  const double near = AdaptiveCombine(r.data(), humanoid::kNumContactJoints);
  // Facing the target matters only when one hand is the sole contact (a reach).
  double r_face = 1.0;
  if (valid == 1) {
    for (int hand : {humanoid::kCjRightHand, humanoid::kCjLeftHand}) {
      if (pairs[hand].type == ContactType::kNone) continue;
      const Eigen::Vector2d d = (pairs[hand].target - root).head<2>();
      if (d.norm() > 1e-12) r_face = std::max(0.0, d.normalized().dot(facing));
    }
  }
  const double rr[2] = {near, r_face};
  out.reward = AdaptiveCombine(rr, 2);
  return out;
}

StepCheck CheckUniHsiStep(const std::array<ContactType, humanoid::kNumContactJoints>& types,
                          const StepReward& reward, bool big_force, int still_steps) {
  StepCheck c;
  bool loose = true, tight = true;
  if (reward.walking) {
    loose = tight = reward.walk_err2 < 0.1;
  } else {
    for (int j = 0; j < humanoid::kNumContactJoints; ++j) {
      const double e = reward.err2[j];
      if (types[j] == ContactType::kContact) {
        loose = loose && e < 0.3;
        tight = tight && e < 0.1;
      } else if (types[j] == ContactType::kNotContact) {
        loose = loose && e >= 0.1;
        tight = tight && e >= 0.05;
      }
    }
  }
  c.triggered = loose && !big_force && still_steps > 10;
  c.advance = c.triggered && tight;
  return c;
}

double PairContactError(ContactType type, double distance) {
  if (type == ContactType::kContact) return distance;
  if (type == ContactType::kNotContact) return std::max(0.3 - distance, 0.0);
  return 0.0;
}

}  // namespace sims::task
