// The synthetic catalogue: loading and checking its JSON, and turning its recipes into clips
// with the shared key shapes (sit-down, lie-down, reach timing) and the named poses.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <spdlog/spdlog.h>
#include "motion/synthetic_internal.h"
#include "sims/motion/synthetic_catalog.h"

#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/core/rng.h"
#include "sims/motion/rotation.h"

namespace sims::motion {

using namespace synth;

namespace {

const HumanoidSkeleton& Skel() { return HumanoidSkeleton::Default(); }

// World poses of the bodies for one key (its first solved frame).
SkeletonPose PoseOf(const BodyKey& key) {
  BodyKey k = key;
  k.t = 0;
  const MotionFrame f = SolveKeys({k}, 30.0)[0];
  SkeletonPose sp;
  SkeletonForwardKinematics(Skel(), f.root_pos, f.root_rot, f.dof_pos, &sp);
  return sp;
}

std::string Suffix(int variant) { return variant == 0 ? "" : "_v" + std::to_string(variant); }

// Solves keys above the floor and `furniture` and labels the clip with the furniture; with
// `rest_on_floor` (no furniture) every frame rests on the floor (see SolveKeys).
MotionClip Build(const std::vector<BodyKey>& keys, const IdleNoise& noise, MotionMeta meta,
                 double fps, const std::vector<FurnitureSpec>& furniture,
                 bool rest_on_floor = false) {
  SolveStats stats;
  std::vector<MotionFrame> frames = SolveKeys(keys, fps, noise, &furniture, &stats, rest_on_floor);
  spdlog::debug("synthetic {}: leg IK miss {:.4f} m, arm IK miss {:.4f} m, lift {:.4f} m",
                meta.name, stats.leg_error, stats.arm_error, stats.max_lift);
  for (std::size_t i = 0; i < furniture.size(); ++i) {
    const std::string p = furniture.size() == 1 ? "" : std::to_string(i) + "_";
    const FurnitureSpec& f = furniture[i];
    meta.params[p + "furniture_height"] = f.height;
    meta.params[p + "furniture_depth"] = f.depth;
    meta.params[p + "furniture_width"] = f.width;
    meta.params[p + "furniture_front_x"] = f.front_x;
    meta.params[p + "furniture_center_y"] = f.center_y;
  }
  return MotionClip(fps, std::move(frames), std::move(meta));
}

// The approach composites: walk up to the seat, stop, turn round in place, then the sit-down
// clip unchanged (so its furniture parameters still hold). Appended after the catalogue and
// drawing nothing from its random stream, so every other clip stays as it was.
constexpr double kApproachSpeed = 1.0;      // m/s
constexpr double kApproachWalkTime = 1.6;   // s at full speed before slowing
constexpr double kApproachStopTime = 0.8;   // s to slow to a stand
constexpr double kApproachTurnTime = 2.8;   // s for the 180° turn (as walk_turn_in_place_180)
constexpr double kApproachBlendTime = 0.3;  // s of crossfade into the sit-down clip

double Heading(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d x = q * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

// Walk up and stop, then (turn_round) a 180° turn in place.
WalkSpec ApproachSpec(const WalkStyle& gait, bool turn_round) {
  const double t0 = kApproachWalkTime, t1 = t0 + kApproachStopTime, T = kApproachTurnTime;
  const double peak = M_PI / (0.5 * T + 0.25 * T);  // bump area ≈ 0.75·peak·T = π
  WalkSpec s;
  s.style = gait;
  s.keys = {{0.0, kApproachSpeed, 0}, {t0, kApproachSpeed, 0}, {t1, 0, 0}, {t1 + 0.2, 0, 0}};
  s.duration = t1 + 0.6;
  if (turn_round) {
    s.keys.push_back({t1 + 0.2 + 0.25 * T, 0, peak});
    s.keys.push_back({t1 + 0.2 + 0.75 * T, 0, peak});
    s.keys.push_back({t1 + 0.2 + T, 0, 0});
    s.duration = t1 + 0.2 + T + 0.4;
  }
  return s;
}

// ---------------------------------------------------------------------------------------
// Key shapes shared by the recipes.

BodyKey At(BodyKey k, double t, bool hold = false) {
  k.t = t;
  k.hold = hold;
  return k;
}

// Hands resting near the given points (world) with elbows out.
void HandsTo(BodyKey* k, const Eigen::Vector3d& right, const Eigen::Vector3d& left, double w = 1) {
  k->limbs[0].weight = w, k->limbs[0].target = right,
  k->limbs[0].hint = Eigen::Vector3d(-0.3, -1, -0.5);
  k->limbs[1].weight = w, k->limbs[1].target = left,
  k->limbs[1].hint = Eigen::Vector3d(-0.3, 1, -0.5);
}

// Rest hand positions of a key (to blend into IK without a jump).
void HandsAtRest(BodyKey* k) {
  const SkeletonPose sp = PoseOf(*k);
  k->limbs[0].target = sp.pos[humanoid::kRightHand];
  k->limbs[1].target = sp.pos[humanoid::kLeftHand];
}

// A point resting on top of a thigh, `along` from hip to knee (hand sphere clears the capsule).
Eigen::Vector3d OnThigh(const SkeletonPose& sp, bool left, double along) {
  const int thigh = left ? humanoid::kLeftThigh : humanoid::kRightThigh;
  const int shin = left ? humanoid::kLeftShin : humanoid::kRightShin;
  return sp.pos[thigh] + along * (sp.pos[shin] - sp.pos[thigh]) +
         Eigen::Vector3d(0, left ? 0.025 : -0.025, 0.115);
}

// How far the hip may sit behind the seat's front edge: the thigh capsule slopes down to the
// knee (knee height is fixed by the shin with the feet flat) and must clear the edge.
double HipBehindEdge(double seat_height) {
  const HumanoidSkeleton& s = Skel();
  const double knee_z = s.ankle_height() + s.shin_length();
  const double hip_z = seat_height + 0.085;
  constexpr double kThighRadius = 0.055;
  double d = 0.22;
  if (hip_z > knee_z) {
    const double slope = (hip_z - knee_z) / s.thigh_length();
    d = std::min(d, 0.9 * (hip_z - kThighRadius - seat_height) / slope);
  }
  return std::max(d, 0.05);
}

// Places a seat of the given size so that, seated with the feet where they stood (x = 0),
// the knees overhang its front edge.
FurnitureSpec PlaceSeat(double height, double depth, double width) {
  const HumanoidSkeleton& s = Skel();
  const double knee_z = s.ankle_height() + s.shin_length();
  const double hip_z = height + 0.085;
  const double dz = hip_z - knee_z;
  const double hip_x = -std::sqrt(std::max(0.0, s.thigh_length() * s.thigh_length() - dz * dz));
  FurnitureSpec f;
  f.height = height;
  f.depth = depth;
  f.width = width;
  f.front_x = hip_x + HipBehindEdge(height);
  return f;
}

// Seated on `seat` with the hands on the thighs.
BodyKey SeatedKey(const FurnitureSpec& seat, double t) {
  BodyKey k = StandingKey(t, 0.1);
  k.pelvis = Eigen::Vector3d(seat.front_x - HipBehindEdge(seat.height), 0, seat.height + 0.085);
  k.pitch = Deg(2);
  k.dofs[kAbdY] = Deg(6);
  k.dofs[kNeckY] = -Deg(5);
  k.dofs[kRElbow] = k.dofs[kLElbow] = -Deg(60);
  // Hands on the thighs, a little behind the knees.
  const SkeletonPose sp = PoseOf(k);
  HandsTo(&k, OnThigh(sp, false, 0.65), OnThigh(sp, true, 0.65));
  return k;
}

// Standing in front of the seat, then down onto it. `lean` scales the forward trunk lean.
std::vector<BodyKey> SitDownKeys(const FurnitureSpec& seat, double lean, double t_sit) {
  const BodyKey seated = SeatedKey(seat, 0);
  const double h = Skel().standing_root_height();
  std::vector<BodyKey> keys;
  BodyKey stand = StandingKey(0.0, 0.1);
  HandsAtRest(&stand);
  keys.push_back(stand);
  keys.push_back(At(stand, 0.5, true));
  BodyKey bend = stand;
  bend.t = 0.5 + 0.45 * t_sit;
  bend.pelvis = Eigen::Vector3d(-0.06, 0, h - 0.16);
  bend.pitch = Deg(30 * lean);
  bend.dofs[kAbdY] = Deg(10 * lean);
  bend.dofs[kNeckY] = -Deg(25 * lean);
  bend.dofs[kRShY] = bend.dofs[kLShY] = -Deg(30);
  bend.dofs[kRElbow] = bend.dofs[kLElbow] = -Deg(25);
  keys.push_back(bend);
  BodyKey land = seated;
  land.t = 0.5 + 0.8 * t_sit;
  land.pelvis = Eigen::Vector3d(seated.pelvis.x() + 0.06, 0, seated.pelvis.z() + 0.05);
  land.pitch = Deg(26 * lean);
  land.dofs[kAbdY] = Deg(8 * lean);
  land.dofs[kNeckY] = -Deg(20 * lean);
  land.limbs[0].weight = land.limbs[1].weight = 1.0;
  keys.push_back(land);
  keys.push_back(At(seated, 0.5 + t_sit, true));
  return keys;
}

MotionClip SitDown(const FurnitureSpec& seat, double lean, double t_sit, double hold,
                   MotionMeta meta, double fps, uint64_t seed) {
  std::vector<BodyKey> keys = SitDownKeys(seat, lean, t_sit);
  keys.push_back(At(keys.back(), keys.back().t + hold, true));
  IdleNoise noise;
  noise.seed = seed;
  noise.look = Deg(4);
  return Build(keys, noise, std::move(meta), fps, {seat});
}

// How far a rise from a seat draws the feet back behind the knees first (m), at most. With the
// shins upright (the seated key) the hips are ~0.4 m behind the ankles and the centre of mass
// stays behind the heels whatever the trunk lean; people tuck their feet under the seat before
// they stand, so the body can pass over them. The calves must stay in front of the seat's
// front face (kRiseCalfClearance behind the ankle), which limits the tuck of deep seats.
constexpr double kRiseFootTuck = 0.16;
constexpr double kRiseCalfClearance = 0.1;

// The hands on the thighs near the knees, elbows back along the body rather than out to the
// sides: the forearms pass inside a chair's armrests (arms swung forward or out land on them
// and hold the body down).
void HandsNearKnees(BodyKey* k) {
  const SkeletonPose sp = PoseOf(*k);
  HandsTo(k, OnThigh(sp, false, 0.8), OnThigh(sp, true, 0.8));
  k->limbs[0].hint = Eigen::Vector3d(-1, -0.3, -0.3);
  k->limbs[1].hint = Eigen::Vector3d(-1, 0.3, -0.3);
}

// Keys of a rise from a seat (forward in time, not a reversed sit-down): seated with the feet
// tucked back, the trunk pitches forward over the knees while the pelvis still rests on the
// seat, the pelvis leaves the seat once the centre of mass is over the feet, then hips and
// knees extend to standing above the tucked feet. `lean` scales the trunk lean, `t_rise` is the
// time from the first lean to standing, `hold` the seated time before it (the first key, at 0).
std::vector<BodyKey> RiseKeys(const FurnitureSpec& seat, double lean, double t_rise, double hold) {
  const double h = Skel().standing_root_height();
  const double d = std::clamp(-seat.front_x - kRiseCalfClearance, 0.0, kRiseFootTuck);
  const auto tuck = [d](BodyKey* k) {
    for (int leg = 2; leg < 4; ++leg) k->limbs[leg].target.x() -= d;
  };
  BodyKey seated = SeatedKey(seat, 0.0);
  tuck(&seated);
  {
    const SkeletonPose sp = PoseOf(seated);
    HandsTo(&seated, OnThigh(sp, false, 0.65), OnThigh(sp, true, 0.65));
  }
  const Eigen::Vector3d hip = seated.pelvis;
  std::vector<BodyKey> keys;
  keys.push_back(seated);
  keys.push_back(At(seated, hold, true));
  // Flexion: trunk forward over the knees, pelvis still on the seat.
  BodyKey flex = seated;
  flex.t = hold + 0.35 * t_rise;
  flex.hold = false;
  flex.pelvis = hip + Eigen::Vector3d(0.03, 0, 0);
  flex.pitch = Deg(32 * lean);
  flex.dofs[kAbdY] = Deg(8 * lean);
  flex.dofs[kNeckY] = -Deg(30 * lean);
  HandsNearKnees(&flex);
  keys.push_back(flex);
  // Seat-off: the pelvis lifts and comes forward over the feet, the trunk at its deepest lean.
  BodyKey off = flex;
  off.t = hold + 0.55 * t_rise;
  off.pelvis = Eigen::Vector3d(hip.x() + 0.24 - d, 0, hip.z() + 0.07);
  off.pitch = Deg(33 * lean);
  HandsNearKnees(&off);
  keys.push_back(off);
  // Extension: hips and knees straighten, the trunk comes up.
  BodyKey rise = off;
  rise.t = hold + 0.8 * t_rise;
  rise.pelvis = Eigen::Vector3d(-d - 0.08, 0, h - 0.2);
  rise.pitch = Deg(26 * lean);
  rise.dofs[kAbdY] = Deg(6 * lean);
  rise.dofs[kNeckY] = -Deg(15 * lean);
  rise.dofs[kRShY] = rise.dofs[kLShY] = -Deg(15);
  rise.dofs[kRElbow] = rise.dofs[kLElbow] = -Deg(20);
  rise.limbs[0].weight = rise.limbs[1].weight = 0;
  keys.push_back(rise);
  BodyKey stand = StandingKey(hold + t_rise, 0.1);
  tuck(&stand);
  stand.pelvis.x() -= d;
  keys.push_back(stand);
  keys.push_back(At(stand, stand.t + 0.6, true));
  return keys;
}

// A rise from a seat as a clip (RiseKeys).
MotionClip RiseFromSeat(const FurnitureSpec& seat, double lean, double t_rise, double hold,
                        MotionMeta meta, double fps, uint64_t seed) {
  IdleNoise noise;
  noise.seed = seed;
  noise.look = Deg(4);
  return Build(RiseKeys(seat, lean, t_rise, hold), noise, std::move(meta), fps, {seat});
}

// Supine / side lying on a bed whose long axis is world y; head toward +y.
FurnitureSpec BedFor(double height) {
  FurnitureSpec bed = PlaceSeat(height, 1.0, 2.2);
  bed.center_y = -0.1;
  return bed;
}

BodyKey SupineKey(const FurnitureSpec& bed, double t) {
  BodyKey k;
  k.t = t;
  k.hold = true;
  // Mid-depth: a bed is 1 m deep here, a sofa's seat ~0.7 m.
  k.pelvis = Eigen::Vector3d(bed.front_x - 0.5 * bed.depth, 0.0, bed.height + 0.11);
  k.yaw = -Deg(90);
  k.pitch = -Deg(90);
  k.dofs[kRShX] = -Deg(8), k.dofs[kLShX] = Deg(8);
  k.dofs[kRElbow] = k.dofs[kLElbow] = -Deg(10);
  k.dofs[kRHipY] = k.dofs[kLHipY] = -Deg(10);
  k.dofs[kRKnee] = k.dofs[kLKnee] = Deg(15);
  k.dofs[kRAnkY] = k.dofs[kLAnkY] = Deg(20);
  k.dofs[kNeckY] = -Deg(10);
  return k;
}

// Gives a key's legs IK targets at its own ankle poses (so IK keys blend into joint keys).
void LegsToIk(BodyKey* k, const Eigen::Vector3d& knee_hint) {
  const SkeletonPose sp = PoseOf(*k);
  for (int leg = 0; leg < 2; ++leg) {
    const int foot = leg == 0 ? humanoid::kRightFoot : humanoid::kLeftFoot;
    LimbKey& l = k->limbs[2 + leg];
    l.weight = 1;
    l.target = sp.pos[foot];
    const Eigen::Vector3d fwd = sp.rot[foot] * Eigen::Vector3d::UnitX();
    l.yaw = std::atan2(fwd.y(), fwd.x());
    l.pitch = std::atan2(-fwd.z(), fwd.head<2>().norm());
    l.hint = knee_hint;
  }
}

std::vector<BodyKey> LieDownKeys(const FurnitureSpec& bed) {
  std::vector<BodyKey> keys = SitDownKeys(bed, 0.8, 2.0);
  const BodyKey seated = keys.back();
  const double t0 = seated.t;
  BodyKey supine = SupineKey(bed, t0 + 2.6);
  LegsToIk(&supine, Eigen::Vector3d(0, 0, 1));
  // Lean back and turn, lifting the feet above the mattress in front of the bed edge.
  BodyKey back = seated;
  back.t = t0 + 0.9;
  back.hold = false;
  back.pelvis += Eigen::Vector3d(-0.05, 0.0, 0.02);
  back.yaw = -Deg(20);
  back.pitch = -Deg(25);
  back.dofs[kAbdY] = Deg(12);
  // Arms reach back and out to the mattress, clear of the folding legs.
  back.limbs[0].weight = back.limbs[1].weight = 0;
  back.dofs[kRShY] = back.dofs[kLShY] = Deg(25);
  back.dofs[kRShX] = -Deg(30), back.dofs[kLShX] = Deg(30);
  back.dofs[kRElbow] = back.dofs[kLElbow] = -Deg(15);
  const Eigen::Quaterniond yaw_back = YawQuat(back.yaw);
  for (int leg = 0; leg < 2; ++leg) {
    const double side = leg == 0 ? -1 : 1;
    LimbKey& l = back.limbs[2 + leg];
    l.target = Eigen::Vector3d(bed.front_x + 0.12, 0, bed.height + 0.17) +
               yaw_back * Eigen::Vector3d(0, side * 0.1, 0);
    l.yaw = back.yaw;
    l.pitch = Deg(20);
    l.hint = yaw_back * Eigen::Vector3d(0.6, side * 0.1, 1);
  }
  keys.push_back(back);
  // Swing the legs over the bed while lying back.
  BodyKey swing = supine;
  swing.t = t0 + 1.7;
  swing.hold = false;
  swing.pelvis = supine.pelvis + Eigen::Vector3d(0.05, 0.05, 0.08);
  swing.yaw = -Deg(70);
  swing.pitch = -Deg(60);
  swing.dofs[kRShY] = swing.dofs[kLShY] = Deg(10);
  swing.dofs[kRShX] = -Deg(30), swing.dofs[kLShX] = Deg(30);
  swing.dofs[kRElbow] = swing.dofs[kLElbow] = -Deg(15);
  for (int leg = 0; leg < 2; ++leg) {
    LimbKey& l = swing.limbs[2 + leg];
    l.target = supine.limbs[2 + leg].target + Eigen::Vector3d(0.1, 0.3, 0.18);
    l.hint = Eigen::Vector3d(0.3, 0, 1);
  }
  keys.push_back(swing);
  keys.push_back(supine);
  return keys;
}

// Rising from lying on a bed: the lie-down's lying part played backwards (supine, legs swung
// over the edge, sitting up on the edge), then a rise from the edge as from a seat (RiseKeys),
// so the way up balances over the feet as the seat get-ups do.
constexpr double kBedRiseLean = 1.0;  // trunk lean scale of the rise from the edge
constexpr double kBedRiseTime = 1.9;  // s from the first lean to standing
constexpr double kBedSitHold = 0.3;   // s seated on the edge before the rise

std::vector<BodyKey> GetUpFromBedKeys(const FurnitureSpec& bed) {
  const std::vector<BodyKey> down = LieDownKeys(bed);
  // down = stand, stand, bend, land, seated, back, swing, supine: keep the lying part.
  const std::vector<BodyKey> lying(down.end() - 4, down.end());
  const double t_seated = lying.back().t - lying.front().t;
  std::vector<BodyKey> keys;
  for (auto it = lying.rbegin(); it + 1 != lying.rend(); ++it) {
    BodyKey k = *it;
    k.t = lying.back().t - it->t;
    keys.push_back(k);
  }
  for (BodyKey k : RiseKeys(bed, kBedRiseLean, kBedRiseTime, kBedSitHold)) {
    k.t += t_seated;
    keys.push_back(k);
  }
  return keys;
}

// ---------------------------------------------------------------------------------------
// On the floor. A get-up from the floor ends standing at the origin facing +x (as the seat
// get-ups do) after kneeling with the knees at x = kKneelX and the left foot stepped forward
// to x = 0; the lying poses are placed so that the way up passes there.

constexpr double kKneelX = -0.40;     // knees when kneeling (m)
constexpr double kKneelWidth = 0.1;   // knees and feet either side of the midline (m)
constexpr double kToeTuckDeg = 70;    // foot pitch (toe down) with the toes tucked under
constexpr double kTuckBack = 0.40;    // toe edge behind the knee when kneeling (m)
constexpr double kHandsAhead = 0.55;  // hands ahead of the knees on hands and knees (m)
constexpr double kHandWidth = 0.17;   // hands either side of the midline (m)
constexpr double kSupineY = -0.30;    // pelvis y lying on the back (rolls over toward +y)
constexpr uint32_t kHands = (1u << humanoid::kRightHand) | (1u << humanoid::kLeftHand);
constexpr uint32_t kFeet = (1u << humanoid::kRightFoot) | (1u << humanoid::kLeftFoot);

// Sets a key's pelvis orientation from world axes of its front (+x) and up (+z).
void Orient(BodyKey* k, const Eigen::Vector3d& front, const Eigen::Vector3d& up) {
  Eigen::Matrix3d R;
  R.col(0) = front.normalized();
  R.col(2) = up.normalized();
  R.col(1) = R.col(2).cross(R.col(0));
  const Eigen::Vector3d ypr = R.eulerAngles(2, 1, 0);
  k->yaw = ypr[0], k->pitch = ypr[1], k->roll = ypr[2];
}

// Moves the pelvis up or down until the key's lowest geom touches the floor, leaving out the
// `skip` bodies (planted hands and feet: their IK targets hold them where they are).
void RestOnFloor(BodyKey* k, uint32_t skip = 0) {
  const auto h = HumanoidSkeleton::DefaultHumanoid();
  humanoid::MjDataPtr d = humanoid::MakeData(h->model());
  BodyKey one = *k;
  one.t = 0;
  for (int iter = 0; iter < 40; ++iter) {
    one.pelvis = k->pelvis;
    const double z = LowestPoint(*h, d.get(), SolveKeys({one}, 30.0)[0], skip);
    if (std::abs(z) < 1e-5) break;
    k->pelvis.z() -= z;
  }
}

// A foot with the toes tucked under (sole facing back, toe edge on the floor at x, y).
LimbKey TuckedFoot(double x, double y, const Eigen::Vector3d& knee_hint) {
  LimbKey l;
  l.weight = 1;
  l.pitch = Deg(kToeTuckDeg);
  l.target = Eigen::Vector3d(x, y, 0) - FootRotation(0, l.pitch) * FootOf(Skel()).toe;
  l.hint = knee_hint;
  return l;
}

// A hand flat on the floor at (x, y), elbow toward `hint`.
LimbKey HandOnFloor(double x, double y, const Eigen::Vector3d& hint) {
  LimbKey l;
  l.weight = 1;
  l.target = Eigen::Vector3d(x, y, 0.04);  // hand sphere radius
  l.hint = hint;
  return l;
}

// Turns a key's legs from joint angles into IK at their own ankle poses, the knees pointing
// where they do (so the feet can be planted or steered from there).
void LegsToIkInPlace(BodyKey* k) {
  const SkeletonPose sp = PoseOf(*k);
  LegsToIk(k, Eigen::Vector3d::UnitZ());
  k->limbs[2].hint = sp.rot[humanoid::kRightThigh] * Eigen::Vector3d::UnitX();
  k->limbs[3].hint = sp.rot[humanoid::kLeftThigh] * Eigen::Vector3d::UnitX();
}

// A key between two keys (w = 0: a, 1: b): pelvis orientation by slerp, the rest (position,
// joint angles, limbs) blended linearly; time and flags from a.
BodyKey Mix(const BodyKey& a, const BodyKey& b, double w) {
  BodyKey k = a;
  k.pelvis = (1 - w) * a.pelvis + w * b.pelvis;
  const Eigen::Quaterniond q =
      YawPitchRoll(a.yaw, a.pitch, a.roll).slerp(w, YawPitchRoll(b.yaw, b.pitch, b.roll));
  Orient(&k, q * Eigen::Vector3d::UnitX(), q * Eigen::Vector3d::UnitZ());
  k.dofs = (1 - w) * a.dofs + w * b.dofs;
  for (int l = 0; l < 4; ++l) {
    LimbKey& m = k.limbs[l];
    const LimbKey &x = a.limbs[l], &y = b.limbs[l];
    m.weight = (1 - w) * x.weight + w * y.weight;
    m.target = (1 - w) * x.target + w * y.target;
    m.yaw = (1 - w) * x.yaw + w * y.yaw;
    m.pitch = (1 - w) * x.pitch + w * y.pitch;
    m.hint = (1 - w) * x.hint + w * y.hint;
  }
  return k;
}

// A point for a hand resting on top of a thigh or shin (`body`), `along` the way to the
// next joint: the hand sphere touches the capsule from above.
Eigen::Vector3d OnTopOf(const SkeletonPose& sp, int body, double along) {
  const Eigen::Vector3d a = sp.pos[body], b = sp.pos[body + 1];
  const Eigen::Vector3d axis = (b - a).normalized();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ() - axis.z() * axis;
  up = up.norm() > 1e-6 ? up.normalized() : Eigen::Vector3d::UnitX();
  return a + along * (b - a) + 0.1 * up;  // capsule 0.055 + hand 0.04, a little clearance
}

// Both hands on top of the left thigh (right hand nearer the hip), elbows out.
void HandsOnLeftThigh(BodyKey* k, const SkeletonPose& sp, double right, double left) {
  HandsTo(k, OnTopOf(sp, humanoid::kLeftThigh, right) + Eigen::Vector3d(0, -0.03, 0),
          OnTopOf(sp, humanoid::kLeftThigh, left) + Eigen::Vector3d(0, 0.02, 0));
  k->limbs[0].hint = Eigen::Vector3d(-0.4, -1, 0.3);
  k->limbs[1].hint = Eigen::Vector3d(-0.4, 1, 0.3);
}

// Turns a key's legs from IK into the joint angles of its solved pose (IK weight 0).
void LegsToJoints(BodyKey* k) {
  BodyKey one = *k;
  one.t = 0;
  const MotionFrame f = SolveKeys({one}, 30.0)[0];
  k->dofs.segment<14>(kRHipX) = f.dof_pos.segment<14>(kRHipX);
  k->limbs[2].weight = k->limbs[3].weight = 0;
}

// Relaxed hanging arms (as standing).
void ArmsHanging(BodyKey* k) {
  const BodyKey stand = StandingKey(0.0);
  for (int i : {kRShX, kRShY, kRShZ, kRElbow, kLShX, kLShY, kLShZ, kLElbow})
    k->dofs[i] = stand.dofs[i];
  k->limbs[0].weight = k->limbs[1].weight = 0;
}

// Makes both descriptions of every limb agree with the key's solved pose: limbs it moves by
// joint angles (IK weight 0) get IK targets where they are, limbs it places by IK get the
// joint angles IK gives them. Blending between a joint-angle key and an IK key then starts
// and ends at the same pose.
void TargetsInPlace(BodyKey* k) {
  BodyKey one = *k;
  one.t = 0;
  const MotionFrame f = SolveKeys({one}, 30.0)[0];
  SkeletonPose sp;
  SkeletonForwardKinematics(Skel(), f.root_pos, f.root_rot, f.dof_pos, &sp);
  for (int l = 0; l < 4; ++l) {
    if (k->limbs[l].weight <= 0) continue;
    const int first = l == 0 ? kRShX : l == 1 ? kLShX : l == 2 ? kRHipX : kLHipX;
    const int count = l < 2 ? 4 : 7;
    k->dofs.segment(first, count) = f.dof_pos.segment(first, count);
  }
  for (int arm = 0; arm < 2; ++arm) {
    LimbKey& l = k->limbs[arm];
    if (l.weight > 0) continue;
    l.target = sp.pos[arm == 0 ? humanoid::kRightHand : humanoid::kLeftHand];
    l.hint = Eigen::Vector3d(-1, arm == 0 ? -0.3 : 0.3, 0);
  }
  for (int leg = 0; leg < 2; ++leg) {
    LimbKey& l = k->limbs[2 + leg];
    if (l.weight > 0) continue;
    const int foot = leg == 0 ? humanoid::kRightFoot : humanoid::kLeftFoot;
    l.target = sp.pos[foot];
    const Eigen::Vector3d fwd = sp.rot[foot] * Eigen::Vector3d::UnitX();
    l.yaw = std::atan2(fwd.y(), fwd.x());
    l.pitch = std::atan2(-fwd.z(), fwd.head<2>().norm());
    l.hint = sp.rot[foot - 2] * Eigen::Vector3d::UnitX();
  }
}

// Whole-body floor poses (the key's time and hold are kept).
BodyKey FloorBase(const BodyKey& k) {
  BodyKey b;
  b.t = k.t;
  b.hold = k.hold;
  b.slerp = true;
  b.monotone = true;
  return b;
}

// Lying on the back, head toward +x, arms by the sides, legs long; the feet by leg IK.
void FloorSupine(BodyKey& k) {
  k = FloorBase(k);
  k.yaw = M_PI, k.pitch = -Deg(90);  // front up, head toward +x
  k.pelvis = Eigen::Vector3d(kKneelX, kSupineY, 0.1);
  k.dofs[kRShX] = -Deg(10), k.dofs[kLShX] = Deg(10);
  k.dofs[kRElbow] = k.dofs[kLElbow] = -Deg(15);
  k.dofs[kRKnee] = k.dofs[kLKnee] = Deg(5);
  k.dofs[kRAnkY] = k.dofs[kLAnkY] = Deg(20);
  k.dofs[kNeckY] = -Deg(8);
  RestOnFloor(&k);
  LegsToIkInPlace(&k);
  TargetsInPlace(&k);
}

// Lying face down, head toward +x, hands on the floor beside the chest, toes tucked under.
void FloorProne(BodyKey& k) {
  k = FloorBase(k);
  k.pitch = Deg(90);  // front down, head toward +x
  k.pelvis = Eigen::Vector3d(kKneelX + 0.40, 0, 0.1);
  k.dofs[kNeckY] = -Deg(25);
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1 : 1;
    k.limbs[side] = HandOnFloor(k.pelvis.x() + 0.30, s * 0.24, Eigen::Vector3d(-1, s * 0.6, 1));
    k.limbs[2 + side] = TuckedFoot(kKneelX - kTuckBack, s * kKneelWidth, -Eigen::Vector3d::UnitZ());
  }
  RestOnFloor(&k, kHands | kFeet);
  TargetsInPlace(&k);
}

// On hands and knees, facing +x, toes tucked under.
void HandsAndKnees(BodyKey& k) {
  k = FloorBase(k);
  k.pitch = Deg(80);
  k.pelvis = Eigen::Vector3d(kKneelX + 0.04, 0, 0.5);
  k.dofs[kNeckY] = -Deg(35);
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1 : 1;
    k.limbs[side] = HandOnFloor(kKneelX + kHandsAhead, s * kHandWidth, Eigen::Vector3d(-1, 0, 0));
    k.limbs[2 + side] =
        TuckedFoot(kKneelX - kTuckBack, s * kKneelWidth, Eigen::Vector3d(1, 0, -0.3));
  }
  RestOnFloor(&k, kHands | kFeet);
  TargetsInPlace(&k);
}

// Kneeling upright on both knees, toes tucked under, arms hanging.
void Kneeling(BodyKey& k) {
  k = FloorBase(k);
  k.pitch = Deg(4);
  k.pelvis = Eigen::Vector3d(kKneelX + 0.02, 0, 0.5);
  ArmsHanging(&k);
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1 : 1;
    k.limbs[2 + side] =
        TuckedFoot(kKneelX - kTuckBack, s * kKneelWidth, Eigen::Vector3d(1, 0, -0.3));
  }
  RestOnFloor(&k, kFeet);
  TargetsInPlace(&k);
}

