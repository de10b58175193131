#include "sims/motion/retarget.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "sims/core/error.h"
#include "sims/humanoid/features.h"
#include "sims/motion/rotation.h"

namespace sims::motion {

namespace {

constexpr int kRequiredBodies[] = {
    humanoid::kPelvis,    humanoid::kRightThigh, humanoid::kRightShin, humanoid::kRightFoot,
    humanoid::kLeftThigh, humanoid::kLeftShin,   humanoid::kLeftFoot};
// Limb bodies whose rest rotation can be aligned from the bone to their child.
constexpr std::pair<int, int> kLimbChild[] = {{humanoid::kRightUpperArm, humanoid::kRightLowerArm},
                                              {humanoid::kRightLowerArm, humanoid::kRightHand},
                                              {humanoid::kLeftUpperArm, humanoid::kLeftLowerArm},
                                              {humanoid::kLeftLowerArm, humanoid::kLeftHand},
                                              {humanoid::kRightThigh, humanoid::kRightShin},
                                              {humanoid::kRightShin, humanoid::kRightFoot},
                                              {humanoid::kLeftThigh, humanoid::kLeftShin},
                                              {humanoid::kLeftShin, humanoid::kLeftFoot}};

bool ParseAxis(const std::string& s, Eigen::Vector3d* v) {
  if (s.empty() || s.size() > 2) return false;
  double sign = 1;
  char c = s.back();
  if (s.size() == 2) {
    if (s[0] == '-')
      sign = -1;
    else if (s[0] != '+')
      return false;
  }
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (c < 'x' || c > 'z') return false;
  *v = sign * Eigen::Vector3d::Unit(c - 'x');
  return true;
}

std::string Normalized(const std::string& name) {
  std::string s =
      name.substr(name.find_last_of(':') == std::string::npos ? 0 : name.find_last_of(':') + 1);
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

int FindJointFlexible(const BvhMotion& bvh, const std::vector<std::string>& candidates) {
  for (const auto& c : candidates) {
    const int j = bvh.FindJoint(c);
    if (j >= 0) return j;
  }
  // Tolerate namespace prefixes ("mixamorig:Hips") and case differences.
  for (const auto& c : candidates)
    for (std::size_t j = 0; j < bvh.joints.size(); ++j)
      if (Normalized(bvh.joints[j].name) == Normalized(c)) return static_cast<int>(j);
  return -1;
}

// Rotation taking BVH coordinates to humanoid world coordinates (x forward, y left, z up).
Eigen::Matrix3d AxisConversion(const RetargetConfig& c) {
  Eigen::Vector3d up, fwd;
  SIMS_CHECK(ParseAxis(c.up_axis, &up) && ParseAxis(c.forward_axis, &fwd));
  const Eigen::Vector3d left = up.cross(fwd);
  Eigen::Matrix3d a;
  a.row(0) = fwd.transpose();
  a.row(1) = left.transpose();
  a.row(2) = up.transpose();
  return a;
}

std::string FormatDeg(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f", v);
  return buf;
}

}  // namespace

void RetargetJoint::Validate() const {
  Require(!bvh.empty(), "bvh", "at least one BVH joint name");
}

void RetargetConfig::Validate() const {
  Eigen::Vector3d up, fwd;
  Require(ParseAxis(up_axis, &up), "up_axis", "one of x, y, z, -x, -y, -z");
  Require(ParseAxis(forward_axis, &fwd), "forward_axis", "one of x, y, z, -x, -y, -z");
  Require(std::abs(up.dot(fwd)) < 0.5, "forward_axis", "an axis perpendicular to up_axis");
  Require(scale >= 0, "scale", "metres per BVH unit (> 0), or 0 for automatic");
  Require(target_fps >= 0, "target_fps", "a frame rate (> 0), or 0 to keep the source rate");
  Require(
      ground == "percentile" || ground == "clip_min" || ground == "per_frame" || ground == "none",
      "ground", "one of percentile, clip_min, per_frame, none");
  Require(ground_percentile >= 0 && ground_percentile <= 100, "ground_percentile",
          "a percentile between 0 and 100");
  Require(clamp_warning_deg >= 0, "clamp_warning_deg", "a non-negative angle");
  for (const auto& [body, j] : joints) {
    bool known = false;
    for (const char* n : humanoid::BodyNames()) known = known || body == n;
    std::string names;
    for (const char* n : humanoid::BodyNames()) names += std::string(names.empty() ? "" : ", ") + n;
    Require(known, "joints." + body, "a humanoid body name (" + names + ")");
  }
  for (int b : kRequiredBodies)
    Require(joints.count(humanoid::BodyNames()[b]) > 0,
            std::string("joints.") + humanoid::BodyNames()[b],
            "a mapping (pelvis, thighs, shins and feet are required)");
}

RetargetConfig LoadRetargetConfig(const std::filesystem::path& path) {
  return LoadConfig<RetargetConfig>(path);
}

MotionClip RetargetBvh(const BvhMotion& bvh, const RetargetConfig& config,
                       const HumanoidSkeleton& skel, RetargetReport* report_out,
                       const std::string& source) {
  ValidateConfig(config, "retarget map '" + config.name + "'");
  RetargetReport report;
  report.source_fps = bvh.fps();
  report.source_frames = bvh.num_frames;
  SIMS_CHECK(bvh.num_frames > 0 && !bvh.joints.empty());

  // Resolve the map.
  std::array<int, humanoid::kNumBodies> src{};
  src.fill(-1);
  for (const auto& [body, j] : config.joints) {
    const int b = humanoid::BodyByName(body);
    src[b] = FindJointFlexible(bvh, j.bvh);
    if (src[b] < 0) {
      std::string c;
      for (const auto& n : j.bvh) c += (c.empty() ? "" : " or ") + n;
      std::string have;
      for (std::size_t k = 0; k < bvh.joints.size() && k < 40; ++k)
        have += (k ? ", " : "") + bvh.joints[k].name;
      ThrowInputError(source, "joint for humanoid body '" + body + "' (map '" + config.name + "')",
                      "a BVH joint named " + c, "joints " + have);
    }
  }

  const Eigen::Matrix3d A = AxisConversion(config);
  const Eigen::Quaterniond qA(A);
  std::vector<Eigen::Quaterniond> rest_rot, rot;
  std::vector<Eigen::Vector3d> rest_pos, pos;
  BvhGlobalPose(bvh, -1, &rest_rot, &rest_pos);

  // Scale from leg lengths (hip → knee → ankle) unless given.
  double scale = config.scale;
  if (scale <= 0) {
    double bvh_leg = 0;
    for (auto [t, s, f] :
         {std::array<int, 3>{humanoid::kRightThigh, humanoid::kRightShin, humanoid::kRightFoot},
          std::array<int, 3>{humanoid::kLeftThigh, humanoid::kLeftShin, humanoid::kLeftFoot}})
      bvh_leg += (rest_pos[src[s]] - rest_pos[src[t]]).norm() +
                 (rest_pos[src[f]] - rest_pos[src[s]]).norm();
    bvh_leg /= 2;
    if (bvh_leg < 1e-9)
      ThrowInputError(source, "OFFSET", "non-zero leg bone offsets (to derive the scale)", "zero");
    scale = (skel.thigh_length() + skel.shin_length()) / bvh_leg;
  }
  report.scale = scale;

  // Humanoid zero pose, for bone directions.
  SkeletonPose zero;
  SkeletonForwardKinematics(skel, Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                            DofVector::Zero(), &zero);
  // Rest corrections: R_body = A·G_joint·Aᵀ · Q_body.
  std::array<Eigen::Quaterniond, humanoid::kNumBodies> Q;
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    Q[b] = Eigen::Quaterniond::Identity();
    if (src[b] < 0) continue;
    const RetargetJoint& rj = config.joints.at(humanoid::BodyNames()[b]);
    if (rj.auto_align) {
      for (auto [body, child] : kLimbChild) {
        if (body != b || src[child] < 0) continue;
        const Eigen::Vector3d e = zero.pos[child] - zero.pos[b];
        const Eigen::Vector3d d = A * (rest_pos[src[child]] - rest_pos[src[b]]);
        if (e.norm() > 1e-9 && d.norm() > 1e-9)
          Q[b] = Eigen::Quaterniond::FromTwoVectors(e.normalized(), d.normalized());
      }
    }
    const auto& c = rj.rest_correction_deg;
    Q[b] = Q[b] * Eigen::Quaterniond(
                      EulerToMatrix({0, 1, 2}, Eigen::Vector3d(c[0], c[1], c[2]) * (M_PI / 180.0)));
  }

