// A humanoid motion clip in the project's own format: per-frame root position, root rotation
// and the 28 hinge angles, a frame rate and labels (captions, skill, emotion, furniture).
// Stored as `<name>.json` (metadata) + `<name>.bin` (float32 frames). Sampling at any time
// gives a humanoid::HumanoidPose with world-frame velocities, so clips feed the environment's
// reference-state init and the AMP demo buffer directly.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sims/core/config.h"
#include "sims/humanoid/state.h"
#include "sims/motion/skeleton.h"

namespace sims::motion {

/// Values per stored frame: root position (3), root quaternion w x y z (4), 28 hinge angles.
inline constexpr int kFrameWidth = 3 + 4 + humanoid::kNumDofs;

/// The nine emotion labels (SIMS): neutral, happy, angry, hurried, tired, sad, stressed,
/// drunk, relaxed.
const std::vector<std::string>& EmotionLabels();
/// Known skill labels: walk, sit, lie, reach, getup, idle, other.
const std::vector<std::string>& SkillLabels();
/// Whether `s` is one of SkillLabels().
bool IsSkillLabel(const std::string& s);
/// Whether `s` is one of EmotionLabels().
bool IsEmotionLabel(const std::string& s);

/// Clip labels and provenance.
struct MotionMeta {
  std::string name;                    ///< Clip name (file stem).
  std::vector<std::string> captions;   ///< Up to 5 synonymous captions.
  std::string skill = "other";         ///< One of SkillLabels().
  std::string emotion = "neutral";     ///< One of EmotionLabels().
  std::string style;                   ///< Free-form style tag ("drunk sway", "legs crossed").
  std::vector<std::string> furniture;  ///< Suitable furniture categories ("chair", "bed", "floor").
  bool synthetic = false;              ///< Procedurally generated, not captured.
  bool mirrored = false;               ///< Left–right mirror of another clip.
  std::string source;                  ///< Origin (BVH path, generator name).
  std::map<std::string, double>
      params;  ///< Numbers such as seat_height; *_y and *_yaw flip when mirrored.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(captions));
    a->Visit(SIMS_NVP(skill));
    a->Visit(SIMS_NVP(emotion));
    a->Visit(SIMS_NVP(style));
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(synthetic));
    a->Visit(SIMS_NVP(mirrored));
    a->Visit(SIMS_NVP(source));
    a->Visit(SIMS_NVP(params));
  }
  /// Throws FieldError for unknown skill/emotion labels or more than 5 captions.
  void Validate() const;
};

/// One stored frame.
struct MotionFrame {
  Eigen::Vector3d root_pos = {0, 0, humanoid::kDefaultRootHeight};  ///< p_WP.
  Eigen::Quaterniond root_rot = Eigen::Quaterniond::Identity();     ///< R_WP.
  DofVector dof_pos = DofVector::Zero();                            ///< Hinge angles (rad).
};

/// A motion clip with precomputed velocities (immutable frames, editable metadata).
class MotionClip {
 public:
  /// An empty clip.
  MotionClip() = default;
  /// A clip of `frames` at `fps` (both validated: fps > 0, at least one frame, finite values).
  MotionClip(double fps, std::vector<MotionFrame> frames, MotionMeta meta = {});

  /// Number of frames.
  int num_frames() const { return static_cast<int>(frames_.size()); }
  /// Frames per second.
  double fps() const { return fps_; }
  /// Length in seconds: (n − 1) / fps.
  double duration() const { return frames_.empty() ? 0.0 : (num_frames() - 1) / fps_; }
  /// Frame i.
  const MotionFrame& frame(int i) const { return frames_[i]; }
  /// All frames.
  const std::vector<MotionFrame>& frames() const { return frames_; }
  /// Labels.
  const MotionMeta& meta() const { return meta_; }
  /// Editable labels.
  MotionMeta& mutable_meta() { return meta_; }

  /// State at frame i (stored velocities).
  humanoid::HumanoidPose FramePose(int i) const;
  /// State at time t (clamped to [0, duration]): lerp/slerp of positions and rotations,
  /// linear blend of the per-frame velocities.
  humanoid::HumanoidPose SamplePose(double t) const;
  /// The clip resampled at `fps` over the same duration.
  MotionClip Resampled(double fps) const;
  /// Frames [begin, end) as a new clip.
  MotionClip Slice(int begin, int end) const;

  /// Root linear velocity at frame i (world, finite differences + Gaussian σ = 2 frames).
  const Eigen::Vector3d& root_lin_vel(int i) const { return root_lin_vel_[i]; }
  /// Root angular velocity at frame i (world, from q_{i+1} q_i⁻¹, Gaussian σ = 2 frames).
  const Eigen::Vector3d& root_ang_vel(int i) const { return root_ang_vel_[i]; }
  /// Hinge velocities at frame i (forward differences).
  const DofVector& dof_vel(int i) const { return dof_vel_[i]; }

 private:
  void ComputeVelocities();

  double fps_ = 30.0;
  std::vector<MotionFrame> frames_;
  MotionMeta meta_;
  std::vector<Eigen::Vector3d> root_lin_vel_, root_ang_vel_;
  std::vector<DofVector> dof_vel_;
};

/// Writes `json_path` (metadata, format tag) and the frames beside it (same stem, .bin),
/// both atomically; the binary is written first so the JSON never points at a missing file.
void SaveClip(const MotionClip& clip, const std::filesystem::path& json_path);

/// Loads a clip written by SaveClip (or a JSON with inline "frames"); errors name the file
/// and the field.
MotionClip LoadClip(const std::filesystem::path& json_path);

/// Smooths a sequence with a Gaussian of `sigma` samples (edges repeat the end values).
std::vector<Eigen::Vector3d> GaussianSmooth(const std::vector<Eigen::Vector3d>& values,
                                            double sigma);
/// Scalar GaussianSmooth (same kernel and edge handling).
std::vector<double> GaussianSmooth(const std::vector<double>& values, double sigma);

/// FK of every frame through MuJoCo (humanoid::ForwardKinematics): body states per frame.
std::vector<humanoid::BodyStates> ClipBodyStates(const MotionClip& clip,
                                                 const humanoid::Humanoid& humanoid);

}  // namespace sims::motion
