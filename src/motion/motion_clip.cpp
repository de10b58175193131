#include "sims/motion/motion_clip.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "sims/core/error.h"
#include "sims/motion/rotation.h"

namespace sims::motion {

namespace fs = std::filesystem;

namespace {

constexpr char kFormat[] = "sims-motion-clip";
constexpr int kVersion = 1;
constexpr char kMagic[8] = {'S', 'I', 'M', 'S', 'C', 'L', 'P', '1'};

std::string Join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
  return out;
}

void PackFrame(const MotionFrame& f, float* out) {
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(f.root_pos[k]);
  out[3] = static_cast<float>(f.root_rot.w());
  out[4] = static_cast<float>(f.root_rot.x());
  out[5] = static_cast<float>(f.root_rot.y());
  out[6] = static_cast<float>(f.root_rot.z());
  for (int k = 0; k < humanoid::kNumDofs; ++k) out[7 + k] = static_cast<float>(f.dof_pos[k]);
}

template <typename T>
MotionFrame UnpackFrame(const T* in) {
  MotionFrame f;
  f.root_pos = Eigen::Vector3d(in[0], in[1], in[2]);
  f.root_rot = Eigen::Quaterniond(in[3], in[4], in[5], in[6]);
  for (int k = 0; k < humanoid::kNumDofs; ++k) f.dof_pos[k] = in[7 + k];
  return f;
}

}  // namespace

const std::vector<std::string>& EmotionLabels() {
  static const std::vector<std::string> labels = {
      "neutral", "happy", "angry", "hurried", "tired", "sad", "stressed", "drunk", "relaxed"};
  return labels;
}

const std::vector<std::string>& SkillLabels() {
  static const std::vector<std::string> labels = {"walk",  "sit",  "lie",  "reach",
                                                  "getup", "idle", "other"};
  return labels;
}

bool IsSkillLabel(const std::string& s) {
  return std::find(SkillLabels().begin(), SkillLabels().end(), s) != SkillLabels().end();
}

bool IsEmotionLabel(const std::string& s) {
  return std::find(EmotionLabels().begin(), EmotionLabels().end(), s) != EmotionLabels().end();
}

void MotionMeta::Validate() const {
  Require(IsSkillLabel(skill), "skill", "one of " + Join(SkillLabels()));
  Require(IsEmotionLabel(emotion), "emotion", "one of " + Join(EmotionLabels()));
  Require(captions.size() <= 5, "captions", "at most 5 captions");
  for (const auto& [k, v] : params) Require(std::isfinite(v), "params." + k, "a finite number");
}

MotionClip::MotionClip(double fps, std::vector<MotionFrame> frames, MotionMeta meta)
    : fps_(fps), frames_(std::move(frames)), meta_(std::move(meta)) {
  if (!(fps_ > 0) || !std::isfinite(fps_))
    ThrowInputError("motion clip '" + meta_.name + "'", "fps", "a positive frame rate",
                    std::to_string(fps_));
  if (frames_.empty())
    ThrowInputError("motion clip '" + meta_.name + "'", "frames", "at least one frame", "0");
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    MotionFrame& f = frames_[i];
    const bool finite = f.root_pos.allFinite() && f.root_rot.coeffs().allFinite() &&
                        f.dof_pos.allFinite() && f.root_rot.norm() > 1e-6;
    if (!finite)
      ThrowInputError("motion clip '" + meta_.name + "'", "frames[" + std::to_string(i) + "]",
                      "finite values and a non-zero quaternion");
    f.root_rot.normalize();
    // Keep consecutive quaternions in one hemisphere so differences and blends are short.
    if (i > 0 && frames_[i - 1].root_rot.dot(f.root_rot) < 0) f.root_rot.coeffs() *= -1.0;
  }
  ComputeVelocities();
}

