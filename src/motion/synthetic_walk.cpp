// Footstep-driven walking (see synthetic.h). Notation: φ is the gait phase in cycles; the
// left foot strikes at integer φ, the right at φ + 0.5; β is the stance fraction.
#include <algorithm>
#include <cmath>

#include "motion/synthetic_internal.h"
#include "sims/core/error.h"
#include "sims/core/rng.h"
#include "sims/humanoid/features.h"
#include "sims/motion/rotation.h"

namespace sims::motion {

using namespace synth;

namespace {

// Speed/turn profile: smoothstep between keys, constant outside.
double KeyValue(const std::vector<WalkKey>& keys, double t, double WalkKey::*field) {
  if (t <= keys.front().t) return keys.front().*field;
  if (t >= keys.back().t) return keys.back().*field;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    if (t > keys[i + 1].t) continue;
    const double s = SmoothStep((t - keys[i].t) / std::max(keys[i + 1].t - keys[i].t, 1e-9));
    return keys[i].*field + (keys[i + 1].*field - keys[i].*field) * s;
  }
  return keys.back().*field;
}

struct Path {
  double t0 = 0, dt = 1.0 / 240;
  std::vector<double> psi, x, y, v, w;
  void At(double t, Eigen::Vector2d* p, double* heading) const {
    const double f = std::clamp((t - t0) / dt, 0.0, static_cast<double>(psi.size() - 1));
    const int i = std::min(static_cast<int>(f), static_cast<int>(psi.size()) - 2);
    const double a = f - i;
    *p = Eigen::Vector2d((1 - a) * x[i] + a * x[i + 1], (1 - a) * y[i] + a * y[i + 1]);
    *heading = (1 - a) * psi[i] + a * psi[i + 1];
  }
  double Speed(double t) const { return v[Index(t)]; }
  double TurnRate(double t) const { return w[Index(t)]; }
  int Index(double t) const {
    return std::clamp(static_cast<int>(std::lround((t - t0) / dt)), 0,
                      static_cast<int>(psi.size()) - 1);
  }
};

struct Foothold {
  Eigen::Vector3d flat;  // ankle position with the foot flat
  double yaw = 0;
};

}  // namespace