// On the right knee, left foot forward flat where it will stand, hands on the left knee.
void OneKnee(BodyKey& k) {
  k = FloorBase(k);
  k.pitch = Deg(10);
  k.pelvis = Eigen::Vector3d(kKneelX + 0.03, -0.02, 0.5);
  k.dofs[kAbdY] = Deg(6);
  k.limbs[2] = TuckedFoot(kKneelX - kTuckBack, -kKneelWidth, Eigen::Vector3d(1, 0, -0.3));
  k.limbs[3] = StandingKey(0.0).limbs[3];
  k.limbs[3].hint = Eigen::Vector3d(1, 0.1, 0.3);
  RestOnFloor(&k, kFeet);
  const SkeletonPose sp = PoseOf(k);
  HandsOnLeftThigh(&k, sp, 0.65, 0.85);
  TargetsInPlace(&k);
}

// ---------------------------------------------------------------------------------------
// Named poses: edits that depend on the body's own geometry (forward kinematics of the edited
// key) or on the bed, which a list of numbers in the catalogue cannot express.

using PoseFn = void (*)(BodyKey&, const FurnitureSpec&);

const std::map<std::string, PoseFn>& NamedPoses() {
  static const std::map<std::string, PoseFn> poses = {
      {"hands_behind_back",
       [](BodyKey& k, const FurnitureSpec&) {
         std::array<Eigen::Vector3d, 2> targets, hints;
         HandsBehindBackTargets(k.pelvis, YawPitchRoll(k.yaw, k.pitch, k.roll), &targets, &hints);
         for (int arm = 0; arm < 2; ++arm) {
           k.limbs[arm].weight = 1;
           k.limbs[arm].target = targets[arm];
           k.limbs[arm].hint = hints[arm];
         }
       }},
      {"hands_mid_thigh",
       [](BodyKey& k, const FurnitureSpec&) {
         const SkeletonPose sp = PoseOf(k);
         HandsTo(&k, OnThigh(sp, false, 0.5), OnThigh(sp, true, 0.5));
       }},
      {"legs_crossed",
       [](BodyKey& k, const FurnitureSpec&) {
         // Right knee over the left one, right foot hanging beside the left shin.
         k.limbs[3].target.y() = 0.06;
         const SkeletonPose sp = PoseOf(k);
         LimbKey& r = k.limbs[2];
         r.target = sp.pos[humanoid::kLeftShin] + Eigen::Vector3d(0.05, 0.13, -0.16);
         r.yaw = Deg(20), r.pitch = Deg(25);
         r.hint = Eigen::Vector3d(0.3, 0.4, 1);
         // Hands rest on the crossed thigh.
         const SkeletonPose crossed = PoseOf(k);
         HandsTo(&k, OnThigh(crossed, false, 0.4) + Eigen::Vector3d(0, -0.03, 0),
                 OnThigh(crossed, false, 0.85) + Eigen::Vector3d(0, 0.05, 0));
       }},
      {"hands_on_knees",
       [](BodyKey& k, const FurnitureSpec&) {
         const SkeletonPose sp = PoseOf(k);
         HandsTo(&k, sp.pos[humanoid::kRightShin] + Eigen::Vector3d(0.02, 0, 0.09),
                 sp.pos[humanoid::kLeftShin] + Eigen::Vector3d(0.02, 0, 0.09));
       }},
      {"on_side",
       [](BodyKey& k, const FurnitureSpec& bed) {
         k.yaw = 0, k.pitch = 0, k.roll = -Deg(80);
         k.pelvis = Eigen::Vector3d(bed.front_x - 0.5, 0.0, bed.height + 0.12);
         k.dofs = DofVector::Zero();
         k.dofs[kRHipY] = k.dofs[kLHipY] = -Deg(50);
         k.dofs[kRKnee] = k.dofs[kLKnee] = Deg(65);
         k.dofs[kLShY] = -Deg(80), k.dofs[kLElbow] = -Deg(70);
         k.dofs[kRShY] = -Deg(10), k.dofs[kRShX] = -Deg(5), k.dofs[kRElbow] = -Deg(30);
         k.dofs[kAbdY] = Deg(10), k.dofs[kNeckY] = Deg(10);
       }},
      {"knees_up",
       [](BodyKey& k, const FurnitureSpec& bed) {
         const SkeletonPose sp = PoseOf(k);
         for (int leg = 0; leg < 2; ++leg) {
           const int thigh = leg == 0 ? humanoid::kRightThigh : humanoid::kLeftThigh;
           LimbKey& l = k.limbs[2 + leg];
           l.weight = 1;
           l.target = sp.pos[thigh] + Eigen::Vector3d(0, -0.5, 0);
           l.target.z() = bed.height + FootOf(Skel()).ankle_height;
           l.yaw = -Deg(90), l.pitch = 0;
           l.hint = Eigen::Vector3d(0, 0, 1);
         }
       }},
      {"floor_supine", [](BodyKey& k, const FurnitureSpec&) { FloorSupine(k); }},
      {"floor_prone", [](BodyKey& k, const FurnitureSpec&) { FloorProne(k); }},
      {"hands_and_knees", [](BodyKey& k, const FurnitureSpec&) { HandsAndKnees(k); }},
      {"kneeling", [](BodyKey& k, const FurnitureSpec&) { Kneeling(k); }},
      {"one_knee", [](BodyKey& k, const FurnitureSpec&) { OneKnee(k); }},
  };
  return poses;
}