namespace {

// Shared by the Vector3d and scalar overloads so both use the same kernel and summation order.
template <typename T>
std::vector<T> GaussianSmoothImpl(const std::vector<T>& values, double sigma, const T& zero) {
  const int n = static_cast<int>(values.size());
  if (sigma <= 0 || n <= 1) return values;
  const int radius = static_cast<int>(4.0 * sigma + 0.5);
  std::vector<double> w(2 * radius + 1);
  double sum = 0;
  for (int k = -radius; k <= radius; ++k)
    sum += w[k + radius] = std::exp(-0.5 * k * k / (sigma * sigma));
  for (double& x : w) x /= sum;
  std::vector<T> out(n, zero);
  for (int i = 0; i < n; ++i)
    for (int k = -radius; k <= radius; ++k)
      out[i] += w[k + radius] * values[std::clamp(i + k, 0, n - 1)];
  return out;
}

}  // namespace

std::vector<Eigen::Vector3d> GaussianSmooth(const std::vector<Eigen::Vector3d>& values,
                                            double sigma) {
  return GaussianSmoothImpl<Eigen::Vector3d>(values, sigma, Eigen::Vector3d::Zero());
}

std::vector<double> GaussianSmooth(const std::vector<double>& values, double sigma) {
  return GaussianSmoothImpl<double>(values, sigma, 0.0);
}

void MotionClip::ComputeVelocities() {
  const int n = num_frames();
  root_lin_vel_.assign(n, Eigen::Vector3d::Zero());
  root_ang_vel_.assign(n, Eigen::Vector3d::Zero());
  dof_vel_.assign(n, DofVector::Zero());
  if (n < 2) return;
  // poselib: np.gradient (central, one-sided at the ends) then a Gaussian filter (σ = 2).
  for (int i = 0; i < n; ++i) {
    const int a = std::max(i - 1, 0), b = std::min(i + 1, n - 1);
    root_lin_vel_[i] = (frames_[b].root_pos - frames_[a].root_pos) * fps_ / (b - a);
  }
  root_lin_vel_ = GaussianSmooth(root_lin_vel_, 2.0);
  for (int i = 0; i + 1 < n; ++i) {
    const Eigen::Quaterniond dq = frames_[i + 1].root_rot * frames_[i].root_rot.conjugate();
    root_ang_vel_[i] = QuatToRotationVector(dq) * fps_;
    dof_vel_[i] = (frames_[i + 1].dof_pos - frames_[i].dof_pos) * fps_;
  }
  root_ang_vel_[n - 1] = root_ang_vel_[n - 2];
  dof_vel_[n - 1] = dof_vel_[n - 2];
  root_ang_vel_ = GaussianSmooth(root_ang_vel_, 2.0);
}

humanoid::HumanoidPose MotionClip::FramePose(int i) const {
  SIMS_CHECK(i >= 0 && i < num_frames());
  humanoid::HumanoidPose p;
  p.root_pos = frames_[i].root_pos;
  p.root_rot = frames_[i].root_rot;
  p.dof_pos = frames_[i].dof_pos;
  p.root_lin_vel = root_lin_vel_[i];
  p.root_ang_vel = root_ang_vel_[i];
  p.dof_vel = dof_vel_[i];
  return p;
}

humanoid::HumanoidPose MotionClip::SamplePose(double t) const {
  SIMS_CHECK(!frames_.empty());
  const double f = std::clamp(t, 0.0, duration()) * fps_;
  const int f0 = std::min(static_cast<int>(std::floor(f)), num_frames() - 1);
  const int f1 = std::min(f0 + 1, num_frames() - 1);
  const double a = std::clamp(f - f0, 0.0, 1.0);
  if (f0 == f1 || a < 1e-12) return FramePose(f0);
  const MotionFrame& x = frames_[f0];
  const MotionFrame& y = frames_[f1];
  humanoid::HumanoidPose p;
  p.root_pos = (1 - a) * x.root_pos + a * y.root_pos;
  p.root_rot = x.root_rot.slerp(a, y.root_rot).normalized();
  p.dof_pos = (1 - a) * x.dof_pos + a * y.dof_pos;
  p.root_lin_vel = (1 - a) * root_lin_vel_[f0] + a * root_lin_vel_[f1];
  p.root_ang_vel = (1 - a) * root_ang_vel_[f0] + a * root_ang_vel_[f1];
  p.dof_vel = (1 - a) * dof_vel_[f0] + a * dof_vel_[f1];
  return p;
}