  const int lt = src[humanoid::kLeftThigh], rt = src[humanoid::kRightThigh];
  const Eigen::Vector3d hip_mid_local =
      0.5 * (skel.offset[humanoid::kLeftThigh] + skel.offset[humanoid::kRightThigh]);
  const double warn = config.clamp_warning_deg * M_PI / 180.0;
  std::array<int, humanoid::kNumDofs> clamp_frames{};
  std::array<double, humanoid::kNumDofs> clamp_max{};

  std::vector<MotionFrame> frames(bvh.num_frames);
  DofVector prev = DofVector::Zero();
  for (int f = 0; f < bvh.num_frames; ++f) {
    BvhGlobalPose(bvh, f, &rot, &pos);
    std::array<Eigen::Quaterniond, humanoid::kNumBodies> desired, realized;
    for (int b = 0; b < humanoid::kNumBodies; ++b)
      if (src[b] >= 0) desired[b] = qA * rot[src[b]] * qA.conjugate() * Q[b];
    MotionFrame& out = frames[f];
    out.root_rot = desired[humanoid::kPelvis].normalized();
    out.root_pos = scale * (A * (0.5 * (pos[lt] + pos[rt]))) - out.root_rot * hip_mid_local;
    realized[0] = out.root_rot;
    DofVector dofs = prev;
    for (int b = 1; b < humanoid::kNumBodies; ++b) {
      const int p = skel.parent[b];
      const Eigen::Quaterniond frame0 = realized[p] * skel.rest[b];
      const int j = skel.joint[b];
      if (j < 0) {
        realized[b] = frame0;
        continue;
      }
      const humanoid::JointSpec& js = humanoid::Joints()[j];
      const int o = js.dof_offset;
      const Eigen::Quaterniond local =
          src[b] >= 0 ? frame0.conjugate() * desired[b] : Eigen::Quaterniond::Identity();
      if (js.dof_count == 3) {
        const Eigen::Vector3d p3 = prev.segment<3>(o);
        dofs.segment<3>(o) = DecomposeHingeTriple(local, skel.lower.segment<3>(o),
                                                  skel.upper.segment<3>(o), f > 0 ? &p3 : nullptr);
      } else {
        // Elbows and knees: the hinge angle that best reproduces the child bone direction.
        int child = -1;
        for (int c = 0; c < humanoid::kNumBodies; ++c)
          if (skel.parent[c] == b) child = c;
        dofs[o] =
            ProjectToYHinge(local, child >= 0 ? skel.offset[child] : Eigen::Vector3d(0, 0, -1));
      }
      for (int k = o; k < o + js.dof_count; ++k) {
        const double c = std::clamp(dofs[k], skel.lower[k], skel.upper[k]);
        const double excess = std::abs(c - dofs[k]);
        if (excess > warn) {
          ++clamp_frames[k];
          clamp_max[k] = std::max(clamp_max[k], excess);
        }
        dofs[k] = c;
      }
      realized[b] = frame0 * JointRotation(j, dofs);
    }
    out.dof_pos = dofs;
    prev = dofs;
  }
  for (int k = 0; k < humanoid::kNumDofs; ++k) {
    if (clamp_frames[k] == 0) continue;
    ClampStat& cs = report.clamped[humanoid::DofNames()[k]];
    cs.frames = clamp_frames[k];
    cs.max_deg = clamp_max[k] * 180.0 / M_PI;
    report.warnings.push_back(std::string(humanoid::DofNames()[k]) + " clamped in " +
                              std::to_string(cs.frames) + " frames (max " + FormatDeg(cs.max_deg) +
                              " deg)");
  }

