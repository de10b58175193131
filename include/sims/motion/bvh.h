// BVH motion files: a reader for any hierarchy and channel order (position channels on any
// joint, End Sites, any frame time), a writer that round-trips what it reads, and forward
// kinematics in the file's own units and axes. A joint's local transform is
// T(offset + position channels) · R(rotation channels composed in the listed order).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sims::motion {

/// One BVH channel.
enum class BvhChannel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

/// Channel name as written in files ("Xrotation").
const char* BvhChannelName(BvhChannel c);

/// One joint of the hierarchy.
struct BvhJoint {
  std::string name;                                  ///< Joint name.
  int parent = -1;                                   ///< Parent joint index (−1 for the root).
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< Offset from the parent (file units).
  std::vector<BvhChannel> channels;                  ///< Channels in file order.
  int channel_start = 0;                             ///< Index of the first channel in a frame row.
  bool has_end_site = false;                         ///< An End Site follows the joint.
  Eigen::Vector3d end_site = Eigen::Vector3d::Zero();  ///< End Site offset.
};

/// A parsed BVH file: hierarchy (parents before children) and frame rows.
struct BvhMotion {
  std::vector<BvhJoint> joints;  ///< Joints in file order.
  double frame_time = 1.0 / 30;  ///< Seconds per frame.
  int num_frames = 0;            ///< Frames.
  std::vector<double> values;    ///< num_frames × num_channels() values, row-major.

  /// Total channels per frame.
  int num_channels() const;
  /// Frames per second.
  double fps() const { return 1.0 / frame_time; }
  /// Index of a joint by exact name, or −1.
  int FindJoint(const std::string& name) const;
  /// Children of joint j.
  std::vector<int> Children(int j) const;
  /// The value row of frame f.
  const double* frame(int f) const {
    return values.data() + static_cast<std::size_t>(f) * num_channels();
  }
};

/// Parses BVH text; `source` names the origin in errors ("file.bvh:LINE: ...").
BvhMotion ParseBvh(const std::string& text, const std::string& source);

/// Reads a BVH file; malformed input throws sims::Error naming the file, line and problem.
BvhMotion ReadBvh(const std::filesystem::path& path);

/// Formats a BVH file (values with up to 9 significant digits).
std::string FormatBvh(const BvhMotion& bvh);

/// Writes a BVH file atomically.
void WriteBvh(const BvhMotion& bvh, const std::filesystem::path& path);

/// Local rotation of joint j at frame f (its rotation channels composed in file order).
Eigen::Quaterniond BvhLocalRotation(const BvhMotion& bvh, int j, int f);

/// Local translation of joint j at frame f (offset + position channels).
Eigen::Vector3d BvhLocalTranslation(const BvhMotion& bvh, int j, int f);

/// Global rotations and positions of all joints at frame f (f = −1: the rest pose, all
/// channels zero).
void BvhGlobalPose(const BvhMotion& bvh, int f, std::vector<Eigen::Quaterniond>* rot,
                   std::vector<Eigen::Vector3d>* pos);

}  // namespace sims::motion