MotionClip MotionClip::Resampled(double fps) const {
  SIMS_CHECK(fps > 0);
  const int n = static_cast<int>(std::floor(duration() * fps + 1e-6)) + 1;
  std::vector<MotionFrame> out(n);
  for (int k = 0; k < n; ++k) {
    const humanoid::HumanoidPose p = SamplePose(k / fps);
    out[k].root_pos = p.root_pos;
    out[k].root_rot = p.root_rot;
    out[k].dof_pos = p.dof_pos;
  }
  return MotionClip(fps, std::move(out), meta_);
}

MotionClip MotionClip::Slice(int begin, int end) const {
  SIMS_CHECK(0 <= begin && begin < end && end <= num_frames());
  return MotionClip(fps_, std::vector<MotionFrame>(frames_.begin() + begin, frames_.begin() + end),
                    meta_);
}

void SaveClip(const MotionClip& clip, const fs::path& json_path) {
  SIMS_CHECK(clip.num_frames() > 0);
  fs::path bin_path = json_path;
  bin_path.replace_extension(".bin");
  std::string bin(sizeof(kMagic) + 8 + sizeof(float) * kFrameWidth * clip.num_frames(), '\0');
  std::memcpy(bin.data(), kMagic, sizeof(kMagic));
  const uint32_t header[2] = {static_cast<uint32_t>(clip.num_frames()),
                              static_cast<uint32_t>(kFrameWidth)};
  std::memcpy(bin.data() + sizeof(kMagic), header, sizeof(header));
  std::vector<float> row(kFrameWidth);
  for (int i = 0; i < clip.num_frames(); ++i) {
    PackFrame(clip.frame(i), row.data());
    std::memcpy(bin.data() + sizeof(kMagic) + 8 + sizeof(float) * kFrameWidth * i, row.data(),
                sizeof(float) * kFrameWidth);
  }
  WriteFileAtomic(bin_path, bin);

  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["fps"] = clip.fps();
  j["num_frames"] = clip.num_frames();
  j["duration"] = clip.duration();
  j["data"] = bin_path.filename().string();
  j["frame_layout"] = "float32 little-endian rows: root_pos xyz, root_rot wxyz, dof_pos[28]";
  j["dof_names"] = nlohmann::json::array();
  for (const char* n : humanoid::DofNames()) j["dof_names"].push_back(n);
  j["meta"] = ConfigToJson(clip.meta());
  WriteJsonFile(json_path, j);
}

