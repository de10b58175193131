// The motion record: what a story run produced, frame by frame, in the form every viewer
// reads (DIR/motion.json). Per frame at a fixed rate (30 fps by default): the time, the root
// pose, the 28 hinge angles and the world pose of all 15 bodies (so a viewer needs no
// kinematics); plus one annotation per script keyframe (skill, caption, emotion, furniture,
// the frames it covered, whether it succeeded) and a reference to the scene it ran in.
//
// JSON layout (format "sims-motion-record", version 1; Z-up world, metres, quaternions w x y z):
//   {"format": "sims-motion-record", "version": 1, "title": "...", "fps": 30,
//    "scene": {"name": "house", "source": "house"},
//    "skeleton": {"bodies": [15 names], "parents": [15 ints], "dofs": [28 names],
//                 "up": "z", "units": "m", "quaternion": "wxyz"},
//    "num_frames": N,
//    "frames": [{"t": 0.0, "root_pos": [x,y,z], "root_rot": [w,x,y,z], "dof_pos": [28],
//                "body_pos": [[x,y,z] x 15], "body_rot": [[w,x,y,z] x 15]}, ...],
//    "keyframes": [{"index": 0, "skill": "walk", "caption": "...", "emotion": "sad",
//                   "furniture": "sofa_0", "start_frame": 0, "end_frame": 89,
//                   "success": true, "detail": ""}, ...]}
// end_frame is inclusive; a keyframe the run never reached has start_frame = end_frame = -1.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "sims/humanoid/humanoid.h"
#include "sims/humanoid/state.h"
#include "sims/motion/motion_clip.h"

namespace sims::io {

/// Format tag written into motion.json.
inline constexpr const char* kMotionRecordFormat = "sims-motion-record";
/// Current format version.
inline constexpr int kMotionRecordVersion = 1;

/// One recorded frame.
struct RecordFrame {
  double time = 0;                                                  ///< Seconds since the start.
  Eigen::Vector3d root_pos = {0, 0, humanoid::kDefaultRootHeight};  ///< p_WP (pelvis origin).
  Eigen::Quaterniond root_rot = Eigen::Quaterniond::Identity();     ///< R_WP.
  motion::DofVector dof_pos = motion::DofVector::Zero();            ///< Hinge angles (rad).
  std::array<Eigen::Vector3d, humanoid::kNumBodies> body_pos;       ///< p_WB of the 15 bodies.
  std::array<Eigen::Quaterniond, humanoid::kNumBodies> body_rot;    ///< R_WB of the 15 bodies.
};

/// What happened to one script keyframe.
struct KeyframeAnnotation {
  int index = 0;          ///< Position in the script (0-based).
  std::string skill;      ///< Skill that ran ("walk", "sit", ...).
  std::string caption;    ///< Script caption.
  std::string emotion;    ///< Emotion / style label.
  std::string furniture;  ///< Target object instance or category ("" / "floor" if none).
  int start_frame = -1;   ///< First frame of the keyframe (-1: never reached).
  int end_frame = -1;     ///< Last frame, inclusive (-1: never reached).
  bool success = false;   ///< The skill's success test held.
  std::string detail;     ///< Free text: why it failed, falls, timeouts.

  /// True when the run reached this keyframe.
  bool reached() const { return start_frame >= 0; }
};

/// Which scene the motion ran in.
struct SceneRef {
  std::string name;    ///< Scene name (scene::Scene::name).
  std::string source;  ///< What scene::LoadSceneFile accepts to load it again ("" = unknown).
};

/// A whole recorded motion.
struct MotionRecord {
  std::string title;                          ///< Story title or summary.
  double fps = 30.0;                          ///< Frames per second.
  SceneRef scene;                             ///< Scene reference.
  std::vector<RecordFrame> frames;            ///< Frames at `fps`, frame i at time i / fps.
  std::vector<KeyframeAnnotation> keyframes;  ///< Script keyframes in script order.

  /// Number of frames.
  int num_frames() const { return static_cast<int>(frames.size()); }
  /// (num_frames − 1) / fps, 0 when empty.
  double duration() const;
  /// The keyframe covering frame f (the last one started at or before f), or −1.
  int KeyframeAt(int frame) const;
  /// Throws sims::Error (naming `source`) on inconsistent frames or keyframe ranges.
  void Validate(const std::string& source = "motion record") const;
};

/// Appends frames from simulator poses (bodies through humanoid::ForwardKinematics) and tracks
/// keyframe annotations. Not thread-safe; one builder per story run.
class MotionRecordBuilder {
 public:
  /// `humanoid` supplies the kinematics (the default humanoid when null); frames are assumed
  /// to arrive at `fps`.
  explicit MotionRecordBuilder(std::shared_ptr<const humanoid::Humanoid> humanoid = nullptr,
                               double fps = 30.0);
  ~MotionRecordBuilder();
  MotionRecordBuilder(const MotionRecordBuilder&) = delete;
  MotionRecordBuilder& operator=(const MotionRecordBuilder&) = delete;

  /// Sets the title.
  void SetTitle(const std::string& title);
  /// Sets the scene reference.
  void SetScene(const SceneRef& scene);
  /// Appends a frame at time num_frames() / fps; returns its index.
  int AddFrame(const humanoid::HumanoidPose& pose);
  /// Opens keyframe `annotation` (its start_frame becomes the next frame's index); closes an
  /// open keyframe first with success = false.
  void BeginKeyframe(KeyframeAnnotation annotation);
  /// Closes the open keyframe at the last added frame with its outcome.
  void EndKeyframe(bool success, const std::string& detail = "");
  /// Adds a finished (or never reached) annotation as is.
  void AddKeyframe(const KeyframeAnnotation& annotation);
  /// True while a keyframe is open.
  bool keyframe_open() const { return open_.has_value(); }
  /// Frames so far.
  int num_frames() const { return record_.num_frames(); }
  /// Read access to the record being built.
  const MotionRecord& record() const { return record_; }
  /// Closes an open keyframe (success = false, detail "unfinished"), validates and returns the
  /// record; the builder is empty afterwards.
  MotionRecord Finish();

 private:
  struct Scratch;
  std::shared_ptr<const humanoid::Humanoid> humanoid_;
  std::unique_ptr<Scratch> scratch_;
  MotionRecord record_;
  std::optional<KeyframeAnnotation> open_;
};

/// The record as JSON (the layout above; numbers rounded to 1e-6).
nlohmann::json MotionRecordToJson(const MotionRecord& record);
/// Parses and validates a record; errors name `source` and the field ("frames[3].body_rot").
MotionRecord MotionRecordFromJson(const nlohmann::json& j, const std::string& source);
/// Writes motion.json atomically.
void SaveMotionRecord(const MotionRecord& record, const std::filesystem::path& path);
/// Reads motion.json; errors name the file and the field.
MotionRecord LoadMotionRecord(const std::filesystem::path& path);

/// Reads a motion record, or a motion clip (motion::SaveClip format) converted with
/// RecordFromClip; errors name the file and say which formats were tried.
MotionRecord LoadMotionRecordOrClip(const std::filesystem::path& path);

/// The record's root pose and hinge angles as a motion clip (for BVH export, metrics).
motion::MotionClip RecordToClip(const MotionRecord& record);
/// A record from a clip resampled at `fps` (one keyframe covering the whole clip, labelled
/// from the clip's metadata); handy for rendering library clips.
MotionRecord RecordFromClip(const motion::MotionClip& clip, double fps = 30.0,
                            std::shared_ptr<const humanoid::Humanoid> humanoid = nullptr);

}  // namespace sims::io
