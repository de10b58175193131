// A motion style (emotion) classifier, the project's own style metric (issue 18; none of the
// peers publishes one we can run): window statistics of a motion (speed, sway, turning, posture
// and the mean and spread of every joint angle over 2 s) and a class-balanced softmax
// regression over them, trained on labelled clips. Deterministic (full-batch gradient descent
// from zeros), torch-free.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/motion/motion_clip.h"

namespace sims::eval {

/// Values per window in StyleFeatures().
inline constexpr int kStyleFeatureDim = 9 + 2 * humanoid::kNumDofs;

/// How windows are cut and the classifier is fitted.
struct StyleClassifierOptions {
  double fps = 30.0;           ///< Frame rate motions are resampled to.
  int window_frames = 60;      ///< Frames per window (2 s).
  int stride_frames = 10;      ///< Frames between window starts.
  int skip_frames = 30;        ///< Leading frames ignored when classifying a motion (its start).
  double l2 = 1e-3;            ///< Weight decay of the regression.
  int iterations = 1500;       ///< Full-batch gradient steps.
  double learning_rate = 0.5;  ///< Step size on standardised features.
};

/// Statistics of one window of frames at `fps` (kStyleFeatureDim values): forward speed mean
/// and spread, lateral speed |mean| and spread, |turn rate|, pelvis height mean and spread,
/// pelvis pitch and |roll| in the heading frame, then each joint angle's mean and spread.
Eigen::VectorXd StyleFeatures(const std::vector<motion::MotionFrame>& frames, int begin, int end,
                              double fps);

/// Held-out accuracy of a classifier on labelled clips.
struct StyleAccuracy {
  double accuracy = 0;                      ///< Share of motions classified as their label.
  std::map<std::string, double> per_label;  ///< Label → accuracy.
  std::map<std::string, int> motions;       ///< Label → motions (segments) scored.
  int total = 0;                            ///< Motions (segments) scored.
};

/// Softmax regression from window statistics to a style label.
class StyleClassifier {
 public:
  /// Fits on windows of `clips` labelled by their meta.emotion (each label weighted equally).
  /// Throws sims::Error with fewer than two labels or a clip shorter than one window.
  static StyleClassifier Train(const std::vector<const motion::MotionClip*>& clips,
                               const StyleClassifierOptions& options = {});

  /// Labels, sorted.
  const std::vector<std::string>& labels() const { return labels_; }
  /// Index of `label`, or −1.
  int LabelIndex(const std::string& label) const;
  /// Log-probabilities of the labels for one window's features.
  Eigen::VectorXd LogProbabilities(const Eigen::VectorXd& features) const;
  /// The label of a motion (frames at options.fps): the most likely under all its windows
  /// after the skipped start (summed log-probabilities); −1 when no window fits.
  int Classify(const std::vector<motion::MotionFrame>& frames) const;
  /// Classifies consecutive `segment_frames`-long pieces of each clip (resampled to
  /// options.fps; 0 = the whole clip; no start skipped) against the clip's emotion.
  StyleAccuracy Score(const std::vector<const motion::MotionClip*>& clips,
                      int segment_frames = 0) const;
  /// The options it was trained with.
  const StyleClassifierOptions& options() const { return options_; }

 private:
  int ClassifyFrames(const std::vector<motion::MotionFrame>& frames, int skip) const;

  StyleClassifierOptions options_;
  std::vector<std::string> labels_;
  Eigen::VectorXd mean_, scale_;  // feature standardisation
  Eigen::MatrixXd weights_;       // [labels, features]
  Eigen::VectorXd bias_;
};

/// Whether a clip is a generator variant ("…_v1", "…_v2_mirror"): the held-out half of a
/// synthetic catalogue.
bool IsClipVariant(const motion::MotionMeta& meta);

}  // namespace sims::eval