std::string NamedPoseList() {
  std::string s;
  for (const auto& [name, fn] : NamedPoses()) s += (s.empty() ? "" : ", ") + name;
  return s;
}

int DofIndex(const std::string& name) {
  const auto& names = humanoid::DofNames();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (name == names[i]) return static_cast<int>(i);
  return -1;
}

void RequireDofNames(const std::map<std::string, double>& dofs, const std::string& field) {
  for (const auto& [name, deg] : dofs)
    Require(DofIndex(name) >= 0, field + "." + name, "a joint name (abdomen_x ... left_ankle_z)");
}

void SetDofs(const std::map<std::string, double>& dofs_deg, double sign, BodyKey* k) {
  for (const auto& [name, deg] : dofs_deg) k->dofs[DofIndex(name)] = sign * Deg(deg);
}

void RequireRange(const SyntheticRange& r, const std::string& field) {
  Require(r[0] <= r[1], field, "[lo, hi] with lo <= hi");
}

// Applies a recipe's edits in a fixed order (the named pose last: it measures the edited key).
void ApplyEdit(const PoseEdit& e, const FurnitureSpec& furniture, BodyKey* k) {
  // Only non-zero offsets touch the pelvis so an absent offset leaves it bit-for-bit alone.
  for (int i = 0; i < 3; ++i)
    if (e.pelvis_offset[i] != 0) k->pelvis[i] += e.pelvis_offset[i];
  if (e.pitch_deg) k->pitch = Deg(*e.pitch_deg);
  SetDofs(e.dofs_deg, 1.0, k);
  if (!e.pose.empty()) NamedPoses().at(e.pose)(*k, furniture);
}

