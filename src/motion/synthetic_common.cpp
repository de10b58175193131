#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <spdlog/spdlog.h>

#include "motion/synthetic_internal.h"
#include "sims/core/error.h"
#include "sims/humanoid/features.h"
#include "sims/motion/skeleton.h"

namespace sims::motion {
namespace synth {

FootGeometry FootOf(const HumanoidSkeleton& skel) {
  FootGeometry g;
  const Eigen::Vector3d c = skel.foot_box_center[0], h = skel.foot_box_half[0];
  g.heel = Eigen::Vector3d(c.x() - h.x(), 0, c.z() - h.z());
  g.toe = Eigen::Vector3d(c.x() + h.x(), 0, c.z() - h.z());
  g.ankle_height = skel.ankle_height();
  return g;
}

Eigen::Vector3d PivotAnkle(const FootGeometry& g, const Eigen::Vector3d& flat, double yaw,
                           double pitch) {
  if (pitch == 0) return flat;
  const Eigen::Vector3d& pivot = pitch < 0 ? g.heel : g.toe;
  const Eigen::Vector3d p_world = flat + FootRotation(yaw, 0) * pivot;  // on the floor
  return p_world - FootRotation(yaw, pitch) * pivot;
}

humanoid::StaticGeometry FurnitureGeometry(const std::vector<FurnitureSpec>& boxes) {
  humanoid::StaticGeometry g;
  int k = 0;
  for (const FurnitureSpec& b : boxes) {
    humanoid::StaticGeom s;
    s.name = "furniture_" + std::to_string(k++);
    s.half_size = Eigen::Vector3d(b.depth / 2, b.width / 2, b.height / 2);
    s.X_WG.translation() = Eigen::Vector3d(b.front_x - b.depth / 2, b.center_y, b.height / 2);
    g.geoms.push_back(s);
  }
  return g;
}

Penetration MeasurePenetration(const humanoid::Humanoid& h, mjData* d, const MotionFrame& f) {
  humanoid::HumanoidPose p;
  p.root_pos = f.root_pos;
  p.root_rot = f.root_rot;
  p.dof_pos = f.dof_pos;
  humanoid::WritePose(h, p, d);
  mj_kinematics(h.model(), d);
  mj_comPos(h.model(), d);
  mj_collision(h.model(), d);
  Penetration out;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    if (con.dist >= 0) continue;
    const bool a = h.is_humanoid_geom(con.geom1), b = h.is_humanoid_geom(con.geom2);
    if (a && b) {
      out.self = std::max(out.self, -con.dist);
      if (-con.dist > 0.02)
        spdlog::trace("self penetration {:.3f} between {} and {}", -con.dist,
                      mj_id2name(h.model(), mjOBJ_GEOM, con.geom1),
                      mj_id2name(h.model(), mjOBJ_GEOM, con.geom2));
    } else if (a || b) {
      out.world = std::max(out.world, -con.dist);
      if (-con.dist > 0.02)
        spdlog::trace("penetration {:.3f} between {} and {}", -con.dist,
                      mj_id2name(h.model(), mjOBJ_GEOM, con.geom1),
                      mj_id2name(h.model(), mjOBJ_GEOM, con.geom2));
    }
  }
  return out;
}

double LowestPoint(const humanoid::Humanoid& h, mjData* d, const MotionFrame& f, uint32_t skip) {
  humanoid::HumanoidPose p;
  p.root_pos = f.root_pos;
  p.root_rot = f.root_rot;
  p.dof_pos = f.dof_pos;
  humanoid::WritePose(h, p, d);
  const mjModel* m = h.model();
  mj_kinematics(m, d);
  double lowest = std::numeric_limits<double>::infinity();
  for (int g = 0; g < m->ngeom; ++g) {
    const int body = h.geom_body(g);
    if (body < 0 || (skip >> body) & 1u) continue;
    const double* pos = d->geom_xpos + 3 * g;
    const double* R = d->geom_xmat + 9 * g;  // row-major: R[6..8] = world z of the local axes
    const double* size = m->geom_size + 3 * g;
    double z = pos[2] - m->geom_rbound[g];
    switch (m->geom_type[g]) {
      case mjGEOM_SPHERE:
        z = pos[2] - size[0];
        break;
      case mjGEOM_CAPSULE:
        z = pos[2] - std::abs(R[8]) * size[1] - size[0];
        break;
      case mjGEOM_BOX:
        z = pos[2] - std::abs(R[6]) * size[0] - std::abs(R[7]) * size[1] - std::abs(R[8]) * size[2];
        break;
      default:
        break;
    }
    lowest = std::min(lowest, z);
  }
  return lowest;
}

MotionMeta SyntheticMeta(const std::string& name, const std::string& skill,
                         const std::string& emotion, const std::string& style,
                         std::vector<std::string> captions, std::vector<std::string> furniture) {
  MotionMeta m;
  m.name = name;
  m.skill = skill;
  m.emotion = emotion;
  m.style = style;
  m.captions = std::move(captions);
  m.furniture = std::move(furniture);
  m.synthetic = true;
  m.source = "sims-synthetic v1 (procedural, not motion capture)";
  return m;
}

void HandsBehindBackTargets(const Eigen::Vector3d& root_pos, const Eigen::Quaterniond& root_rot,
                            std::array<Eigen::Vector3d, 2>* targets,
                            std::array<Eigen::Vector3d, 2>* hints) {
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1 : 1;
    (*targets)[side] = root_pos + root_rot * Eigen::Vector3d(-0.17, s * 0.055, 0.09);
    (*hints)[side] = root_rot * Eigen::Vector3d(-0.4, s, -0.2);
  }
}

