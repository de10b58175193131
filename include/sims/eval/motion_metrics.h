// Motion-quality metrics (SIMS §4.3, LINGO §5.1) on recorded motions:
// - penetration: share of body sample points inside scene geometry, mean and max depth;
// - foot sliding: mean horizontal foot speed while the foot is on the floor;
// - FID and APD over per-frame pose features (heading-frame body positions + joint
//   rotations), against reference clips for FID, within the generated set for APD.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sims/humanoid/humanoid.h"
#include "sims/io/motion_record.h"
#include "sims/scene/voxels.h"

namespace sims::eval {

/// Points on the humanoid's collision geoms in each body's frame (axis and surface samples).
std::vector<std::vector<Eigen::Vector3d>> BodySamplePoints(const humanoid::Humanoid& humanoid);

/// Penetration of the recorded bodies into the scene over all frames.
scene::PenetrationStats MotionPenetration(const io::MotionRecord& record,
                                          const scene::SceneOccupancy& occupancy,
                                          const std::vector<std::vector<Eigen::Vector3d>>& samples);

/// Foot sliding: mean horizontal speed (m/s) of a foot between consecutive frames in which it
/// stays below `contact_height` (foot body origin, ≈ 5 cm above the sole when flat).
struct FootSliding {
  double mean_speed = 0;     ///< m/s over contact frame pairs.
  double sliding_ratio = 0;  ///< Share of contact pairs faster than 0.1 m/s.
  int contact_pairs = 0;     ///< Frame pairs counted.
};

/// Adds up FootSliding over foot positions one frame pair at a time (a live rollout).
class FootSlidingMeter {
 public:
  /// Feet whose origin is above `contact_height` (m) in either frame are in the air.
  explicit FootSlidingMeter(double contact_height = 0.08) : contact_height_(contact_height) {}
  /// Counts one foot's move from `a` to `b` over `dt` seconds.
  void Add(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double dt);
  /// Counts both feet over every consecutive frame pair of a recorded motion.
  void AddRecord(const io::MotionRecord& record);
  /// Counts both feet over the frame pairs ending in frames first + 1 .. last (inclusive,
  /// clipped to the record): one keyframe's stretch of a story.
  void AddRecord(const io::MotionRecord& record, int first, int last);
  /// The figures so far.
  FootSliding Result() const;

 private:
  double contact_height_;
  double total_ = 0;
  int fast_ = 0, pairs_ = 0;
};

/// Chatter: the RMS change of PD targets (rad) from one control step to the next, pooled over
/// joints and step pairs.
class ActionRateMeter {
 public:
  /// Counts the move of `n` targets from `before` to `now`.
  void Add(const double* before, const double* now, int n);
  /// RMS change so far (0 before any pair).
  double Rms() const;

 private:
  double sum_sq_ = 0;
  int64_t count_ = 0;
};

/// Foot sliding of a recorded motion.
FootSliding MeasureFootSliding(const io::MotionRecord& record, double contact_height = 0.08);

/// Per-frame pose feature (114 values): 14 body positions relative to the root in the heading
/// frame, and the 72-d joint rotation observation.
Eigen::VectorXd PoseFeature(const io::RecordFrame& frame);

/// Features of every `stride`-th frame of a record as rows.
Eigen::MatrixXd PoseFeatures(const io::MotionRecord& record, int stride = 1);

/// The rows of `parts` one after another (all with the same column count).
Eigen::MatrixXd StackRows(const std::vector<Eigen::MatrixXd>& parts);

/// Fréchet distance between Gaussians fitted to the rows of a and b.
double FrechetDistance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

/// Average pairwise Euclidean distance between rows (all pairs, or `max_pairs` deterministic
/// samples when there are more).
double AveragePairwiseDistance(const Eigen::MatrixXd& rows, int max_pairs = 20000);

}  // namespace sims::eval