IdleNoise NoiseOf(const SyntheticNoise& s) {
  IdleNoise n;
  n.breathing = s.breathing;
  n.look = Deg(s.look_deg);
  n.sway = s.sway;
  n.fidget = Deg(s.fidget_deg);
  return n;
}

MotionMeta Meta(const SyntheticLabels& l, const std::string& skill, int variant,
                const std::vector<std::string>& default_furniture) {
  return SyntheticMeta(l.name + Suffix(variant), skill, l.emotion, l.style, l.captions,
                       l.furniture.empty() ? default_furniture : l.furniture);
}

// Keys of a get-up from the floor (see FloorGetUpRecipe): lying still for kFloorRest s, the
// way up with its times scaled by `tempo`, then standing still for the recipe's hold.
constexpr double kFloorRest = 0.3;

BodyKey FloorPose(void (*pose)(BodyKey&), double t, bool hold = false) {
  BodyKey k;
  k.t = t;
  k.hold = hold;
  pose(k);
  return k;
}

void Slump(BodyKey* k, double deg) {
  k->dofs[kAbdY] += Deg(deg);
  k->dofs[kNeckY] += Deg(deg);
}

std::vector<BodyKey> FloorGetUpKeys(const FloorGetUpRecipe& r, double tempo) {
  std::vector<BodyKey> keys;
  double t = kFloorRest;
  auto after = [&](double dt) { return t += dt * tempo; };
  const bool prone = r.start == "prone";
  const BodyKey lie = FloorPose(prone ? FloorProne : FloorSupine, 0.0, true);
  keys.push_back(lie);
  keys.push_back(At(lie, t, true));
  if (prone) {
    // Push up onto straight arms with the knees down, the body in a line from the knees.
    BodyKey push = lie;
    push.t = after(0.8);
    push.hold = false;
    const double line = Deg(35);  // above the floor
    push.pitch = Deg(90) - line;
    push.pelvis = Eigen::Vector3d(kKneelX + Skel().thigh_length() * std::cos(line), 0, 0.3);
    push.dofs[kNeckY] = -Deg(30);
    for (int side = 0; side < 2; ++side) {
      push.limbs[side].hint = Eigen::Vector3d(-1, 0, 0);
      push.limbs[2 + side].hint = Eigen::Vector3d(std::sin(line), 0, -std::cos(line));
    }
    RestOnFloor(&push, kHands | kFeet);
    keys.push_back(push);
  } else {
    // Draw the knees up to the chest, the heels leaving the floor straight up, and start to
    // roll toward the right side.
    BodyKey heels = lie;
    heels.hold = false;
    heels.t = after(0.2);
    heels.dofs[kNeckY] = Deg(10);
    for (int leg = 0; leg < 2; ++leg) heels.limbs[2 + leg].target += Eigen::Vector3d(0.03, 0, 0.06);
    keys.push_back(heels);
    const Eigen::Quaterniond q_lie = YawPitchRoll(lie.yaw, lie.pitch, lie.roll);
    auto roll = [&](BodyKey* k, double deg) {  // about the long axis, front turning to +y
      const Eigen::Quaterniond q = Eigen::AngleAxisd(-Deg(deg), Eigen::Vector3d::UnitX()) * q_lie;
      Orient(k, q * Eigen::Vector3d::UnitX(), q * Eigen::Vector3d::UnitZ());
    };
    BodyKey tuck = heels;
    tuck.t = after(0.35);
    roll(&tuck, 20);
    tuck.dofs[kNeckY] = Deg(25), tuck.dofs[kAbdY] = Deg(15);
    // Arms forward, the left one starting to reach over.
    tuck.dofs[kRShY] = -Deg(30), tuck.dofs[kRShX] = -Deg(30), tuck.dofs[kRElbow] = -Deg(60);
    tuck.dofs[kLShY] = -Deg(70), tuck.dofs[kLElbow] = -Deg(30);
    for (int leg = 0; leg < 2; ++leg) {
      LimbKey& l = tuck.limbs[2 + leg];
      l.target = Eigen::Vector3d(kKneelX - 0.3, lie.limbs[2 + leg].target.y() + 0.05, 0.3);
      l.pitch = -Deg(30);
      l.hint = Eigen::Vector3d(0, 0.3, 1);
    }
    RestOnFloor(&tuck);
    keys.push_back(tuck);
    // On the right side, knees in front, feet off the floor, the left hand reaching over to
    // the floor ahead of the chest.
    BodyKey side = FloorBase(tuck);
    side.t = after(0.45);
    roll(&side, 90);
    side.pelvis = Eigen::Vector3d(kKneelX, kSupineY + 0.12, 0.15);
    side.dofs[kRHipY] = side.dofs[kLHipY] = -Deg(80);
    side.dofs[kRKnee] = side.dofs[kLKnee] = Deg(100);
    side.dofs[kRHipZ] = -Deg(8), side.dofs[kLHipX] = Deg(10);
    side.dofs[kRAnkY] = side.dofs[kLAnkY] = Deg(20);
    side.dofs[kAbdY] = Deg(10), side.dofs[kNeckY] = Deg(10);
    side.limbs[0] = HandOnFloor(kKneelX + 0.5, kSupineY + 0.25, Eigen::Vector3d(-1, 0, 0.3));
    side.limbs[1] = HandOnFloor(kKneelX + 0.5, kSupineY + 0.4, Eigen::Vector3d(-0.3, 0, 1));
    RestOnFloor(&side, kHands);
    keys.push_back(side);
    // Over onto hands and knees with the toes just off the floor (the right hand lifted and
    // placed on the way), then down onto them.
    BodyKey hover = FloorPose(HandsAndKnees, 0.0);
    for (int leg = 0; leg < 2; ++leg) hover.limbs[2 + leg].target.z() += 0.025;
    LegsToJoints(&hover);
    TargetsInPlace(&hover);
    BodyKey over = Mix(side, hover, 0.5);
    over.t = after(0.35);
    over.limbs[0].target.z() += 0.06;
    keys.push_back(over);
    hover.t = after(0.35);
    keys.push_back(hover);
  }
  // On hands and knees, toes tucked under (a rest there when tired).
  BodyKey hk = FloorPose(HandsAndKnees, after(prone ? 0.7 : 0.2));
  Slump(&hk, 0.5 * r.slump_deg);
  keys.push_back(hk);
  if (r.pause > 0) {
    keys.back().hold = true;
    keys.push_back(At(hk, t += r.pause, true));
  }
  // Kneel up, step the left foot forward onto one knee, rise over it, bring the right foot up.
  BodyKey kneel = FloorPose(Kneeling, after(0.5));
  Slump(&kneel, r.slump_deg);
  keys.push_back(kneel);
  BodyKey one = FloorPose(OneKnee, 0);
  Slump(&one, r.slump_deg);
  BodyKey stand = StandingKey(0.0);
  stand.slerp = stand.monotone = true;
  TargetsInPlace(&stand);
  // A foot steps up off its toes, over to where it lands, and straight down (it leaves and
  // meets the floor without sliding).
  auto step_keys = [&](const BodyKey& from, const BodyKey& to, int leg, double sway) {
    const double s = leg == 0 ? -1 : 1;
    BodyKey up = Mix(from, to, 0.25);
    up.t = after(0.15);
    up.pelvis.y() -= s * sway;
    up.limbs[2 + leg] = from.limbs[2 + leg];
    up.limbs[2 + leg].target += Eigen::Vector3d(0.0, 0.04 * s, 0.16);
    up.limbs[2 + leg].pitch = Deg(60);
    up.limbs[2 + leg].hint = Eigen::Vector3d(1, 0.5 * s, 0.3);
    keys.push_back(up);
    BodyKey over = Mix(from, to, 0.8);
    over.t = after(0.22);
    over.limbs[2 + leg] = to.limbs[2 + leg];
    over.limbs[2 + leg].target.z() += 0.05;
    over.limbs[2 + leg].hint += Eigen::Vector3d(0, 0.3 * s, 0);
    over.dofs[kRShX] -= Deg(10), over.dofs[kLShX] += Deg(10);  // hands clear of the thighs
    for (int arm = 0; arm < 2; ++arm) over.limbs[arm].target.z() += 0.06;  // and the raised knee
    keys.push_back(over);
  };
  step_keys(kneel, one, 1, 0.03);
  one.t = after(0.15);
  keys.push_back(one);
  BodyKey rise = one;
  rise.t = after(0.5);
  rise.pelvis = Eigen::Vector3d(-0.2, -0.02, 0.66);
  rise.pitch = Deg(30);
  rise.dofs[kAbdY] = Deg(12 + r.slump_deg);
  HandsOnLeftThigh(&rise, PoseOf(rise), 0.6, 0.85);
  keys.push_back(rise);
  step_keys(rise, stand, 0, 0.0);
  stand.t = after(0.15);
  keys.push_back(stand);
  for (BodyKey& k : keys) TargetsInPlace(&k);
  keys.push_back(At(stand, t + r.hold, true));
  return keys;
}

