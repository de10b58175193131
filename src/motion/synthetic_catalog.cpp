// The synthetic catalogue: which clips exist, their keyframes, captions and labels.
#include <algorithm>
#include <cmath>
#include <functional>

#include <spdlog/spdlog.h>
#include "motion/synthetic_internal.h"

#include "sims/core/error.h"
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

// Solves keys above the floor and `furniture` and labels the clip with the furniture.
MotionClip Build(const std::vector<BodyKey>& keys, const IdleNoise& noise, MotionMeta meta,
                 double fps, const std::vector<FurnitureSpec>& furniture) {
  SolveStats stats;
  std::vector<MotionFrame> frames = SolveKeys(keys, fps, noise, &furniture, &stats);
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

MotionClip Reversed(const MotionClip& c, MotionMeta meta) {
  std::vector<MotionFrame> f = c.frames();
  std::reverse(f.begin(), f.end());
  meta.params = c.meta().params;
  return MotionClip(c.fps(), std::move(f), std::move(meta));
}

// ---------------------------------------------------------------------------------------
// Walks.

struct WalkRecipe {
  std::string name, emotion, style;
  std::vector<std::string> captions;
  WalkSpec spec;
};

WalkStyle Style(const std::function<void(WalkStyle&)>& edit) {
  WalkStyle s;
  edit(s);
  return s;
}

std::vector<WalkRecipe> WalkRecipes() {
  std::vector<WalkRecipe> r;
  auto straight = [](double v, double dur = 8.0) {
    WalkSpec s;
    s.duration = dur;
    s.keys = {{0, v, 0}};
    return s;
  };
  const std::pair<double, const char*> speeds[] = {
      {0.6, "slow"}, {0.9, "moderate"}, {1.2, "normal"}, {1.5, "brisk"}};
  for (auto [v, word] : speeds) {
    r.push_back(
        {std::string("walk_") + word,
         "neutral",
         "normal",
         {std::string("a person walks forward at a ") + word + " pace",
          "someone walks straight ahead", std::string("walking forward, ") + word + " speed",
          "a person walks in a straight line"},
         straight(v)});
  }
  for (const char* side : {"left", "right"}) {
    const double sgn = std::string(side) == "left" ? 1 : -1;
    for (auto [rate, word] : {std::pair<double, const char*>{0.35, "gently"}, {0.75, "sharply"}}) {
      WalkSpec s;
      s.duration = 8.0;
      s.keys = {{0, 1.0, 0}, {1.0, 1.0, sgn * rate}, {7.0, 1.0, sgn * rate}, {8.0, 1.0, 0}};
      r.push_back({std::string("walk_turn_") + side + "_" + word,
                   "neutral",
                   "turning",
                   {std::string("a person walks while turning ") + side,
                    std::string("someone walks in a curve to the ") + side,
                    std::string("walking and ") + word + " turning " + side,
                    std::string("a person follows a path that bends ") + side},
                   s});
    }
  }
  {
    WalkSpec s;
    s.duration = 8.0;
    s.keys = {{0, 1.0, 0},       {1.0, 1.0, 0.55},  {3.5, 1.0, 0.55},
              {4.5, 1.0, -0.55}, {7.0, 1.0, -0.55}, {8.0, 1.0, 0}};
    r.push_back({"walk_s_curve",
                 "neutral",
                 "turning",
                 {"a person walks along an s-shaped path", "someone walks weaving left then right",
                  "walking in a winding line"},
                 s});
  }
  for (auto [v, word] : {std::pair<double, const char*>{0.8, "slowly"}, {1.2, "steadily"}}) {
    WalkSpec s;
    s.duration = 7.0;
    s.keys = {{0.0, 0, 0}, {0.8, 0, 0}, {2.0, v, 0}, {4.8, v, 0}, {6.0, 0, 0}, {7.0, 0, 0}};
    r.push_back({std::string("walk_start_stop_") + (v < 1 ? "slow" : "normal"),
                 "neutral",
                 "start stop",
                 {std::string("a person starts walking, walks ") + word + " a few meters and stops",
                  "someone walks forward from standing and comes to a halt",
                  "starting to walk, then stopping", "a person walks to a spot and stops there"},
                 s});
  }
  for (const char* side : {"left", "right"}) {
    const double sgn = std::string(side) == "left" ? 1 : -1;
    for (int deg : {90, 180}) {
      // Turn in place (smooth yaw-rate bump), then walk off and stop.
      const double turn_time = deg == 90 ? 1.6 : 2.8;
      const double peak =
          Deg(deg) / (0.5 * turn_time + 0.5 * turn_time * 0.5);  // bump area ≈ 0.75·peak·T
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
      const std::string turn =
          deg == 90 ? std::string("turns ") + side : std::string("turns around to the ") + side;
      r.push_back({"walk_turn_in_place_" + std::string(side) + "_" + std::to_string(deg),
                   "neutral",
                   "turn in place",
                   {"a person " + turn + " and walks away",
                    "someone " + turn + " on the spot, then walks forward",
                    "standing, " + std::string(deg == 90 ? "turning " : "turning around to the ") +
                        side + " and walking off"},
                   s});
    }
  }
  // Styles.
  r.push_back(
      {"walk_sad_bowed_head",
       "sad",
       "slow with bowed head",
       {"a sad person walks slowly with the head bowed", "walking slowly, head down, looking sad",
        "someone shuffles forward sadly", "a person walks dejectedly with a drooping head"},
       [&] {
         WalkSpec s = straight(0.55);
         s.style = Style([](WalkStyle& w) {
           w.head_pitch_deg = 35, w.lean_deg = 10, w.arm_swing_deg = 8, w.lift = 0.04;
           w.heel_strike_deg = 6, w.toe_off_deg = 18, w.cadence_scale = 0.85, w.sway = 0.015;
           w.elbow_deg = 8, w.elbow_swing_deg = 4;
         });
         return s;
       }()});
  r.push_back({"walk_tired",
               "tired",
               "dragging feet",
               {"a tired person drags their feet while walking", "walking slowly and wearily",
                "someone walks exhausted, slumped forward", "a weary person trudges along"},
               [&] {
                 WalkSpec s = straight(0.6);
                 s.style = Style([](WalkStyle& w) {
                   w.head_pitch_deg = 15, w.lean_deg = 12, w.arm_swing_deg = 6, w.lift = 0.035;
                   w.heel_strike_deg = 4, w.toe_off_deg = 15, w.cadence_scale = 0.85,
                   w.crouch = 0.02;
                   w.elbow_deg = 8, w.elbow_swing_deg = 3, w.sway = 0.025;
                 });
                 return s;
               }()});
  r.push_back(
      {"walk_big_steps",
       "neutral",
       "big steps",
       {"a person walks with big strides", "taking long steps while walking",
        "someone strides forward with long steps", "walking with an exaggerated long stride"},
       [&] {
         WalkSpec s = straight(1.3);
         s.style = Style([](WalkStyle& w) {
           w.stride_scale = 1.3, w.arm_swing_deg = 30, w.lift = 0.09, w.heel_strike_deg = 20;
         });
         return s;
       }()});
  r.push_back({"walk_drunk",
               "drunk",
               "drunk sway",
               {"a drunk person staggers forward", "someone sways from side to side while walking",
                "walking unsteadily like a drunk", "a tipsy person stumbles along"},
               [&] {
                 WalkSpec s = straight(0.7);
                 s.style = Style([](WalkStyle& w) {
                   w.drunk = 1.0, w.step_width = 0.13, w.head_pitch_deg = 10, w.arm_abduct_deg = 14;
                   w.cadence_scale = 0.9, w.lean_deg = 4, w.sway = 0.03;
                 });
                 s.seed = 11;
                 return s;
               }()});
  r.push_back({"walk_hands_behind_back",
               "relaxed",
               "hands behind back",
               {"a person strolls with the hands clasped behind the back",
                "walking leisurely with hands behind the back",
                "someone walks calmly, arms folded behind", "a relaxed stroll, hands behind"},
               [&] {
                 WalkSpec s = straight(0.8);
                 s.style = Style([](WalkStyle& w) { w.hands_behind_back = true, w.lean_deg = 4; });
                 return s;
               }()});
  r.push_back({"walk_tiptoe",
               "stressed",
               "tiptoe",
               {"a person sneaks forward on tiptoe", "walking nervously on the toes",
                "someone tiptoes quietly", "a person creeps along on the balls of the feet"},
               [&] {
                 WalkSpec s = straight(0.5);
                 s.style = Style([](WalkStyle& w) {
                   w.tiptoe = true, w.cadence_scale = 1.1, w.lift = 0.05, w.arm_abduct_deg = 14;
                   w.elbow_deg = 45, w.crouch = 0.01, w.lean_deg = 8, w.arm_swing_deg = 10;
                   w.sway = 0.015;
                 });
                 return s;
               }()});
  r.push_back({"walk_hurried",
               "hurried",
               "hurried fast walk",
               {"a person walks hurriedly", "someone rushes forward quickly",
                "walking fast in a hurry", "a person hurries along with quick steps"},
               [&] {
                 WalkSpec s = straight(1.7);
                 s.style = Style([](WalkStyle& w) {
                   w.cadence_scale = 1.08, w.lean_deg = 7, w.arm_swing_deg = 26, w.elbow_deg = 55;
                   w.elbow_swing_deg = 15;
                 });
                 return s;
               }()});
  r.push_back({"walk_angry",
               "angry",
               "stomping",
               {"an angry person stomps forward", "walking aggressively with heavy steps",
                "someone marches angrily", "a furious person storms ahead"},
               [&] {
                 WalkSpec s = straight(1.4);
                 s.style = Style([](WalkStyle& w) {
                   w.lean_deg = 8, w.heel_strike_deg = 20, w.arm_swing_deg = 28, w.elbow_deg = 40;
                   w.arm_abduct_deg = 12, w.head_pitch_deg = 5, w.lift = 0.09;
                 });
                 return s;
               }()});
  r.push_back({"walk_happy",
               "happy",
               "bouncy",
               {"a happy person walks with a bounce in the step", "someone walks cheerfully",
                "bouncing happily while walking", "a joyful person walks along"},
               [&] {
                 WalkSpec s = straight(1.25);
                 s.style = Style([](WalkStyle& w) {
                   w.bounce = 0.02, w.arm_swing_deg = 32, w.head_pitch_deg = -8, w.lift = 0.09;
                   w.cadence_scale = 1.05, w.lean_deg = 0;
                 });
                 return s;
               }()});
  r.push_back({"walk_relaxed_stroll",
               "relaxed",
               "stroll",
               {"a person strolls in a relaxed way", "someone ambles along leisurely",
                "walking slowly and casually", "a calm, easy stroll"},
               [&] {
                 WalkSpec s = straight(0.85);
                 s.keys = {{0, 0.85, 0}, {2, 0.85, 0.2}, {6, 0.85, 0.2}, {8, 0.85, 0}};
                 s.style =
                     Style([](WalkStyle& w) { w.arm_swing_deg = 16, w.cadence_scale = 0.95; });
                 return s;
               }()});
  return r;
}

// ---------------------------------------------------------------------------------------
// Idles, sits, lies, reaches, get-ups.

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
  k->limbs[0].target = sp.pos[sim::kRightHand];
  k->limbs[1].target = sp.pos[sim::kLeftHand];
}