MotionClip LoadClip(const fs::path& json_path) {
  const std::string src = json_path.string();
  const nlohmann::json j = ReadJsonFile(json_path);
  if (!j.is_object()) ThrowInputError(src, "", "a motion clip object");
  if (j.value("format", std::string()) != kFormat)
    ThrowInputError(src, "format", std::string("\"") + kFormat + "\"",
                    j.contains("format") ? j["format"].dump() : "missing");
  if (!j.contains("version") || !j["version"].is_number_integer() ||
      j["version"].get<int>() > kVersion)
    ThrowInputError(src, "version", "an integer <= " + std::to_string(kVersion),
                    j.contains("version") ? j["version"].dump() : "missing");
  if (!j.contains("fps") || !j["fps"].is_number() || !(j["fps"].get<double>() > 0))
    ThrowInputError(src, "fps", "a positive number",
                    j.contains("fps") ? j["fps"].dump() : "missing");
  const double fps = j["fps"].get<double>();
  if (j.contains("dof_names")) {
    std::vector<std::string> names;
    try {
      names = j["dof_names"].get<std::vector<std::string>>();
    } catch (const std::exception&) {
      ThrowInputError(src, "dof_names", "an array of strings");
    }
    bool same = names.size() == humanoid::kNumDofs;
    for (int k = 0; same && k < humanoid::kNumDofs; ++k) same = names[k] == humanoid::DofNames()[k];
    if (!same)
      ThrowInputError(src, "dof_names", "the 28 hinge names of humanoid::DofNames() in order");
  }
  MotionMeta meta;
  if (j.contains("meta")) meta = ConfigFromJson<MotionMeta>(j["meta"], src + " (meta)");

  std::vector<MotionFrame> frames;
  if (j.contains("frames")) {
    const auto& fr = j["frames"];
    if (!fr.is_array()) ThrowInputError(src, "frames", "an array of frames");
    for (std::size_t i = 0; i < fr.size(); ++i) {
      if (!fr[i].is_array() || fr[i].size() != kFrameWidth)
        ThrowInputError(src, "frames[" + std::to_string(i) + "]",
                        "an array of " + std::to_string(kFrameWidth) + " numbers");
      double v[kFrameWidth];
      for (int k = 0; k < kFrameWidth; ++k) {
        if (!fr[i][k].is_number())
          ThrowInputError(src, "frames[" + std::to_string(i) + "][" + std::to_string(k) + "]",
                          "a number", fr[i][k].dump());
        v[k] = fr[i][k].get<double>();
      }
      frames.push_back(UnpackFrame(v));
    }
  } else {
    if (!j.contains("data") || !j["data"].is_string())
      ThrowInputError(src, "data", "the name of the frame file (or inline \"frames\")");
    const fs::path bin_path = json_path.parent_path() / j["data"].get<std::string>();
    std::ifstream in(bin_path, std::ios::binary);
    if (!in) ThrowInputError(bin_path.string(), "", "a readable frame file", "cannot open");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string bin = ss.str();
    if (bin.size() < sizeof(kMagic) + 8 || std::memcmp(bin.data(), kMagic, sizeof(kMagic)) != 0)
      ThrowInputError(bin_path.string(), "header", "the SIMSCLP1 magic", "another file type");
    uint32_t header[2];
    std::memcpy(header, bin.data() + sizeof(kMagic), sizeof(header));
    if (header[1] != kFrameWidth)
      ThrowInputError(bin_path.string(), "width", std::to_string(kFrameWidth) + " values per frame",
                      std::to_string(header[1]));
    const std::size_t need =
        sizeof(kMagic) + 8 + sizeof(float) * kFrameWidth * std::size_t(header[0]);
    if (bin.size() != need)
      ThrowInputError(bin_path.string(), "frames",
                      std::to_string(header[0]) + " frames (" + std::to_string(need) + " bytes)",
                      std::to_string(bin.size()) + " bytes (truncated?)");
    if (j.contains("num_frames") && j["num_frames"] != header[0])
      ThrowInputError(src, "num_frames",
                      std::to_string(header[0]) + " (as in " + bin_path.filename().string() + ")",
                      j["num_frames"].dump());
    frames.resize(header[0]);
    std::vector<float> row(kFrameWidth);
    for (uint32_t i = 0; i < header[0]; ++i) {
      std::memcpy(row.data(), bin.data() + sizeof(kMagic) + 8 + sizeof(float) * kFrameWidth * i,
                  sizeof(float) * kFrameWidth);
      frames[i] = UnpackFrame(row.data());
    }
  }
  if (frames.empty()) ThrowInputError(src, "frames", "at least one frame", "0");
  try {
    return MotionClip(fps, std::move(frames), std::move(meta));
  } catch (const Error& e) {
    throw Error(src + ": " + e.what());
  }
}

std::vector<humanoid::BodyStates> ClipBodyStates(const MotionClip& clip,
                                                 const humanoid::Humanoid& humanoid) {
  humanoid::MjDataPtr data = humanoid::MakeData(humanoid.model());
  std::vector<humanoid::BodyStates> out(clip.num_frames());
  for (int i = 0; i < clip.num_frames(); ++i)
    humanoid::ForwardKinematics(humanoid, clip.FramePose(i), data.get(), &out[i]);
  return out;
}

}  // namespace sims::motion