// Speed/turn keys of a turn on the spot (smooth yaw-rate bump), then a walk off and a stop.
WalkSpec TurnInPlaceSpec(const TurnInPlace& turn) {
  const double sgn = turn.degrees > 0 ? 1 : -1;
  const double turn_time = turn.turn_time;
  // bump area ≈ 0.75·peak·T
  const double peak = Deg(std::abs(turn.degrees)) / (0.5 * turn_time + 0.5 * turn_time * 0.5);
  WalkSpec s;
  s.duration = 6.2 + turn_time;
  s.keys = {{0.0, 0, 0},
            {0.5, 0, 0},
            {0.5 + 0.25 * turn_time, 0, sgn * peak},
            {0.5 + 0.75 * turn_time, 0, sgn * peak},
            {0.5 + turn_time, 0.2, 0},
            {1.5 + turn_time, 1.1, 0},
            {4.2 + turn_time, 1.1, 0},
            {5.2 + turn_time, 0, 0}};
  return s;
}

}  // namespace

void SyntheticLabels::ValidateLabels() const {
  Require(!name.empty(), "name", "a clip name");
  Require(!emotion.empty(), "emotion", "an emotion label");
  Require(!captions.empty(), "captions", "at least one caption");
  for (const auto& c : captions) Require(!c.empty(), "captions", "non-empty captions");
}