MotionClip GenerateWalk(const WalkSpec& spec, const MotionMeta& meta_in, double fps) {
  SIMS_CHECK(!spec.keys.empty() && spec.duration > 0 && fps > 0);
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  const FootGeometry foot = FootOf(skel);
  const WalkStyle& st = spec.style;
  Rng rng(spec.seed);
  double ph[8];
  for (double& p : ph) p = rng.Uniform(0, 2 * M_PI);
  const double drunk = st.drunk;

  // Root path on a fine grid, integrated outwards from the origin at t = 0.
  const double pad = 3.0;
  Path path;
  path.t0 = -pad;
  const int np = static_cast<int>(std::ceil((spec.duration + 2 * pad) / path.dt)) + 1;
  path.psi.assign(np, 0), path.x.assign(np, 0), path.y.assign(np, 0), path.v.assign(np, 0),
      path.w.assign(np, 0);
  for (int i = 0; i < np; ++i) {
    const double t = path.t0 + i * path.dt;
    double v = KeyValue(spec.keys, t, &WalkKey::speed);
    double w = KeyValue(spec.keys, t, &WalkKey::yaw_rate);
    if (drunk > 0) {
      const double moving = std::min(1.0, v / 0.3);
      w += moving * drunk * (0.35 * std::sin(0.8 * t + ph[0]) + 0.2 * std::sin(1.9 * t + ph[1]));
      v *= 1 + 0.15 * drunk * std::sin(1.3 * t + ph[2]);
    }
    path.v[i] = v, path.w[i] = w;
  }
  const int i0 = path.Index(0.0);
  for (int i = i0 + 1; i < np; ++i) {
    path.psi[i] = path.psi[i - 1] + path.dt * 0.5 * (path.w[i] + path.w[i - 1]);
    const double vm = 0.5 * (path.v[i] + path.v[i - 1]), pm = 0.5 * (path.psi[i] + path.psi[i - 1]);
    path.x[i] = path.x[i - 1] + path.dt * vm * std::cos(pm);
    path.y[i] = path.y[i - 1] + path.dt * vm * std::sin(pm);
  }
  for (int i = i0 - 1; i >= 0; --i) {
    path.psi[i] = path.psi[i + 1] - path.dt * 0.5 * (path.w[i] + path.w[i + 1]);
    const double vm = 0.5 * (path.v[i] + path.v[i + 1]), pm = 0.5 * (path.psi[i] + path.psi[i + 1]);
    path.x[i] = path.x[i + 1] - path.dt * vm * std::cos(pm);
    path.y[i] = path.y[i + 1] - path.dt * vm * std::sin(pm);
  }

  // Cadence from the fastest key speed; a longer stride at the same speed lowers it.
  double v_ref = 0.3;
  for (const WalkKey& k : spec.keys) v_ref = std::max(v_ref, k.speed);
  const double f_step =
      std::clamp(1.45 + 0.45 * v_ref, 1.3, 2.4) * st.cadence_scale / st.stride_scale;
  const double T = 2.0 / f_step;                                            // stride period
  const double beta = std::clamp(0.62 - 0.04 * (v_ref - 1.0), 0.56, 0.68);  // stance fraction
  auto phase = [&](double t) { return t / T + spec.phase; };
  const double sign[2] = {-1.0, 1.0};   // right, left
  const double offset[2] = {0.5, 0.0};  // phase of heel strike

  auto foothold = [&](int side, long k) {
    const double tc = (k + offset[side] - spec.phase) * T;
    const double tm = tc + 0.5 * beta * T;
    Eigen::Vector2d p;
    double psi;
    path.At(tm, &p, &psi);
    // Turning on the spot needs a wider stance so the pivoting feet stay clear of each other.
    double width = st.step_width + 0.05 * std::clamp(std::abs(path.TurnRate(tm)) / 1.0, 0.0, 1.0) *
                                       (1.0 - std::clamp(path.Speed(tm) / 0.5, 0.0, 1.0));
    if (drunk > 0) {
      Rng r(spec.seed * 1000003ULL + static_cast<uint64_t>(2 * (k + 1000) + side));
      width += drunk * r.Uniform(-0.03, 0.06);
      psi += drunk * Deg(r.Uniform(-8, 8));
    }
    Foothold h;
    const Eigen::Vector2d lat = Eigen::Vector2d(-std::sin(psi), std::cos(psi)) * sign[side] * width;
    h.flat = Eigen::Vector3d(p.x() + lat.x(), p.y() + lat.y(), foot.ankle_height);
    h.yaw = psi + sign[side] * Deg(st.toe_out_deg);
    return h;
  };
  // Step amplitude 0..1 between two footholds (zero when standing still).
  auto step_amount = [&](const Foothold& a, const Foothold& b) {
    const double d = (b.flat - a.flat).head<2>().norm() + 0.25 * std::abs(WrapAngle(b.yaw - a.yaw));
    return std::clamp(d / 0.22, 0.0, 1.0);
  };
  const double hs = Deg(st.heel_strike_deg), to = Deg(st.toe_off_deg), tip = Deg(st.tiptoe_deg);
  const double u_hs = 0.1, u_to = 0.2;

  // Ankle target and orientation of one foot at time t.
  auto foot_at = [&](int side, double t, Eigen::Vector3d* ankle, Eigen::Quaterniond* rot) {
    const double c = phase(t) - offset[side];
    const long k = static_cast<long>(std::floor(c));
    const double u = c - k;
    const Foothold prev = foothold(side, k - 1), cur = foothold(side, k),
                   next = foothold(side, k + 1);
    const double g_in = step_amount(prev, cur), g_out = step_amount(cur, next);
    const double stance_pitch = st.tiptoe ? tip : 0.0;
    const double strike = st.tiptoe ? tip : -hs * g_in;
    const double lift_off = st.tiptoe ? tip + 0.4 * to * g_out : to * g_out;
    double pitch, yaw;
    Eigen::Vector3d a;
    if (u < beta) {
      pitch = stance_pitch;
      if (u < u_hs) pitch = strike + (stance_pitch - strike) * SmoothStep(u / u_hs);
      if (u > beta - u_to)
        pitch = stance_pitch + (lift_off - stance_pitch) * SmoothStep((u - (beta - u_to)) / u_to);
      yaw = cur.yaw;
      a = PivotAnkle(foot, cur.flat, yaw, pitch);
    } else {
      const double s = (u - beta) / (1 - beta);
      const double land = st.tiptoe ? tip : -hs * g_out;
      const Eigen::Vector3d a0 = PivotAnkle(foot, cur.flat, cur.yaw, lift_off);
      const Eigen::Vector3d a1 = PivotAnkle(foot, next.flat, next.yaw, land);
      const double m = MinJerk(s);
      a = a0 + (a1 - a0) * m;
      a.z() += st.lift * g_out * std::sin(M_PI * std::pow(s, 0.85));
      pitch = lift_off + (land - lift_off) * SmoothStep(s);
      yaw = cur.yaw + WrapAngle(next.yaw - cur.yaw) * m;
    }
    *rot = FootRotation(yaw, pitch);
    // Keep the whole sole above the floor (toes scuffing at toe-off, heels at strike).
    double lowest = 1e9;
    for (int q = 0; q < 8; ++q) {
      const Eigen::Vector3d sgn((q & 1) ? 1 : -1, (q & 2) ? 1 : -1, (q & 4) ? 1 : -1);
      const Eigen::Vector3d corner =
          skel.foot_box_center[0] + sgn.cwiseProduct(skel.foot_box_half[0]);
      lowest = std::min(lowest, (a + *rot * corner).z());
    }
    if (lowest < 0) a.z() -= lowest;
    *ankle = a;
  };

  const int n = static_cast<int>(std::floor(spec.duration * fps + 1e-6)) + 1;
  std::vector<MotionFrame> frames(n);
  std::vector<std::array<Eigen::Vector3d, 2>> ankles(n);
  std::vector<std::array<Eigen::Quaterniond, 2>> feet(n);
  std::vector<double> bound(n), z(n);
  const double l_max = 0.998 * (skel.thigh_length() + skel.shin_length());
  const double h_stand = skel.standing_root_height();
  std::vector<double> yaw_osc(n), roll(n), pitch(n), act(n), arm_act(n), phases(n);
  for (int f = 0; f < n; ++f) {
    const double t = f / fps;
    const double phi = phase(t);
    phases[f] = phi;
    Eigen::Vector2d p;
    double psi;
    path.At(t, &p, &psi);
    const double v = path.Speed(t), w = path.TurnRate(t);
    act[f] = std::clamp(std::max(v / 0.5, std::abs(w) / 0.7), 0.0, 1.0);
    arm_act[f] = std::clamp(v, 0.0, 1.7) + 0.2 * std::clamp(std::abs(w), 0.0, 1.0);
    const double sway_phase = 2 * M_PI * (phi - 0.5 * beta + 0.25);
    double sway = st.sway * act[f] * std::sin(sway_phase);
    if (drunk > 0) sway += 0.07 * drunk * std::sin(2 * M_PI * t / 2.7 + ph[3]);
    yaw_osc[f] = -Deg(st.pelvis_rot_deg) * act[f] * std::cos(2 * M_PI * phi);
    roll[f] = Deg(st.pelvis_roll_deg) * act[f] * std::sin(sway_phase) +
              drunk * Deg(4) * std::sin(2 * M_PI * t / 2.7 + ph[3]);
    pitch[f] = Deg(3) + Deg(0.6 * st.lean_deg);
    MotionFrame& out = frames[f];
    out.root_rot = YawPitchRoll(psi + yaw_osc[f], pitch[f], roll[f]);
    out.root_pos = Eigen::Vector3d(p.x() - std::sin(psi) * sway, p.y() + std::cos(psi) * sway, 0);
    bound[f] = 1e9;
    for (int side = 0; side < 2; ++side) foot_at(side, t, &ankles[f][side], &feet[f][side]);
    // A swinging foot passes beside the standing one, never through it: where the feet are
    // level (along the path), keep it at least kMinGap to its own side of the other foot.
    for (int side = 0; side < 2; ++side) {
      const double c = phase(t) - offset[side];
      const double u = c - std::floor(c);
      if (u < beta) continue;  // in stance
      const double sw = (u - beta) / (1 - beta);
      constexpr double kMinGap = 0.15;
      const int other = 1 - side;
      const Eigen::Quaterniond R_path = YawQuat(psi);
      Eigen::Vector3d rel = R_path.conjugate() * (ankles[f][side] - ankles[f][other]);
      const double w = SmoothStep(sw / 0.2) * SmoothStep((1 - sw) / 0.2) *
                       SmoothStep((0.3 - std::abs(rel.x())) / 0.1);
      if (sign[side] * rel.y() < kMinGap && w > 0) {
        rel.y() += w * (sign[side] * kMinGap - rel.y());
        ankles[f][side] = ankles[f][other] + R_path * rel;
      }
    }
    for (int side = 0; side < 2; ++side) {
      const int thigh = side == 0 ? humanoid::kRightThigh : humanoid::kLeftThigh;
      const Eigen::Vector3d hip = out.root_pos + out.root_rot * skel.offset[thigh];
      const double dxy2 = (hip - ankles[f][side]).head<2>().squaredNorm();
      const double reach = dxy2 < l_max * l_max ? std::sqrt(l_max * l_max - dxy2) : 0.0;
      bound[f] = std::min(bound[f], ankles[f][side].z() - hip.z() + reach);
    }
    const double bob = st.bounce * act[f] * (std::cos(4 * M_PI * (phi - 0.5 * beta)) - 1);
    z[f] = std::min(h_stand - st.crouch - 0.004 + bob, bound[f]);
  }
  // Smooth the height where the reach bound kinks it, without exceeding the bound.
  const std::vector<double> zs = GaussianSmooth(z, 1.2);
  for (int f = 0; f < n; ++f) frames[f].root_pos.z() = std::min(zs[f], bound[f]);

  for (int f = 0; f < n; ++f) {
    MotionFrame& out = frames[f];
    const double t = f / fps, phi = phases[f];
    DofVector d = DofVector::Zero();
    // Trunk: counter-rotate the shoulders against the pelvis, keep the chest level, lean.
    d[kAbdX] = -0.7 * roll[f];
    d[kAbdY] = Deg(st.lean_deg) + Deg(1.0) * std::sin(2 * M_PI * t / 3.5);
    d[kAbdZ] = -1.5 * yaw_osc[f];
    d[kNeckX] = -0.3 * roll[f];
    d[kNeckY] = Deg(st.head_pitch_deg) - 0.8 * (pitch[f] + d[kAbdY]);
    d[kNeckZ] = 0.5 * yaw_osc[f];
    if (drunk > 0) {
      d[kAbdX] += drunk * Deg(6) * std::sin(2 * M_PI * t / 3.3 + ph[4]);
      d[kNeckX] += drunk * Deg(10) * std::sin(2 * M_PI * t / 2.3 + ph[5]);
      d[kNeckZ] += drunk * Deg(10) * std::sin(2 * M_PI * t / 4.1 + ph[6]);
    }
    // Arms: each swings forward with the opposite leg.
    if (st.hands_behind_back) {
      HandsBehindBack(out.root_pos, out.root_rot, &d);
    } else {
      const double swing = Deg(st.arm_swing_deg) * arm_act[f];
      const double lag = 0.04;
      const double r_fwd = std::cos(2 * M_PI * (phi - lag)),
                   l_fwd = std::cos(2 * M_PI * (phi - 0.5 - lag));
      d[kRShY] = Deg(3) - swing * r_fwd;
      d[kLShY] = Deg(3) - swing * l_fwd;
      const double abduct =
          Deg(st.arm_abduct_deg) + drunk * Deg(8) * (1 + std::sin(2 * M_PI * t / 1.9 + ph[7]));
      d[kRShX] = -abduct;
      d[kLShX] = abduct;
      d[kRShZ] = Deg(8);
      d[kLShZ] = -Deg(8);
      const double eb = Deg(st.elbow_deg), es = Deg(st.elbow_swing_deg) * std::min(arm_act[f], 1.0);
      d[kRElbow] = -(eb + es * std::max(0.0, r_fwd));
      d[kLElbow] = -(eb + es * std::max(0.0, l_fwd));
    }
    // Legs by IK onto the feet; the knee points along the foot.
    for (int side = 0; side < 2; ++side) {
      const Eigen::Vector3d fwd = feet[f][side] * Eigen::Vector3d::UnitX();
      const Eigen::Vector3d knee_dir(fwd.x(), fwd.y(), 0);
      SolveLegIk(skel, side == 1, out.root_pos, out.root_rot, ankles[f][side], feet[f][side],
                 knee_dir, &d);
    }
    ClampToLimits(skel, &d);
    out.dof_pos = d;
  }

  MotionMeta meta = meta_in;
  meta.synthetic = true;
  if (meta.source.empty()) meta.source = "sims-synthetic v1 (procedural, not motion capture)";
  meta.params["speed"] = v_ref;
  meta.params["stride_period"] = T;
  meta.params["step_length"] = v_ref * T / 2;
  double max_turn = 0;
  for (const WalkKey& k : spec.keys) max_turn = std::max(max_turn, std::abs(k.yaw_rate));
  meta.params["max_turn_rate"] = max_turn;
  Eigen::Vector2d end;
  double end_psi;
  path.At(spec.duration, &end, &end_psi);
  meta.params["end_x"] = end.x();
  meta.params["end_y"] = end.y();
  meta.params["end_yaw"] = end_psi;
  return MotionClip(fps, std::move(frames), std::move(meta));
}

}  // namespace sims::motion
