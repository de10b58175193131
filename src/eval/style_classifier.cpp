#include "sims/eval/style_classifier.h"

#include <algorithm>
#include <cmath>
#include <regex>
#include <set>

#include "sims/core/error.h"
#include "sims/humanoid/features.h"

namespace sims::eval {

namespace {

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

std::vector<motion::MotionFrame> FramesAt(const motion::MotionClip& clip, double fps) {
  if (std::abs(clip.fps() - fps) < 1e-9) return clip.frames();
  return clip.Resampled(fps).frames();
}

// Row-wise log-softmax.
Eigen::MatrixXd LogSoftmax(const Eigen::MatrixXd& logits) {
  Eigen::MatrixXd out = logits;
  for (int r = 0; r < out.rows(); ++r) {
    const double m = out.row(r).maxCoeff();
    const double lse = m + std::log((out.row(r).array() - m).exp().sum());
    out.row(r).array() -= lse;
  }
  return out;
}

}  // namespace

Eigen::VectorXd StyleFeatures(const std::vector<motion::MotionFrame>& frames, int begin, int end,
                              double fps) {
  SIMS_CHECK(begin >= 0 && end <= static_cast<int>(frames.size()) && end - begin >= 2);
  const int n = end - begin;
  // Per-frame signals; velocities from forward differences in the heading frame of the frame.
  Eigen::ArrayXd fwd(n - 1), lat(n - 1), turn(n - 1), z(n), pitch(n), roll(n);
  Eigen::MatrixXd dofs(humanoid::kNumDofs, n);
  for (int k = 0; k < n; ++k) {
    const motion::MotionFrame& f = frames[begin + k];
    const Eigen::Quaterniond h_inv = humanoid::HeadingInverse(f.root_rot);
    if (k + 1 < n) {
      const motion::MotionFrame& g = frames[begin + k + 1];
      const Eigen::Vector3d v = h_inv * ((g.root_pos - f.root_pos) * fps);
      fwd[k] = v.x();
      lat[k] = v.y();
      turn[k] =
          WrapAngle(humanoid::HeadingAngle(g.root_rot) - humanoid::HeadingAngle(f.root_rot)) * fps;
    }
    z[k] = f.root_pos.z();
    // World up seen from the pelvis with its heading removed: tilt forward/back and sideways.
    const Eigen::Vector3d up_P = (h_inv * f.root_rot).conjugate() * Eigen::Vector3d::UnitZ();
    pitch[k] = up_P.x();
    roll[k] = up_P.y();
    dofs.col(k) = f.dof_pos;
  }
  auto stddev = [](const Eigen::ArrayXd& a) {
    return std::sqrt(std::max(0.0, (a - a.mean()).square().mean()));
  };
  Eigen::VectorXd out(kStyleFeatureDim);
  int i = 0;
  out[i++] = fwd.mean();
  out[i++] = stddev(fwd);
  out[i++] = std::abs(lat.mean());  // |…| and spreads: a mirrored motion has the same values
  out[i++] = stddev(lat);
  out[i++] = turn.abs().mean();
  out[i++] = z.mean();
  out[i++] = stddev(z);
  out[i++] = pitch.mean();
  out[i++] = std::abs(roll.mean());
  for (int d = 0; d < humanoid::kNumDofs; ++d) {
    const Eigen::ArrayXd a = dofs.row(d).transpose().array();
    out[i++] = a.mean();
    out[i++] = stddev(a);
  }
  SIMS_CHECK(i == kStyleFeatureDim);
  return out;
}

bool IsClipVariant(const motion::MotionMeta& meta) {
  static const std::regex variant(".*_v[0-9]+(_mirror)?");
  return std::regex_match(meta.name, variant);
}

StyleClassifier StyleClassifier::Train(const std::vector<const motion::MotionClip*>& clips,
                                       const StyleClassifierOptions& options) {
  if (options.window_frames < 2 || options.stride_frames < 1 || options.skip_frames < 0 ||
      !(options.fps > 0) || options.iterations < 1 || !(options.learning_rate > 0))
    throw Error("style classifier: invalid options");
  StyleClassifier c;
  c.options_ = options;
  std::set<std::string> labels;
  for (const auto* clip : clips) labels.insert(clip->meta().emotion);
  c.labels_.assign(labels.begin(), labels.end());
  if (c.labels_.size() < 2)
    throw Error("style classifier: needs clips of at least two emotions, got " +
                std::to_string(c.labels_.size()));

  // Windows of every clip, labelled.
  std::vector<Eigen::VectorXd> rows;
  std::vector<int> y;
  for (const auto* clip : clips) {
    const auto frames = FramesAt(*clip, options.fps);
    const int n = static_cast<int>(frames.size());
    if (n < options.window_frames)
      throw Error("style classifier: clip '" + clip->meta().name + "' has " + std::to_string(n) +
                  " frames, fewer than one window (" + std::to_string(options.window_frames) + ")");
    for (int b = 0; b + options.window_frames <= n; b += options.stride_frames) {
      rows.push_back(StyleFeatures(frames, b, b + options.window_frames, options.fps));
      y.push_back(c.LabelIndex(clip->meta().emotion));
    }
  }
  const int N = static_cast<int>(rows.size()), D = kStyleFeatureDim,
            C = static_cast<int>(c.labels_.size());
  Eigen::MatrixXd X(N, D);
  for (int r = 0; r < N; ++r) X.row(r) = rows[r].transpose();
  c.mean_ = X.colwise().mean().transpose();
  c.scale_ = ((X.rowwise() - c.mean_.transpose()).array().square().colwise().mean().sqrt())
                 .transpose()
                 .matrix();
  for (int d = 0; d < D; ++d) c.scale_[d] = c.scale_[d] > 1e-6 ? c.scale_[d] : 1.0;
  X = (X.rowwise() - c.mean_.transpose()).array().rowwise() / c.scale_.transpose().array();

  // Class-balanced targets: each label carries the same total weight.
  std::vector<int> count(C, 0);
  for (int l : y) ++count[l];
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(N, C);
  Eigen::VectorXd w(N);
  for (int r = 0; r < N; ++r) {
    T(r, y[r]) = 1.0;
    w[r] = 1.0 / (C * count[y[r]]);
  }
  c.weights_ = Eigen::MatrixXd::Zero(C, D);
  c.bias_ = Eigen::VectorXd::Zero(C);
  for (int it = 0; it < options.iterations; ++it) {
    Eigen::MatrixXd logits = X * c.weights_.transpose();
    logits.rowwise() += c.bias_.transpose();
    const Eigen::MatrixXd P = LogSoftmax(logits).array().exp();
    const Eigen::MatrixXd G = (P - T).array().colwise() * w.array();  // d loss / d logits
    c.weights_ -= options.learning_rate * (G.transpose() * X + options.l2 * c.weights_);
    c.bias_ -= options.learning_rate * G.colwise().sum().transpose();
  }
  return c;
}

int StyleClassifier::LabelIndex(const std::string& label) const {
  const auto it = std::find(labels_.begin(), labels_.end(), label);
  return it == labels_.end() ? -1 : static_cast<int>(it - labels_.begin());
}

Eigen::VectorXd StyleClassifier::LogProbabilities(const Eigen::VectorXd& features) const {
  const Eigen::VectorXd x = (features - mean_).cwiseQuotient(scale_);
  const Eigen::MatrixXd logits = (weights_ * x + bias_).transpose();
  return LogSoftmax(logits).transpose();
}

int StyleClassifier::ClassifyFrames(const std::vector<motion::MotionFrame>& frames,
                                    int skip) const {
  const int n = static_cast<int>(frames.size());
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(static_cast<int>(labels_.size()));
  int windows = 0;
  for (int b = skip; b + options_.window_frames <= n; b += options_.stride_frames, ++windows)
    sum += LogProbabilities(StyleFeatures(frames, b, b + options_.window_frames, options_.fps));
  if (windows == 0) return -1;
  int best = 0;
  sum.maxCoeff(&best);
  return best;
}

int StyleClassifier::Classify(const std::vector<motion::MotionFrame>& frames) const {
  return ClassifyFrames(frames, options_.skip_frames);
}

StyleAccuracy StyleClassifier::Score(const std::vector<const motion::MotionClip*>& clips,
                                     int segment_frames) const {
  StyleAccuracy a;
  std::map<std::string, int> right;
  int correct = 0;
  for (const auto* clip : clips) {
    const std::string& label = clip->meta().emotion;
    if (LabelIndex(label) < 0) continue;  // an emotion the classifier was not trained on
    const auto frames = FramesAt(*clip, options_.fps);
    const int n = static_cast<int>(frames.size());
    const int piece = segment_frames > 0 ? segment_frames : n;
    for (int b = 0; b + piece <= n; b += piece) {
      const std::vector<motion::MotionFrame> part(frames.begin() + b, frames.begin() + b + piece);
      const bool ok = ClassifyFrames(part, 0) == LabelIndex(label);
      ++a.motions[label];
      right[label] += ok;
      correct += ok;
      ++a.total;
    }
  }
  for (const auto& [label, n] : a.motions)
    a.per_label[label] = static_cast<double>(right[label]) / n;
  a.accuracy = a.total ? static_cast<double>(correct) / a.total : 0.0;
  return a;
}

}  // namespace sims::eval