void TurnInPlace::Validate() const {
  Require(degrees != 0 && std::abs(degrees) <= 360, "degrees", "a non-zero angle within ±360");
  Require(turn_time > 0, "turn_time", "a positive time (s)");
}

void WalkRecipe::Validate() const {
  ValidateLabels();
  Require(duration > 0, "duration", "a positive duration (s)");
  Require(turn_in_place || !keys.empty(), "keys", "at least one key (or turn_in_place)");
  Require(!turn_in_place || keys.empty(), "keys", "no keys together with turn_in_place");
  for (std::size_t i = 1; i < keys.size(); ++i)
    Require(keys[i].t >= keys[i - 1].t, "keys[" + std::to_string(i) + "].t",
            "times in increasing order");
}

void WalkSection::Validate() const {
  RequireRange(speed_scale, "speed_scale");
  RequireRange(turn_scale, "turn_scale");
  RequireRange(drift, "drift");
}

void SyntheticNoise::Validate() const {
  Require(breathing >= 0 && look_deg >= 0 && sway >= 0 && fidget_deg >= 0, "noise",
          "non-negative amplitudes");
}

void PoseEdit::Validate() const {
  RequireDofNames(dofs_deg, "dofs_deg");
  Require(pose.empty() || NamedPoses().count(pose), "pose", "empty or one of " + NamedPoseList());
}

void IdleSection::Validate() const {
  Require(duration > 0, "duration", "a positive duration (s)");
  Require(foot_width > 0, "foot_width", "a positive width (m)");
}

void SitMotion::Validate() const {
  ValidateLabels();
  Require(sit_time > 0, "sit_time", "a positive time (s)");
  Require(hold >= 0, "hold", "a non-negative time (s)");
  Require(!furniture.empty(), "furniture", "at least one furniture label");
}

void SeatSpec::Validate() const {
  Require(height > 0 && depth > 0 && width > 0, "height", "positive seat dimensions (m)");
  RequireRange(height_jitter, "height_jitter");
}

void SeatRecipe::Validate() const {
  for (double h : extra_heights)
    Require(h > 0.2 && h < 1.0, "extra_heights", "seat heights in (0.2, 1.0) m");
}

void SitIdleSection::Validate() const {
  Require(duration > 0, "duration", "a positive duration (s)");
  Require(!furniture.empty(), "furniture", "at least one furniture label");
}

void BedSection::Validate() const {
  Require(height > 0, "height", "a positive height (m)");
  RequireRange(variant_height, "variant_height");
  for (double h : extra_heights)
    Require(h > 0.2 && h < 1.0, "extra_heights", "bed heights in (0.2, 1.0) m");
  Require(lie_hold >= 0, "lie_hold", "a non-negative time (s)");
}

void SofaLieSection::Validate() const {
  for (double h : heights) Require(h > 0.2 && h < 1.0, "heights", "seat heights in (0.2, 1.0) m");
  Require(depth >= 0.4 && depth <= 1.2, "depth", "a seat depth in [0.4, 1.2] m");
  Require(width >= 1.2, "width", "a seat width ≥ 1.2 m (room to lie along it)");
  Require(pelvis_offset >= 0 && pelvis_offset < 0.5 * width, "pelvis_offset",
          "an offset in [0, width / 2) m");
  Require(lie_hold >= 0, "lie_hold", "a non-negative time (s)");
  Require(lie_down.name.empty() || !furniture.empty(), "furniture", "at least one furniture label");
}

void LieIdleSection::Validate() const {
  Require(duration > 0, "duration", "a positive duration (s)");
}

void FloorGetUpRecipe::Validate() const {
  ValidateLabels();
  Require(start == "supine" || start == "prone", "start", "\"supine\" or \"prone\"");
  Require(tempo > 0, "tempo", "a positive time scale");
  Require(pause >= 0, "pause", "a non-negative time (s)");
  Require(hold >= 0, "hold", "a non-negative time (s)");
}