  MotionMeta meta;
  meta.source = source;
  MotionClip clip(bvh.fps(), std::move(frames), meta);
  if (config.target_fps > 0 && std::abs(config.target_fps - bvh.fps()) > 1e-6)
    clip = clip.Resampled(config.target_fps);

  // Ground fix from the foot soles.
  if (config.ground != "none") {
    std::vector<MotionFrame> fr = clip.frames();
    std::vector<double> sole(fr.size());
    SkeletonPose sp;
    double lowest = 1e9;
    // Flat feet only for the percentile: a foot tipped far over (lying, falling) reaches below
    // where the source skeleton's ankle did, and would float the standing frames.
    std::vector<double> flat_soles;
    for (std::size_t i = 0; i < fr.size(); ++i) {
      SkeletonForwardKinematics(skel, fr[i].root_pos, fr[i].root_rot, fr[i].dof_pos, &sp);
      const double foot_sole[2] = {SoleHeight(skel, sp, false), SoleHeight(skel, sp, true)};
      sole[i] = std::min(foot_sole[0], foot_sole[1]);
      lowest = std::min(lowest, sole[i]);
      double flat = 1e9;
      for (bool left : {false, true}) {
        const Eigen::Vector3d up =
            sp.rot[left ? humanoid::kLeftFoot : humanoid::kRightFoot] * Eigen::Vector3d::UnitZ();
        if (up.z() > std::cos(30 * M_PI / 180)) flat = std::min(flat, foot_sole[left]);
      }
      if (flat < 1e9) flat_soles.push_back(flat);
    }
    double level = lowest;
    if (config.ground == "percentile" && !flat_soles.empty()) {
      const std::size_t k =
          std::min(flat_soles.size() - 1,
                   static_cast<std::size_t>(config.ground_percentile / 100.0 * flat_soles.size()));
      std::nth_element(flat_soles.begin(), flat_soles.begin() + k, flat_soles.end());
      level = flat_soles[k];
    }
    for (std::size_t i = 0; i < fr.size(); ++i)
      fr[i].root_pos.z() +=
          (config.ground == "per_frame" ? -sole[i] : -level) + config.ground_offset;
    report.ground_shift = -level + config.ground_offset;
    clip = MotionClip(clip.fps(), std::move(fr), clip.meta());
  } else if (config.ground_offset != 0) {
    std::vector<MotionFrame> fr = clip.frames();
    for (auto& f : fr) f.root_pos.z() += config.ground_offset;
    report.ground_shift = config.ground_offset;
    clip = MotionClip(clip.fps(), std::move(fr), clip.meta());
  }
  if (report_out) *report_out = std::move(report);
  return clip;
}

namespace {

// World (humanoid axes) → BVH axes.
Eigen::Matrix3d ExportAxes(const HumanoidBvhOptions& o) {
  Eigen::Matrix3d p = Eigen::Matrix3d::Identity();
  if (o.y_up) p << 0, 1, 0, 0, 0, 1, 1, 0, 0;  // bvh x = left, y = up, z = forward
  return p;
}

}  // namespace

BvhMotion HumanoidClipToBvh(const MotionClip& clip, const HumanoidSkeleton& skel,
                            const HumanoidBvhOptions& options) {
  SIMS_CHECK(options.scale > 0 && clip.num_frames() > 0);
  const Eigen::Matrix3d P = ExportAxes(options);
  // Channel order so that the humanoid's Rx·Ry·Rz reads as the three file channels.
  const AxisOrder order = options.y_up ? AxisOrder{2, 0, 1} : AxisOrder{0, 1, 2};
  const BvhChannel rot_channels[3] = {BvhChannel::kXrotation, BvhChannel::kYrotation,
                                      BvhChannel::kZrotation};
  BvhMotion bvh;
  bvh.frame_time = 1.0 / clip.fps();
  bvh.num_frames = clip.num_frames();
  int ch = 0;
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    BvhJoint j;
    j.name = humanoid::BodyNames()[b];
    j.parent = skel.parent[b];
    j.offset =
        b == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(options.scale * (P * skel.offset[b]));
    if (b == 0) {
      j.channels = {BvhChannel::kXposition, BvhChannel::kYposition, BvhChannel::kZposition};
    }
    for (int k = 0; k < 3; ++k) j.channels.push_back(rot_channels[order[k]]);
    j.channel_start = ch;
    ch += static_cast<int>(j.channels.size());
    bool leaf = true;
    for (int c = 0; c < humanoid::kNumBodies; ++c) leaf = leaf && skel.parent[c] != b;
    if (leaf) {
      Eigen::Vector3d tip(0, 0, -0.08);  // hands
      if (b == humanoid::kHead) tip = Eigen::Vector3d(0, 0, 0.25);
      if (b == humanoid::kRightFoot || b == humanoid::kLeftFoot) {
        const int side = b == humanoid::kLeftFoot ? 1 : 0;
        tip = skel.foot_box_center[side] +
              Eigen::Vector3d(skel.foot_box_half[side].x(), 0, -skel.foot_box_half[side].z());
      }
      j.has_end_site = true;
      j.end_site = options.scale * (P * tip);
    }
    bvh.joints.push_back(j);
  }
  bvh.values.resize(static_cast<std::size_t>(bvh.num_frames) * ch);
  const double deg = 180.0 / M_PI;
  for (int f = 0; f < clip.num_frames(); ++f) {
    const MotionFrame& fr = clip.frame(f);
    double* row = bvh.values.data() + static_cast<std::size_t>(f) * ch;
    const Eigen::Vector3d p = options.scale * (P * fr.root_pos);
    const Eigen::Vector3d r =
        MatrixToEuler(order, P * fr.root_rot.toRotationMatrix() * P.transpose()) * deg;
    for (int k = 0; k < 3; ++k) row[k] = p[k], row[3 + k] = r[k];
    for (int b = 1; b < humanoid::kNumBodies; ++b) {
      const BvhJoint& j = bvh.joints[b];
      Eigen::Vector3d a = Eigen::Vector3d::Zero();
      const int jt = skel.joint[b];
      const bool identity_rest =
          skel.rest[b].angularDistance(Eigen::Quaterniond::Identity()) < 1e-12;
      if (jt >= 0 && identity_rest) {
        // The hinge angles are the channel values (x, y, z hinges map to the order's axes).
        const humanoid::JointSpec& js = humanoid::Joints()[jt];
        if (js.dof_count == 3)
          a = fr.dof_pos.segment<3>(js.dof_offset);
        else
          a = Eigen::Vector3d(0, fr.dof_pos[js.dof_offset], 0);
      } else if (!identity_rest) {
        Eigen::Quaterniond local = skel.rest[b];
        if (jt >= 0) local = local * JointRotation(jt, fr.dof_pos);
        const Eigen::Vector3d e =
            MatrixToEuler(order, P * local.toRotationMatrix() * P.transpose());
        // MatrixToEuler's angles are about order's axes in BVH frame = hinge x, y, z.
        a = e;
      }
      for (int k = 0; k < 3; ++k) row[j.channel_start + k] = a[k] * deg;
    }
  }
  return bvh;
}

void WriteHumanoidBvh(const MotionClip& clip, const std::filesystem::path& path,
                      const HumanoidBvhOptions& options) {
  WriteBvh(HumanoidClipToBvh(clip, HumanoidSkeleton::Default(), options), path);
}

RetargetConfig HumanoidBvhRetargetConfig(const HumanoidBvhOptions& options) {
  RetargetConfig c;
  c.name = "sims_humanoid";
  c.up_axis = options.y_up ? "y" : "z";
  c.forward_axis = options.y_up ? "z" : "x";
  c.scale = 1.0 / options.scale;
  c.target_fps = 0;
  c.ground = "none";
  for (const char* n : humanoid::BodyNames()) {
    RetargetJoint j;
    j.bvh = {n};
    j.auto_align = false;
    c.joints[n] = j;
  }
  return c;
}

}  // namespace sims::motion