void HandsBehindBack(const Eigen::Vector3d& root_pos, const Eigen::Quaterniond& root_rot,
                     DofVector* dofs) {
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  SkeletonPose sp;
  SkeletonForwardKinematics(skel, root_pos, root_rot, *dofs, &sp);
  std::array<Eigen::Vector3d, 2> targets, hints;
  HandsBehindBackTargets(root_pos, root_rot, &targets, &hints);
  for (int side = 0; side < 2; ++side)
    SolveArmIk(skel, side == 1, sp.pos[humanoid::kTorso], sp.rot[humanoid::kTorso], targets[side],
               hints[side], dofs);
}

BodyKey StandingKey(double t, double foot_width) {
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  const FootGeometry g = FootOf(s);
  BodyKey k;
  k.t = t;
  k.hold = true;
  k.pelvis = Eigen::Vector3d(0, 0, s.standing_root_height() - 0.006);
  k.dofs[kRShX] = -Deg(6);
  k.dofs[kLShX] = Deg(6);
  k.dofs[kRShZ] = Deg(8);
  k.dofs[kLShZ] = -Deg(8);
  k.dofs[kRElbow] = k.dofs[kLElbow] = -Deg(12);
  for (int leg = 0; leg < 2; ++leg) {
    const double side = leg == 0 ? -1 : 1;
    LimbKey& l = k.limbs[2 + leg];
    l.weight = 1;
    l.target = Eigen::Vector3d(0, side * foot_width, g.ankle_height);
    l.yaw = side * Deg(4);
    l.hint = Eigen::Vector3d(1, side * 0.15, 0);
  }
  return k;
}

namespace {

constexpr int kChannels = 6 + humanoid::kNumDofs + 4 * 9;

Eigen::VectorXd Pack(const BodyKey& k) {
  Eigen::VectorXd v(kChannels);
  v.segment<3>(0) = k.pelvis;
  v[3] = k.yaw, v[4] = k.pitch, v[5] = k.roll;
  v.segment<humanoid::kNumDofs>(6) = k.dofs;
  for (int l = 0; l < 4; ++l) {
    const int o = 6 + humanoid::kNumDofs + 9 * l;
    v[o] = k.limbs[l].weight;
    v.segment<3>(o + 1) = k.limbs[l].target;
    v[o + 4] = k.limbs[l].yaw;
    v[o + 5] = k.limbs[l].pitch;
    v.segment<3>(o + 6) = k.limbs[l].hint;
  }
  return v;
}

}  // namespace