void FloorGetUpSection::Validate() const {
  RequireRange(tempo_scale, "tempo_scale");
  Require(tempo_scale[0] > 0, "tempo_scale", "positive time scales");
}

void ReachRecipe::Validate() const {
  ValidateLabels();
  Require(side == "right" || side == "left", "side", "\"right\" or \"left\"");
  Require(!furniture.empty(), "furniture", "at least one furniture label");
  RequireDofNames(dofs_deg, "dofs_deg");
}

void ReachSection::Validate() const {
  Require(target_jitter >= 0, "target_jitter", "a non-negative distance (m)");
  RequireDofNames(side_dofs_deg, "side_dofs_deg");
}

void SyntheticCatalog::Validate() const {
  std::set<std::string> names;
  auto unique = [&](const std::string& section, const std::string& name) {
    Require(names.insert(name).second, section + ".name",
            "clip names unique in the catalogue ('" + name + "' repeats)");
  };
  for (const auto& r : walk.recipes) unique("walk.recipes", r.name);
  for (const auto& r : idle.recipes) unique("idle.recipes", r.name);
  for (const auto& r : seats) unique("seats", r.sit.name), unique("seats", r.getup.name);
  for (const auto& r : sit_idle.recipes) unique("sit_idle.recipes", r.name);
  unique("bed.lie_down", bed.lie_down.name);
  unique("bed.getup", bed.getup.name);
  for (const auto& r : lie_idle.recipes) unique("lie_idle.recipes", r.name);
  for (const auto& r : reach.recipes) unique("reach.recipes", r.name);
  for (const auto& r : floor_getup.recipes) unique("floor_getup.recipes", r.name);
  if (!sofa_lie.lie_down.name.empty()) unique("sofa_lie.lie_down", sofa_lie.lie_down.name);
}

std::filesystem::path DefaultSyntheticCatalogPath() {
  return ConfigPath("motion/synthetic_catalog.json");
}

SyntheticCatalog LoadSyntheticCatalog(const std::filesystem::path& path) {
  return LoadConfig<SyntheticCatalog>(path);
}