// A point resting on top of a thigh, `along` from hip to knee (hand sphere clears the capsule).
Eigen::Vector3d OnThigh(const SkeletonPose& sp, bool left, double along) {
  const int thigh = left ? sim::kLeftThigh : sim::kRightThigh;
  const int shin = left ? sim::kLeftShin : sim::kRightShin;
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
  k.pelvis = Eigen::Vector3d(bed.front_x - 0.5, 0.0, bed.height + 0.11);
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
    const int foot = leg == 0 ? sim::kRightFoot : sim::kLeftFoot;
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

}  // namespace

std::vector<MotionClip> GenerateSyntheticClips(const SyntheticOptions& options) {
  ValidateConfig(options, "synthetic options");
  const double fps = options.fps;
  auto wanted = [&](const std::string& skill) {
    return options.skills.empty() ||
           std::find(options.skills.begin(), options.skills.end(), skill) != options.skills.end();
  };
  std::vector<MotionClip> out;
  Rng rng(options.seed);
  const double h_stand = Skel().standing_root_height();

  if (wanted("walk")) {
    for (const WalkRecipe& r : WalkRecipes()) {
      for (int v = 0; v < options.variants; ++v) {
        WalkSpec s = r.spec;
        s.phase = rng.Uniform();
        s.seed = s.seed * 7919 + options.seed * 104729 + v;
        if (v > 0) {
          const double speed = rng.Uniform(0.88, 1.12), turn = rng.Uniform(0.85, 1.15);
          for (WalkKey& k : s.keys) k.speed *= speed, k.yaw_rate *= turn;
          // Later variants drift gently so straight walks also cover slight curves.
          if (r.style != "turning" && r.style != "turn in place" && r.style != "start stop") {
            const double drift = rng.Uniform(-0.15, 0.15);
            for (WalkKey& k : s.keys) k.yaw_rate += drift;
          }
        }
        out.push_back(GenerateWalk(
            s, SyntheticMeta(r.name + Suffix(v), "walk", r.emotion, r.style, r.captions, {"floor"}),
            fps));
      }
    }
  }

  if (wanted("idle")) {
    struct IdleRecipe {
      std::string name, emotion, style;
      std::vector<std::string> captions;
      std::function<void(BodyKey&, IdleNoise&)> edit;
    };
    const std::vector<IdleRecipe> idles = {
        {"idle_stand_neutral",
         "neutral",
         "looking around",
         {"a person stands and looks around", "standing still, glancing around",
          "someone waits in place", "a person stands idle"},
         [](BodyKey&, IdleNoise& n) { n.look = Deg(25), n.sway = 0.015; }},
        {"idle_stand_tired",
         "tired",
         "slouching",
         {"a tired person stands slouched", "standing wearily with drooping shoulders",
          "someone stands exhausted, head hanging"},
         [](BodyKey& k, IdleNoise& n) {
           k.dofs[kAbdY] = Deg(14), k.dofs[kNeckY] = Deg(20), k.pelvis.z() -= 0.01;
           n.sway = 0.02, n.breathing = 2.0;
         }},
        {"idle_stand_relaxed",
         "relaxed",
         "hands behind back",
         {"a person stands relaxed with hands behind the back",
          "standing calmly, hands clasped behind",
          "someone waits patiently, hands behind the back"},
         [](BodyKey& k, IdleNoise& n) {
           std::array<Eigen::Vector3d, 2> targets, hints;
           HandsBehindBackTargets(k.pelvis, YawPitchRoll(k.yaw, k.pitch, k.roll), &targets, &hints);
           for (int arm = 0; arm < 2; ++arm) {
             k.limbs[arm].weight = 1;
             k.limbs[arm].target = targets[arm];
             k.limbs[arm].hint = hints[arm];
           }
           n.look = Deg(15), n.sway = 0.01;
         }},
        {"idle_stand_stressed",
         "stressed",
         "fidgeting",
         {"a stressed person fidgets while standing", "standing nervously, shifting weight",
          "someone waits anxiously, unable to keep still"},
         [](BodyKey&, IdleNoise& n) { n.look = Deg(30), n.sway = 0.03, n.fidget = Deg(8); }},
        {"idle_stand_sad",
         "sad",
         "head down",
         {"a sad person stands with the head down", "standing still, looking down sadly",
          "someone stands dejected, shoulders slumped"},
         [](BodyKey& k, IdleNoise& n) {
           k.dofs[kNeckY] = Deg(35), k.dofs[kAbdY] = Deg(8);
           n.look = Deg(5), n.sway = 0.008;
         }},
    };
    for (const IdleRecipe& r : idles) {
      for (int v = 0; v < options.variants; ++v) {
        BodyKey k = StandingKey(0.0, 0.1 + 0.02 * v);
        IdleNoise n;
        r.edit(k, n);
        n.seed = rng.NextU64();
        std::vector<BodyKey> keys = {k, At(k, 6.0, true)};
        out.push_back(Build(
            keys, n,
            SyntheticMeta(r.name + Suffix(v), "idle", r.emotion, r.style, r.captions, {"floor"}),
            fps, {}));
      }
    }
  }

  if (wanted("sit") || wanted("getup")) {
    struct Seat {
      std::string name, furniture;
      double height;
    };
    const Seat seats[] = {
        {"chair", "chair", 0.44}, {"sofa", "sofa", 0.40}, {"stool", "stool", 0.46}};
    for (const Seat& seat_def : seats) {
      for (int v = 0; v < options.variants; ++v) {
        const FurnitureSpec seat = PlaceSeat(
            seat_def.height + (v == 0 ? 0.0 : rng.Uniform(-0.03, 0.02)),
            seat_def.furniture == "sofa" ? 0.55 : 0.45, seat_def.furniture == "sofa" ? 1.6 : 0.5);
        const std::vector<std::string> furn = {seat_def.furniture,
                                               seat_def.furniture == "sofa" ? "couch" : "armchair"};
        const bool tired = seat_def.furniture == "sofa";
        if (wanted("sit")) {
          MotionClip c = SitDown(
              seat, tired ? 0.7 : 1.0, tired ? 1.8 : 2.2, 1.5,
              SyntheticMeta("sit_down_" + seat_def.name + Suffix(v), "sit",
                            tired ? "tired" : "neutral", tired ? "plopping down" : "controlled",
                            {"a person sits down on the " + seat_def.furniture,
                             std::string(tired ? "someone drops wearily onto the "
                                               : "someone carefully sits on the ") +
                                 seat_def.furniture,
                             "sitting down on a " + seat_def.furniture,
                             "a person lowers themselves onto a seat"},
                            furn),
              fps, rng.NextU64());
          out.push_back(std::move(c));
        }
        if (wanted("getup")) {
          MotionClip down = SitDown(seat, 1.25, 1.9, 0.8, MotionMeta{}, fps, rng.NextU64());
          out.push_back(
              Reversed(down, SyntheticMeta("getup_from_" + seat_def.name + Suffix(v), "getup",
                                           "neutral", "stand up",
                                           {"a person stands up from the " + seat_def.furniture,
                                            "someone gets up from a seat",
                                            "rising from the " + seat_def.furniture + " to stand",
                                            "a person pushes up out of the " + seat_def.furniture},
                                           furn)));
        }
      }
    }
  }

  if (wanted("sit")) {
    struct SitIdle {
      std::string name, emotion, style;
      std::vector<std::string> captions;
      std::function<void(BodyKey&, IdleNoise&)> edit;
    };
    const std::vector<SitIdle> sits = {
        {"sit_idle_upright",
         "neutral",
         "upright",
         {"a person sits upright on a chair", "sitting straight with hands on the thighs",
          "someone sits still and looks around", "a person waits seated"},
         [](BodyKey&, IdleNoise& n) { n.look = Deg(20); }},
        {"sit_idle_lean_back",
         "relaxed",
         "lean back",
         {"a person leans back relaxed in the seat", "sitting comfortably, leaning back",
          "someone lounges in a chair", "a relaxed person reclines while sitting"},
         [](BodyKey& k, IdleNoise& n) {
           k.pelvis.x() -= 0.04;
           k.pitch = -Deg(14), k.dofs[kAbdY] = -Deg(4), k.dofs[kNeckY] = Deg(12);
           const SkeletonPose sp = PoseOf(k);
           HandsTo(&k, OnThigh(sp, false, 0.5), OnThigh(sp, true, 0.5));
           n.look = Deg(12);
         }},
        {"sit_idle_legs_crossed",
         "relaxed",
         "legs crossed",
         {"a person sits with the right leg crossed over the left",
          "sitting cross-legged on a chair", "someone sits with legs crossed",
          "a person crosses the legs while seated"},
         [](BodyKey& k, IdleNoise& n) {
           // Right knee over the left one, right foot hanging beside the left shin.
           k.limbs[3].target.y() = 0.06;
           const SkeletonPose sp = PoseOf(k);
           LimbKey& r = k.limbs[2];
           r.target = sp.pos[sim::kLeftShin] + Eigen::Vector3d(0.05, 0.13, -0.16);
           r.yaw = Deg(20), r.pitch = Deg(25);
           r.hint = Eigen::Vector3d(0.3, 0.4, 1);
           // Hands rest on the crossed thigh.
           const SkeletonPose crossed = PoseOf(k);
           HandsTo(&k, OnThigh(crossed, false, 0.4) + Eigen::Vector3d(0, -0.03, 0),
                   OnThigh(crossed, false, 0.85) + Eigen::Vector3d(0, 0.05, 0));
           n.look = Deg(15);
         }},
        {"sit_idle_hands_on_knees",
         "neutral",
         "hands on knees",
         {"a person sits with the hands on the knees",
          "sitting forward, hands resting on the knees",
          "someone sits attentively with hands on knees"},
         [](BodyKey& k, IdleNoise& n) {
           k.pitch = Deg(10), k.dofs[kAbdY] = Deg(8);
           const SkeletonPose sp = PoseOf(k);
           HandsTo(&k, sp.pos[sim::kRightShin] + Eigen::Vector3d(0.02, 0, 0.09),
                   sp.pos[sim::kLeftShin] + Eigen::Vector3d(0.02, 0, 0.09));
           n.look = Deg(10);
         }},
    };
    for (const SitIdle& r : sits) {
      for (int v = 0; v < options.variants; ++v) {
        const FurnitureSpec seat =
            PlaceSeat(0.44 + (v == 0 ? 0.0 : rng.Uniform(-0.04, 0.02)), 0.45, 0.5);
        BodyKey k = SeatedKey(seat, 0.0);
        IdleNoise n;
        r.edit(k, n);
        n.seed = rng.NextU64();
        out.push_back(Build({k, At(k, 6.0, true)}, n,
                            SyntheticMeta(r.name + Suffix(v), "sit", r.emotion, r.style, r.captions,
                                          {"chair", "sofa", "armchair"}),
                            fps, {seat}));
      }
    }
  }

  if (wanted("lie") || wanted("getup")) {
    for (int v = 0; v < options.variants; ++v) {
      const FurnitureSpec bed = BedFor(v == 0 ? 0.48 : rng.Uniform(0.42, 0.52));
      if (wanted("lie")) {
        std::vector<BodyKey> keys = LieDownKeys(bed);
        keys.push_back(At(keys.back(), keys.back().t + 1.5, true));
        IdleNoise n;
        n.seed = rng.NextU64();
        out.push_back(Build(
            keys, n,
            SyntheticMeta("lie_down_bed" + Suffix(v), "lie", "tired", "lie down",
                          {"a person lies down on the bed", "someone sits on the bed and lies back",
                           "getting into bed and lying down", "a tired person lies down to rest"},
                          {"bed"}),
            fps, {bed}));
      }
      if (wanted("getup")) {
        std::vector<BodyKey> keys = LieDownKeys(bed);
        IdleNoise n;
        n.seed = rng.NextU64();
        MotionClip down = Build(keys, n, MotionMeta{}, fps, {bed});
        out.push_back(Reversed(
            down,
            SyntheticMeta("getup_from_bed" + Suffix(v), "getup", "neutral", "get out of bed",
                          {"a person gets up from the bed", "someone sits up in bed and stands up",
                           "getting out of bed", "a person rises from lying on the bed"},
                          {"bed"})));
      }
    }
  }

  if (wanted("lie")) {
    struct LieIdle {
      std::string name, emotion, style;
      std::vector<std::string> captions;
      std::function<void(BodyKey&, const FurnitureSpec&)> edit;
    };
    const std::vector<LieIdle> lies = {
        {"lie_idle_back",
         "relaxed",
         "on back",
         {"a person lies on the back on the bed", "lying flat on the back, resting",
          "someone rests lying face up", "a person lies still in bed"},
         [](BodyKey&, const FurnitureSpec&) {}},
        {"lie_idle_side",
         "tired",
         "on side",
         {"a person lies on the side on the bed", "lying curled up on one side",
          "someone sleeps on their side", "a person rests lying sideways"},
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
        {"lie_idle_knees_up",
         "relaxed",
         "knees up",
         {"a person lies on the back with the knees up", "lying on the bed with knees bent",
          "someone rests on their back, feet flat on the bed"},
         [](BodyKey& k, const FurnitureSpec& bed) {
           const SkeletonPose sp = PoseOf(k);
           for (int leg = 0; leg < 2; ++leg) {
             const int thigh = leg == 0 ? sim::kRightThigh : sim::kLeftThigh;
             LimbKey& l = k.limbs[2 + leg];
             l.weight = 1;
             l.target = sp.pos[thigh] + Eigen::Vector3d(0, -0.5, 0);
             l.target.z() = bed.height + FootOf(Skel()).ankle_height;
             l.yaw = -Deg(90), l.pitch = 0;
             l.hint = Eigen::Vector3d(0, 0, 1);
           }
         }},
    };
    for (const LieIdle& r : lies) {
      for (int v = 0; v < options.variants; ++v) {
        const FurnitureSpec bed = BedFor(v == 0 ? 0.48 : rng.Uniform(0.42, 0.52));
        BodyKey k = SupineKey(bed, 0.0);
        r.edit(k, bed);
        IdleNoise n;
        n.seed = rng.NextU64();
        n.look = Deg(10);
        out.push_back(
            Build({k, At(k, 6.0, true)}, n,
                  SyntheticMeta(r.name + Suffix(v), "lie", r.emotion, r.style, r.captions, {"bed"}),
                  fps, {bed}));
      }
    }
  }

  if (wanted("reach")) {
    struct Height {
      std::string name;
      double x, z;
    };
    const Height heights[] = {{"low", 0.45, 0.45}, {"medium", 0.5, 1.05}, {"high", 0.32, 1.7}};
    for (const char* side : {"right", "left"}) {
      const bool left = std::string(side) == "left";
      const double sgn = left ? 1 : -1;
      for (const Height& ht : heights) {
        for (int v = 0; v < options.variants; ++v) {
          const Eigen::Vector3d target(ht.x + (v ? rng.Uniform(-0.05, 0.05) : 0),
                                       sgn * (0.25 + (v ? rng.Uniform(-0.05, 0.05) : 0)),
                                       ht.z + (v ? rng.Uniform(-0.05, 0.05) : 0));
          BodyKey stand = StandingKey(0.0, 0.1);
          HandsAtRest(&stand);
          const int arm = left ? 1 : 0;
          stand.limbs[arm].hint = Eigen::Vector3d(-0.2, sgn, -1);
          BodyKey reach = stand;
          reach.t = 1.5;
          reach.hold = true;
          reach.limbs[arm].weight = 1;
          reach.limbs[arm].target = target;
          if (ht.name == "low") {
            reach.pelvis = Eigen::Vector3d(-0.12, 0, h_stand - 0.26);
            reach.pitch = Deg(40), reach.dofs[kAbdY] = Deg(20), reach.dofs[kNeckY] = -Deg(20);
            reach.limbs[arm].hint = Eigen::Vector3d(-0.5, sgn, 0);
          } else if (ht.name == "medium") {
            reach.pelvis.x() = 0.02;
            reach.pitch = Deg(6), reach.dofs[kAbdY] = Deg(4);
          } else {
            reach.pitch = -Deg(3), reach.dofs[kAbdY] = -Deg(4), reach.dofs[kNeckY] = -Deg(25);
            reach.limbs[arm].hint = Eigen::Vector3d(0, sgn, -0.3);
          }
          reach.dofs[kAbdZ] = -sgn * Deg(8);
          reach.dofs[kNeckZ] = sgn * Deg(15);
          BodyKey hold = reach;
          hold.t = 2.6;
          hold.limbs[arm].target += Eigen::Vector3d(0.01, 0, 0.01);
          std::vector<BodyKey> keys = {stand, At(stand, 0.5, true), reach,
                                       hold,  At(stand, 3.7, true), At(stand, 4.3, true)};
          IdleNoise n;
          n.seed = rng.NextU64();
          MotionClip c =
              Build(keys, n,
                    SyntheticMeta(std::string("reach_") + side + "_" + ht.name + Suffix(v), "reach",
                                  "neutral", std::string(side) + " hand " + ht.name,
                                  {std::string("a person reaches ") +
                                       (ht.name == "low"    ? "down"
                                        : ht.name == "high" ? "up"
                                                            : "forward") +
                                       " with the " + side + " hand",
                                   std::string("someone touches something ") +
                                       (ht.name == "low"    ? "low"
                                        : ht.name == "high" ? "high up"
                                                            : "at chest height") +
                                       " with the " + side + " hand",
                                   std::string("reaching out with the ") + side + " arm",
                                   std::string("a person stretches the ") + side +
                                       " hand toward a " + ht.name + " target"},
                                  {ht.name == "low" ? "table" : "shelf", "cabinet"}),
                    fps, {});
          c.mutable_meta().params["target_x"] = target.x();
          c.mutable_meta().params["target_y"] = target.y();
          c.mutable_meta().params["target_z"] = target.z();
          out.push_back(std::move(c));
        }
      }
    }
  }
  return out;
}

}  // namespace sims::motion