namespace {

struct KeyTrack {
  std::vector<BodyKey> keys;
  std::vector<Eigen::VectorXd> p, m;
};

Eigen::VectorXd Evaluate(const KeyTrack& k, double t) {
  const int nk = static_cast<int>(k.keys.size());
  if (nk == 1 || t <= k.keys[0].t) return k.p[0];
  if (t >= k.keys[nk - 1].t) return k.p[nk - 1];
  int seg = 0;
  while (seg + 1 < nk - 1 && t > k.keys[seg + 1].t) ++seg;
  const double h = k.keys[seg + 1].t - k.keys[seg].t;
  if (h <= 1e-9) return k.p[seg + 1];
  const double s = std::clamp((t - k.keys[seg].t) / h, 0.0, 1.0);
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * k.p[seg] + (s3 - 2 * s2 + s) * h * k.m[seg] +
         (-2 * s3 + 3 * s2) * k.p[seg + 1] + (s3 - s2) * h * k.m[seg + 1];
}

// One frame from interpolated channels, with the pelvis raised by `lift` and, with `rot`,
// that pelvis orientation instead of the interpolated yaw/pitch/roll.
MotionFrame SolveFrame(const Eigen::VectorXd& v, const DofVector& noise_dofs,
                       const Eigen::Vector3d& noise_root, double lift, SolveStats* stats,
                       const Eigen::Quaterniond* rot = nullptr) {
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  MotionFrame out;
  out.root_pos = v.segment<3>(0) + noise_root;
  out.root_pos.z() += lift;
  out.root_rot = rot ? *rot : YawPitchRoll(v[3], v[4], v[5]);
  DofVector dofs = v.segment<humanoid::kNumDofs>(6) + noise_dofs;
  const DofVector base = dofs;
  // Legs first (they do not depend on the arms), then arms from the torso pose.
  for (int leg = 0; leg < 2; ++leg) {
    const int o = 6 + humanoid::kNumDofs + 9 * (2 + leg);
    const double w = std::clamp(v[o], 0.0, 1.0);
    if (w < 1e-6) continue;
    DofVector ik = base;
    const LimbIkResult r =
        SolveLegIk(skel, leg == 1, out.root_pos, out.root_rot, v.segment<3>(o + 1),
                   FootRotation(v[o + 4], v[o + 5]), v.segment<3>(o + 6), &ik);
    if (stats && w > 0.99) stats->leg_error = std::max(stats->leg_error, r.position_error);
    const int hip = leg == 0 ? kRHipX : kLHipX;
    for (int k = hip; k < hip + 7; ++k) dofs[k] = (1 - w) * base[k] + w * ik[k];
  }
  SkeletonPose sp;
  SkeletonForwardKinematics(skel, out.root_pos, out.root_rot, dofs, &sp);
  for (int arm = 0; arm < 2; ++arm) {
    const int o = 6 + humanoid::kNumDofs + 9 * arm;
    const double w = std::clamp(v[o], 0.0, 1.0);
    if (w < 1e-6) continue;
    DofVector ik = dofs;
    // Hand targets rest on the body or furniture, so they rise with the pelvis lift.
    const Eigen::Vector3d target = v.segment<3>(o + 1) + Eigen::Vector3d(0, 0, lift);
    const LimbIkResult r = SolveArmIk(skel, arm == 1, sp.pos[humanoid::kTorso],
                                      sp.rot[humanoid::kTorso], target, v.segment<3>(o + 6), &ik);
    if (stats && w > 0.99) stats->arm_error = std::max(stats->arm_error, r.position_error);
    const int sh = arm == 0 ? kRShX : kLShX;
    for (int k = sh; k < sh + 4; ++k) dofs[k] = (1 - w) * dofs[k] + w * ik[k];
  }
  ClampToLimits(skel, &dofs);
  out.dof_pos = dofs;
  return out;
}

}  // namespace