MotionClip ComposeAfter(const MotionClip& lead, const MotionClip& clip, double blend_seconds) {
  SIMS_CHECK(lead.num_frames() > 0 && clip.num_frames() > 0 && lead.fps() == clip.fps());
  const MotionFrame& last = lead.frame(lead.num_frames() - 1);
  const MotionFrame& first = clip.frame(0);
  const double yaw = Heading(first.root_rot) - Heading(last.root_rot);
  const Eigen::Quaterniond dq(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  auto place = [&](MotionFrame f) {
    const Eigen::Vector3d d(f.root_pos.x() - last.root_pos.x(), f.root_pos.y() - last.root_pos.y(),
                            0);
    const Eigen::Vector3d p = dq * d;
    f.root_pos =
        Eigen::Vector3d(first.root_pos.x() + p.x(), first.root_pos.y() + p.y(), f.root_pos.z());
    f.root_rot = (dq * f.root_rot).normalized();
    return f;
  };
  std::vector<MotionFrame> frames;
  for (int i = 0; i + 1 < lead.num_frames(); ++i) frames.push_back(place(lead.frame(i)));
  const MotionFrame from = place(last);
  const int blend =
      std::min(clip.num_frames(), static_cast<int>(std::lround(blend_seconds * clip.fps())));
  for (int k = 0; k < clip.num_frames(); ++k) {
    MotionFrame f = clip.frame(k);
    if (k < blend) {
      const double u = (k + 1.0) / (blend + 1.0);
      const double a = u * u * (3 - 2 * u);  // smoothstep
      f.root_pos = (1 - a) * from.root_pos + a * f.root_pos;
      f.root_rot = from.root_rot.slerp(a, f.root_rot).normalized();
      f.dof_pos = (1 - a) * from.dof_pos + a * f.dof_pos;
    }
    frames.push_back(f);
  }
  return MotionClip(clip.fps(), std::move(frames), clip.meta());
}

std::vector<MotionClip> GenerateSyntheticClips(const SyntheticOptions& options) {
  return GenerateSyntheticClips(LoadSyntheticCatalog(DefaultSyntheticCatalogPath()), options);
}

std::vector<MotionClip> GenerateSyntheticClips(const SyntheticCatalog& catalog,
                                               const SyntheticOptions& options) {
  ValidateConfig(options, "synthetic options");
  ValidateConfig(catalog, "synthetic catalogue");
  const double fps = options.fps;
  auto wanted = [&](const std::string& skill) {
    return options.skills.empty() ||
           std::find(options.skills.begin(), options.skills.end(), skill) != options.skills.end();
  };
  std::vector<MotionClip> out;
  // One stream for the whole catalogue: the order of the sections and draws below fixes
  // every variant, so keep it when adding recipes (append them).
  Rng rng(options.seed);
  const double h_stand = Skel().standing_root_height();
  const FurnitureSpec no_furniture;

  if (wanted("walk")) {
    const WalkSection& sec = catalog.walk;
    for (const WalkRecipe& r : sec.recipes) {
      WalkSpec base;
      if (r.turn_in_place) {
        base = TurnInPlaceSpec(*r.turn_in_place);
      } else {
        base.duration = r.duration;
        base.keys = r.keys;
      }
      base.style = r.gait;
      base.seed = r.seed;
      for (int v = 0; v < options.variants; ++v) {
        WalkSpec s = base;
        s.phase = rng.Uniform();
        s.seed = s.seed * 7919 + options.seed * 104729 + v;
        if (v > 0) {
          const double speed = rng.Uniform(sec.speed_scale[0], sec.speed_scale[1]);
          const double turn = rng.Uniform(sec.turn_scale[0], sec.turn_scale[1]);
          for (WalkKey& k : s.keys) k.speed *= speed, k.yaw_rate *= turn;
          // Later variants drift gently so straight walks also cover slight curves.
          if (r.drift) {
            const double drift = rng.Uniform(sec.drift[0], sec.drift[1]);
            for (WalkKey& k : s.keys) k.yaw_rate += drift;
          }
        }
        out.push_back(GenerateWalk(s, Meta(r, "walk", v, sec.furniture), fps));
      }
    }
  }

  if (wanted("idle")) {
    const IdleSection& sec = catalog.idle;
    for (const IdleRecipe& r : sec.recipes) {
      for (int v = 0; v < options.variants; ++v) {
        BodyKey k = StandingKey(0.0, sec.foot_width + sec.foot_width_step * v);
        ApplyEdit(r.key, no_furniture, &k);
        IdleNoise n = NoiseOf(r.noise);
        n.seed = rng.NextU64();
        std::vector<BodyKey> keys = {k, At(k, sec.duration, true)};
        out.push_back(Build(keys, n, Meta(r, "idle", v, sec.furniture), fps, {}));
      }
    }
  }

  // A seat recipe's sit-down and get-up on one seat (names + suffix).
  auto add_seat_clips = [&](const SeatRecipe& r, const FurnitureSpec& seat, int v,
                            const std::string& suffix) {
    if (wanted("sit")) {
      MotionMeta meta = Meta(r.sit, "sit", v, {});
      meta.name += suffix;
      out.push_back(
          SitDown(seat, r.sit.lean, r.sit.sit_time, r.sit.hold, meta, fps, rng.NextU64()));
    }
    if (wanted("getup")) {
      MotionMeta meta = Meta(r.getup, "getup", v, {});
      meta.name += suffix;
      out.push_back(RiseFromSeat(seat, r.getup.lean, r.getup.sit_time, r.getup.hold, meta, fps,
                                 rng.NextU64()));
    }
  };
  if (wanted("sit") || wanted("getup")) {
    for (const SeatRecipe& r : catalog.seats) {
      for (int v = 0; v < options.variants; ++v) {
        const SeatSpec& s = r.seat;
        const FurnitureSpec seat = PlaceSeat(
            s.height + (v == 0 ? 0.0 : rng.Uniform(s.height_jitter[0], s.height_jitter[1])),
            s.depth, s.width);
        add_seat_clips(r, seat, v, "");
      }
    }
  }

  if (wanted("sit")) {
    const SitIdleSection& sec = catalog.sit_idle;
    for (const IdleRecipe& r : sec.recipes) {
      for (int v = 0; v < options.variants; ++v) {
        const SeatSpec& s = sec.seat;
        const FurnitureSpec seat = PlaceSeat(
            s.height + (v == 0 ? 0.0 : rng.Uniform(s.height_jitter[0], s.height_jitter[1])),
            s.depth, s.width);
        BodyKey k = SeatedKey(seat, 0.0);
        ApplyEdit(r.key, seat, &k);
        IdleNoise n = NoiseOf(r.noise);
        n.seed = rng.NextU64();
        out.push_back(Build({k, At(k, sec.duration, true)}, n, Meta(r, "sit", v, sec.furniture),
                            fps, {seat}));
      }
    }
  }

  const BedSection& beds = catalog.bed;
  auto next_bed = [&](int v) {
    return BedFor(v == 0 ? beds.height
                         : rng.Uniform(beds.variant_height[0], beds.variant_height[1]));
  };
  if (wanted("lie") || wanted("getup")) {
    for (int v = 0; v < options.variants; ++v) {
      const FurnitureSpec bed = next_bed(v);
      if (wanted("lie")) {
        std::vector<BodyKey> keys = LieDownKeys(bed);
        keys.push_back(At(keys.back(), keys.back().t + beds.lie_hold, true));
        IdleNoise n;
        n.seed = rng.NextU64();
        out.push_back(Build(keys, n, Meta(beds.lie_down, "lie", v, beds.furniture), fps, {bed}));
      }
      if (wanted("getup")) {
        IdleNoise n;
        n.seed = rng.NextU64();
        out.push_back(Build(GetUpFromBedKeys(bed), n, Meta(beds.getup, "getup", v, beds.furniture),
                            fps, {bed}));
      }
    }
  }

  if (wanted("lie")) {
    const LieIdleSection& sec = catalog.lie_idle;
    for (const IdleRecipe& r : sec.recipes) {
      for (int v = 0; v < options.variants; ++v) {
        const FurnitureSpec bed = next_bed(v);
        BodyKey k = SupineKey(bed, 0.0);
        ApplyEdit(r.key, bed, &k);
        IdleNoise n = NoiseOf(r.noise);
        n.seed = rng.NextU64();
        out.push_back(
            Build({k, At(k, sec.duration, true)}, n, Meta(r, "lie", v, sec.furniture), fps, {bed}));
      }
    }
  }

  if (wanted("reach")) {
    const ReachSection& sec = catalog.reach;
    const double j = sec.target_jitter;
    for (const ReachRecipe& r : sec.recipes) {
      const bool left = r.side == "left";
      const double sgn = left ? 1 : -1;
      for (int v = 0; v < options.variants; ++v) {
        // One constructor call as before: the compiler's argument order fixes the draw order.
        const Eigen::Vector3d target(r.target[0] + (v ? rng.Uniform(-j, j) : 0),
                                     sgn * (r.target[1] + (v ? rng.Uniform(-j, j) : 0)),
                                     r.target[2] + (v ? rng.Uniform(-j, j) : 0));
        BodyKey stand = StandingKey(0.0, 0.1);
        HandsAtRest(&stand);
        const int arm = left ? 1 : 0;
        stand.limbs[arm].hint =
            Eigen::Vector3d(sec.rest_hint[0], sgn * sec.rest_hint[1], sec.rest_hint[2]);
        BodyKey reach = stand;
        reach.t = 1.5;
        reach.hold = true;
        reach.limbs[arm].weight = 1;
        reach.limbs[arm].target = target;
        if (r.pelvis_drop) reach.pelvis = Eigen::Vector3d(0, 0, h_stand - *r.pelvis_drop);
        if (r.pelvis_x) reach.pelvis.x() = *r.pelvis_x;
        if (r.pitch_deg) reach.pitch = Deg(*r.pitch_deg);
        SetDofs(r.dofs_deg, 1.0, &reach);
        if (r.hint)
          reach.limbs[arm].hint = Eigen::Vector3d((*r.hint)[0], sgn * (*r.hint)[1], (*r.hint)[2]);
        SetDofs(sec.side_dofs_deg, sgn, &reach);
        BodyKey hold = reach;
        hold.t = 2.6;
        hold.limbs[arm].target += Eigen::Vector3d(0.01, 0, 0.01);
        std::vector<BodyKey> keys = {stand, At(stand, 0.5, true), reach,
                                     hold,  At(stand, 3.7, true), At(stand, 4.3, true)};
        IdleNoise n;
        n.seed = rng.NextU64();
        MotionClip c = Build(keys, n, Meta(r, "reach", v, {}), fps, {});
        c.mutable_meta().params["target_x"] = target.x();
        c.mutable_meta().params["target_y"] = target.y();
        c.mutable_meta().params["target_z"] = target.z();
        out.push_back(std::move(c));
      }
    }
  }
  // Approach composites: walk up, stop, (sit: turn round,) then the sit-down or reach clip;
  // one per such clip (see ApproachSpec).
  const WalkStyle* gait = nullptr;
  for (const WalkRecipe& r : catalog.walk.recipes)
    if (r.name == "walk_normal") gait = &r.gait;
  const size_t n = out.size();
  for (size_t i = 0; gait && i < n; ++i) {
    const MotionMeta& m = out[i].meta();
    const bool sit = wanted("sit") && m.skill == "sit" && m.name.rfind("sit_down", 0) == 0;
    const bool reach = wanted("reach") && m.skill == "reach";
    if (!sit && !reach) continue;
    WalkSpec spec = ApproachSpec(*gait, sit);
    spec.seed = 7 + i;
    MotionClip c = ComposeAfter(GenerateWalk(spec, MotionMeta{}, fps), out[i], kApproachBlendTime);
    MotionMeta& cm = c.mutable_meta();
    if (sit) {
      cm.name = "sit_approach" + m.name.substr(std::string("sit_down").size());
      cm.style = "walk up, turn and sit";
      cm.captions = {"a person walks up to a seat, turns around and sits down",
                     "someone walks over, turns and takes a seat",
                     "walking to a chair and sitting down on it"};
      cm.source = "synthetic composite: walk, turn in place, " + m.name;
    } else {
      cm.name = "reach_approach" + m.name.substr(std::string("reach").size());
      cm.style = "walk up and reach";
      cm.captions = {"a person walks up to something and reaches for it",
                     "someone walks over and stretches out a hand",
                     "walking to a shelf and reaching out"};
      cm.source = "synthetic composite: walk, stop, " + m.name;
    }
    out.push_back(std::move(c));
  }

  // Floor get-ups come last (after the composites, which take nothing from the stream).
  if (wanted("getup")) {
    const FloorGetUpSection& sec = catalog.floor_getup;
    for (const FloorGetUpRecipe& r : sec.recipes) {
      for (int v = 0; v < options.variants; ++v) {
        const double tempo =
            r.tempo * (v == 0 ? 1.0 : rng.Uniform(sec.tempo_scale[0], sec.tempo_scale[1]));
        IdleNoise n;
        n.seed = rng.NextU64();
        MotionClip c = Build(FloorGetUpKeys(r, tempo), n, Meta(r, "getup", v, sec.furniture), fps,
                             {}, /*rest_on_floor=*/true);
        c.mutable_meta().params["floor"] = 1.0;
        out.push_back(std::move(c));
      }
    }
  }
  // Beds of the extra heights come after everything else, so the draws above stay as they were.
  for (double h : beds.extra_heights) {
    const FurnitureSpec bed = BedFor(h);
    const std::string suffix = "_h" + std::to_string(std::lround(100 * h));
    if (wanted("lie")) {
      std::vector<BodyKey> keys = LieDownKeys(bed);
      keys.push_back(At(keys.back(), keys.back().t + beds.lie_hold, true));
      IdleNoise n;
      n.seed = rng.NextU64();
      MotionMeta meta = Meta(beds.lie_down, "lie", 0, beds.furniture);
      meta.name += suffix;
      out.push_back(Build(keys, n, meta, fps, {bed}));
    }
    if (wanted("getup")) {
      IdleNoise n;
      n.seed = rng.NextU64();
      MotionMeta meta = Meta(beds.getup, "getup", 0, beds.furniture);
      meta.name += suffix;
      out.push_back(Build(GetUpFromBedKeys(bed), n, meta, fps, {bed}));
    }
  }
  // Sofa lie-downs last of all, for the same reason.
  const SofaLieSection& sofa = catalog.sofa_lie;
  if (wanted("lie") && !sofa.lie_down.name.empty()) {
    for (double h : sofa.heights) {
      FurnitureSpec seat = PlaceSeat(h, sofa.depth, sofa.width);
      // The character sits down at y = 0 and lies with its head toward +y.
      seat.center_y = -sofa.pelvis_offset;
      std::vector<BodyKey> keys = LieDownKeys(seat);
      keys.push_back(At(keys.back(), keys.back().t + sofa.lie_hold, true));
      IdleNoise n;
      n.seed = rng.NextU64();
      MotionMeta meta = Meta(sofa.lie_down, "lie", 0, sofa.furniture);
      meta.name += "_h" + std::to_string(std::lround(100 * h));
      out.push_back(Build(keys, n, meta, fps, {seat}));
    }
  }
  // Seats of the extra heights after that, so every draw above stays as it was.
  for (const SeatRecipe& r : catalog.seats) {
    for (double h : r.extra_heights) {
      const FurnitureSpec seat = PlaceSeat(h, r.seat.depth, r.seat.width);
      add_seat_clips(r, seat, 0, "_h" + std::to_string(std::lround(100 * h)));
    }
  }
  return out;
}

}  // namespace sims::motion
