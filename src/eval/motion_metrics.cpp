#include "sims/eval/motion_metrics.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "sims/core/error.h"
#include "sims/core/rng.h"
#include "sims/humanoid/features.h"

namespace sims::eval {

std::vector<std::vector<Eigen::Vector3d>> BodySamplePoints(const humanoid::Humanoid& humanoid) {
  const mjModel* m = humanoid.model();
  std::vector<std::vector<Eigen::Vector3d>> out(humanoid::kNumBodies);
  for (int g = 0; g < m->ngeom; ++g) {
    const int b = humanoid.geom_body(g);
    if (b < 0) continue;
    const Eigen::Vector3d p(m->geom_pos[3 * g], m->geom_pos[3 * g + 1], m->geom_pos[3 * g + 2]);
    const Eigen::Quaterniond q(m->geom_quat[4 * g], m->geom_quat[4 * g + 1],
                               m->geom_quat[4 * g + 2], m->geom_quat[4 * g + 3]);
    const double* s = m->geom_size + 3 * g;
    auto& pts = out[b];
    auto ring = [&](const Eigen::Vector3d& c, double r) {
      // Centre plus six surface points along the geom frame's axes.
      pts.push_back(c);
      for (int k = 0; k < 3; ++k)
        for (double sign : {-1.0, 1.0})
          pts.push_back(c + q * (sign * r * Eigen::Vector3d::Unit(k)));
    };
    switch (m->geom_type[g]) {
      case mjGEOM_SPHERE:
        ring(p, s[0]);
        break;
      case mjGEOM_CAPSULE:
        for (double t : {-1.0, 0.0, 1.0}) ring(p + q * Eigen::Vector3d(0, 0, t * s[1]), s[0]);
        break;
      case mjGEOM_BOX:
        pts.push_back(p);
        for (int c = 0; c < 8; ++c)
          pts.push_back(p + q * Eigen::Vector3d((c & 1 ? 1 : -1) * s[0], (c & 2 ? 1 : -1) * s[1],
                                                (c & 4 ? 1 : -1) * s[2]));
        break;
      default:
        pts.push_back(p);
    }
  }
  return out;
}

scene::PenetrationStats MotionPenetration(
    const io::MotionRecord& record, const scene::SceneOccupancy& occupancy,
    const std::vector<std::vector<Eigen::Vector3d>>& samples) {
  std::vector<Eigen::Vector3d> world;
  for (const auto& f : record.frames)
    for (int b = 0; b < humanoid::kNumBodies; ++b)
      for (const auto& p : samples[b]) world.push_back(f.body_pos[b] + f.body_rot[b] * p);
  return scene::MeasurePenetration(occupancy, world);
}

void FootSlidingMeter::Add(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double dt) {
  if (a.z() > contact_height_ || b.z() > contact_height_) return;
  const double v = (b - a).head<2>().norm() / dt;
  total_ += v;
  fast_ += v > 0.1;
  ++pairs_;
}

FootSliding FootSlidingMeter::Result() const {
  FootSliding s;
  s.contact_pairs = pairs_;
  if (pairs_) {
    s.mean_speed = total_ / pairs_;
    s.sliding_ratio = static_cast<double>(fast_) / pairs_;
  }
  return s;
}

void ActionRateMeter::Add(const double* before, const double* now, int n) {
  for (int j = 0; j < n; ++j) sum_sq_ += (now[j] - before[j]) * (now[j] - before[j]);
  count_ += n;
}

double ActionRateMeter::Rms() const { return count_ ? std::sqrt(sum_sq_ / count_) : 0.0; }

void FootSlidingMeter::AddRecord(const io::MotionRecord& record) {
  AddRecord(record, 0, static_cast<int>(record.frames.size()) - 1);
}

void FootSlidingMeter::AddRecord(const io::MotionRecord& record, int first, int last) {
  const double dt = 1.0 / record.fps;
  last = std::min(last, static_cast<int>(record.frames.size()) - 1);
  for (int t = std::max(first, 0) + 1; t <= last; ++t)
    for (int foot : {humanoid::kLeftFoot, humanoid::kRightFoot})
      Add(record.frames[t - 1].body_pos[foot], record.frames[t].body_pos[foot], dt);
}

FootSliding MeasureFootSliding(const io::MotionRecord& record, double contact_height) {
  FootSlidingMeter meter(contact_height);
  meter.AddRecord(record);
  return meter.Result();
}

Eigen::VectorXd PoseFeature(const io::RecordFrame& f) {
  Eigen::VectorXd v(3 * (humanoid::kNumBodies - 1) + humanoid::kDofObsDim);
  const Eigen::Quaterniond h_inv = humanoid::HeadingInverse(f.body_rot[humanoid::kPelvis]);
  int k = 0;
  for (int b = 1; b < humanoid::kNumBodies; ++b) {
    const Eigen::Vector3d d = h_inv * (f.body_pos[b] - f.body_pos[humanoid::kPelvis]);
    for (int c = 0; c < 3; ++c) v[k++] = d[c];
  }
  float dof[humanoid::kDofObsDim];
  humanoid::DofObservation(f.dof_pos, dof);
  for (int c = 0; c < humanoid::kDofObsDim; ++c) v[k++] = dof[c];
  return v;
}

Eigen::MatrixXd PoseFeatures(const io::MotionRecord& record, int stride) {
  const int n = (record.num_frames() + stride - 1) / std::max(stride, 1);
  Eigen::MatrixXd m(n, 3 * (humanoid::kNumBodies - 1) + humanoid::kDofObsDim);
  for (int i = 0; i < n; ++i)
    m.row(i) = PoseFeature(record.frames[static_cast<size_t>(i) * stride]).transpose();
  return m;
}

Eigen::MatrixXd StackRows(const std::vector<Eigen::MatrixXd>& parts) {
  Eigen::Index rows = 0, cols = 0;
  for (const auto& p : parts) rows += p.rows(), cols = p.cols();
  Eigen::MatrixXd m(rows, cols);
  Eigen::Index r = 0;
  for (const auto& p : parts) {
    SIMS_CHECK(p.cols() == cols);
    m.middleRows(r, p.rows()) = p;
    r += p.rows();
  }
  return m;
}

double FrechetDistance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  auto stats = [](const Eigen::MatrixXd& x, Eigen::VectorXd* mu, Eigen::MatrixXd* cov) {
    *mu = x.colwise().mean().transpose();
    const Eigen::MatrixXd c = x.rowwise() - mu->transpose();
    *cov = c.transpose() * c / std::max<double>(1.0, static_cast<double>(x.rows() - 1));
  };
  Eigen::VectorXd mu_a, mu_b;
  Eigen::MatrixXd s_a, s_b;
  stats(a, &mu_a, &s_a);
  stats(b, &mu_b, &s_b);
  // Tr(sqrt(S_a S_b)) = Σ sqrt(λ) of the symmetric PSD matrix sqrt(S_a) S_b sqrt(S_a).
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ea(s_a);
  const Eigen::VectorXd la = ea.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::MatrixXd sqrt_a =
      ea.eigenvectors() * la.asDiagonal() * ea.eigenvectors().transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> em(sqrt_a * s_b * sqrt_a);
  const double tr_sqrt = em.eigenvalues().cwiseMax(0.0).cwiseSqrt().sum();
  return (mu_a - mu_b).squaredNorm() + s_a.trace() + s_b.trace() - 2.0 * tr_sqrt;
}

double AveragePairwiseDistance(const Eigen::MatrixXd& rows, int max_pairs) {
  const int64_t n = rows.rows();
  if (n < 2) return 0.0;
  double sum = 0;
  int64_t count = 0;
  if (n * (n - 1) / 2 <= max_pairs) {
    for (int64_t i = 0; i < n; ++i)
      for (int64_t j = i + 1; j < n; ++j, ++count) sum += (rows.row(i) - rows.row(j)).norm();
  } else {
    Rng rng(12345);
    for (; count < max_pairs; ++count) {
      const int64_t i = rng.UniformInt(n);
      int64_t j = rng.UniformInt(n - 1);
      if (j >= i) ++j;
      sum += (rows.row(i) - rows.row(j)).norm();
    }
  }
  return sum / count;
}

}  // namespace sims::eval