std::vector<MotionFrame> SolveKeys(const std::vector<BodyKey>& keys, double fps,
                                   const IdleNoise& noise,
                                   const std::vector<FurnitureSpec>* furniture, SolveStats* stats,
                                   bool rest_on_floor) {
  SIMS_CHECK(keys.size() >= 1);
  SIMS_CHECK(!rest_on_floor || (furniture && furniture->empty()));
  KeyTrack track;
  track.keys = keys;
  const int nk = static_cast<int>(keys.size());
  for (int i = 0; i < nk; ++i) track.p.push_back(Pack(keys[i]));
  for (int i = 0; i < nk; ++i) {
    track.m.push_back(Eigen::VectorXd::Zero(kChannels));
    if (i == 0 || i == nk - 1 || keys[i].hold) continue;
    const double dt = keys[i + 1].t - keys[i - 1].t;
    if (dt > 1e-9) track.m[i] = (track.p[i + 1] - track.p[i - 1]) / dt;
    if (!keys[i].monotone) continue;
    const double h0 = keys[i].t - keys[i - 1].t, h1 = keys[i + 1].t - keys[i].t;
    for (int c = 0; c < kChannels; ++c) {
      const double d0 = track.p[i][c] - track.p[i - 1][c], d1 = track.p[i + 1][c] - track.p[i][c];
      double& m = track.m[i][c];
      if (d0 * d1 <= 0 || h0 <= 1e-9 || h1 <= 1e-9) {
        m = 0;
      } else {
        const double limit = 3 * std::min(std::abs(d0) / h0, std::abs(d1) / h1);
        m = std::clamp(m, -limit, limit);
      }
    }
  }
  Rng rng(noise.seed);
  double ph[8];
  for (double& x : ph) x = rng.Uniform(0, 2 * M_PI);

  const double duration = keys.back().t;
  const int n = static_cast<int>(std::floor(duration * fps + 1e-6)) + 1;
  std::vector<Eigen::VectorXd> channels(n);
  std::vector<DofVector> noise_dofs(n, DofVector::Zero());
  std::vector<Eigen::Vector3d> noise_root(n, Eigen::Vector3d::Zero());
  for (int f = 0; f < n; ++f) {
    const double t = f / fps;
    channels[f] = Evaluate(track, t);
    noise_root[f].y() = noise.sway * std::sin(2 * M_PI * t / 5.3 + ph[0]);
    noise_root[f].x() = 0.3 * noise.sway * std::sin(2 * M_PI * t / 7.1 + ph[1]);
    DofVector& d = noise_dofs[f];
    d[kAbdY] = Deg(1.5) * noise.breathing * std::sin(2 * M_PI * t / 4.0 + ph[2]);
    d[kNeckZ] = noise.look * std::sin(2 * M_PI * t / 6.5 + ph[3]);
    d[kNeckY] = 0.3 * noise.look * std::sin(2 * M_PI * t / 4.7 + ph[4]);
    d[kRShY] = noise.fidget * std::sin(2 * M_PI * t / 1.7 + ph[5]);
    d[kLShY] = noise.fidget * std::sin(2 * M_PI * t / 2.1 + ph[6]);
    d[kAbdZ] = 0.5 * noise.fidget * std::sin(2 * M_PI * t / 2.9 + ph[7]);
  }
  // Slerp segments: the pelvis orientation follows the shortest rotation between the keys,
  // timed by a key-index channel splined like the others (so it turns as the body moves).
  std::vector<Eigen::Quaterniond> rot(n);
  std::vector<bool> has_rot(n, false);
  bool any_slerp = false;
  for (const BodyKey& k : keys) any_slerp = any_slerp || k.slerp;
  if (any_slerp && nk > 1) {
    KeyTrack index;
    index.keys = keys;
    for (int i = 0; i < nk; ++i) index.p.push_back(Eigen::VectorXd::Constant(1, i));
    for (int i = 0; i < nk; ++i) {
      index.m.push_back(Eigen::VectorXd::Zero(1));
      if (i == 0 || i == nk - 1 || keys[i].hold) continue;
      const double dt = keys[i + 1].t - keys[i - 1].t;
      if (dt > 1e-9) index.m[i][0] = 2.0 / dt;
    }
    std::vector<Eigen::Quaterniond> q(nk);
    for (int i = 0; i < nk; ++i) q[i] = YawPitchRoll(keys[i].yaw, keys[i].pitch, keys[i].roll);
    for (int f = 0; f < n; ++f) {
      const double t = f / fps;
      if (t <= keys[0].t || t >= keys[nk - 1].t) continue;
      int seg = 0;
      while (seg + 1 < nk - 1 && t > keys[seg + 1].t) ++seg;
      if (!keys[seg].slerp) continue;
      const double s = Evaluate(index, t)[0] - seg;
      rot[f] = q[seg].slerp(s, q[seg + 1]).normalized();
      has_rot[f] = true;
    }
  }
  auto rot_of = [&](int f) { return has_rot[f] ? &rot[f] : nullptr; };

  std::vector<double> lift(n, 0.0);
  if (furniture && rest_on_floor) {
    // Two-sided: raise out of the floor or lower onto it until the lowest point touches.
    const std::shared_ptr<const humanoid::Humanoid> h = HumanoidSkeleton::DefaultHumanoid();
    humanoid::MjDataPtr d = humanoid::MakeData(h->model());
    constexpr double kTolerance = 2e-4;
    auto lowest = [&](int f, double l) {
      return LowestPoint(
          *h, d.get(),
          SolveFrame(channels[f], noise_dofs[f], noise_root[f], l, nullptr, rot_of(f)));
    };
    // Newton steps on the lowest point's height, then (should the limbs' IK make it
    // non-monotonic) only upward steps until nothing is below the floor.
    auto settle = [&](int f, double l) {
      for (int iter = 0; iter < 32; ++iter) {
        const double z = lowest(f, l);
        if (std::abs(z) <= kTolerance || (iter >= 12 && z > 0)) break;
        l -= iter < 12 ? z : std::min(z, -kTolerance);
      }
      return l;
    };
    for (int f = 0; f < n; ++f) lift[f] = settle(f, 0.0);
    // Smoothed (the neighbours' maximum, then a light Gaussian: contact switching from one
    // body part to another leaves kinks), never below the settled height (lower would sink a
    // body part), and settled again where a higher pelvis brings a limb down.
    std::vector<double> env(n);
    for (int f = 0; f < n; ++f)
      env[f] = std::max({lift[std::max(f - 1, 0)], lift[f], lift[std::min(f + 1, n - 1)]});
    const std::vector<double> smooth = GaussianSmooth(env, 1.0);
    for (int f = 0; f < n; ++f)
      if (smooth[f] > lift[f])
        lift[f] = lowest(f, smooth[f]) >= -kTolerance ? smooth[f] : settle(f, smooth[f]);
  } else if (furniture) {
    // The floor-only model is the shared default humanoid; furniture needs its own model.
    const std::shared_ptr<const humanoid::Humanoid> h =
        furniture->empty() ? HumanoidSkeleton::DefaultHumanoid()
                           : std::make_shared<const humanoid::Humanoid>(
                                 humanoid::BuildModel(FurnitureGeometry(*furniture)));
    humanoid::MjDataPtr d = humanoid::MakeData(h->model());
    constexpr double kTolerance = 5e-4;
    for (int f = 0; f < n; ++f) {
      for (int iter = 0; iter < 10; ++iter) {
        const MotionFrame fr =
            SolveFrame(channels[f], noise_dofs[f], noise_root[f], lift[f], nullptr, rot_of(f));
        const double pen = MeasurePenetration(*h, d.get(), fr).world;
        if (pen <= kTolerance) break;
        lift[f] += pen;
      }
    }
    // A smooth envelope above the per-frame lifts (running max, Gaussian, max).
    std::vector<double> env(n);
    for (int f = 0; f < n; ++f) {
      double m = 0;
      for (int k = std::max(0, f - 4); k <= std::min(n - 1, f + 4); ++k) m = std::max(m, lift[k]);
      env[f] = m;
    }
    env = GaussianSmooth(env, 2.0);
    for (int f = 0; f < n; ++f) lift[f] = std::max(env[f], lift[f]);
  }
  std::vector<MotionFrame> frames(n);
  for (int f = 0; f < n; ++f) {
    frames[f] = SolveFrame(channels[f], noise_dofs[f], noise_root[f], lift[f], stats, rot_of(f));
    if (stats) stats->max_lift = std::max(stats->max_lift, lift[f]);
  }
  return frames;
}

}  // namespace synth

ClipQuality MeasureClipQuality(const MotionClip& clip) {
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  const auto h = HumanoidSkeleton::DefaultHumanoid();
  humanoid::MjDataPtr d = humanoid::MakeData(h->model());
  ClipQuality q;
  q.min_sole_height = 1e9;
  std::array<std::array<Eigen::Vector3d, 8>, 2> prev;
  for (int f = 0; f < clip.num_frames(); ++f) {
    const MotionFrame& fr = clip.frame(f);
    for (int i = 0; i < humanoid::kNumDofs; ++i)
      q.max_limit_excess = std::max(
          {q.max_limit_excess, skel.lower[i] - fr.dof_pos[i], fr.dof_pos[i] - skel.upper[i]});
    SkeletonPose sp;
    SkeletonForwardKinematics(skel, fr.root_pos, fr.root_rot, fr.dof_pos, &sp);
    for (int side = 0; side < 2; ++side) {
      const auto corners = FootBoxCorners(skel, sp, side == 1);
      for (int c = 0; c < 8; ++c) {
        q.min_sole_height = std::min(q.min_sole_height, corners[c].z());
        if (f > 0 && corners[c].z() < 0.005 && prev[side][c].z() < 0.005)
          q.max_stance_slide = std::max(q.max_stance_slide,
                                        (corners[c] - prev[side][c]).head<2>().norm() * clip.fps());
      }
      prev[side] = corners;
    }
    const synth::Penetration pen = synth::MeasurePenetration(*h, d.get(), fr);
    q.max_floor_penetration = std::max(q.max_floor_penetration, pen.world);
    q.max_floor_gap = std::max(q.max_floor_gap, synth::LowestPoint(*h, d.get(), fr));
    q.max_self_penetration = std::max(q.max_self_penetration, pen.self);
  }
  return q;
}

}  // namespace sims::motion
