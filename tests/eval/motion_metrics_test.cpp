#include "sims/eval/motion_metrics.h"

#include <gtest/gtest.h>

#include "sims/humanoid/model_builder.h"

namespace sims::eval {
namespace {

std::shared_ptr<const humanoid::Humanoid> Humanoid() {
  static auto h = std::make_shared<const humanoid::Humanoid>(humanoid::BuildModel());
  return h;
}

// Standing still, or sliding along x at `speed` with feet on the floor.
io::MotionRecord Standing(double speed, int frames = 31, Eigen::Vector3d start = {0, 0, 0.89}) {
  io::MotionRecordBuilder b(Humanoid());
  for (int t = 0; t < frames; ++t) {
    humanoid::HumanoidPose p;
    p.root_pos = start + Eigen::Vector3d(speed * t / 30.0, 0, 0);
    b.AddFrame(p);
  }
  return b.Finish();
}

// Two pairs of two targets: moves (0.3, 0.4) and (0, 0) give √((0.09 + 0.16) / 4) = 0.25 rad.
TEST(MotionMetricsTest, ActionRateIsTheRmsTargetChange) {
  ActionRateMeter m;
  EXPECT_EQ(m.Rms(), 0.0);
  const double a[2] = {0.1, -0.2}, b[2] = {0.4, 0.2};
  m.Add(a, b, 2);
  EXPECT_NEAR(m.Rms(), std::sqrt(0.25 / 2), 1e-12);
  m.Add(b, b, 2);
  EXPECT_NEAR(m.Rms(), 0.25, 1e-12);
}

TEST(MotionMetricsTest, FootSlidingOfAHandMadeGlide) {
  EXPECT_NEAR(MeasureFootSliding(Standing(0.0)).mean_speed, 0.0, 1e-9);
  const auto s = MeasureFootSliding(Standing(0.3));
  EXPECT_EQ(s.contact_pairs, 2 * 30);
  EXPECT_NEAR(s.mean_speed, 0.3, 1e-6);
  EXPECT_DOUBLE_EQ(s.sliding_ratio, 1.0);
  // Lifted 0.5 m: no foot on the floor, nothing counted.
  EXPECT_EQ(MeasureFootSliding(Standing(0.3, 31, {0, 0, 1.4})).contact_pairs, 0);
  // A stretch of frames (a story keyframe's): the pairs ending in frames 11..20, clipped.
  FootSlidingMeter stretch;
  stretch.AddRecord(Standing(0.3), 10, 20);
  EXPECT_EQ(stretch.Result().contact_pairs, 2 * 10);
  EXPECT_NEAR(stretch.Result().mean_speed, 0.3, 1e-6);
  FootSlidingMeter clipped;
  clipped.AddRecord(Standing(0.3), 25, 99);
  EXPECT_EQ(clipped.Result().contact_pairs, 2 * 5);
}

TEST(MotionMetricsTest, PenetrationOfAKnownBox) {
  scene::Scene s;
  scene::Object box;
  box.category = "table";
  box.instance = "box";
  scene::Part part;
  part.name = "body";
  part.mesh = scene::TriangleMesh::Box({1.8, -1, 0}, {3.2, 1, 2});
  box.parts.push_back(part);
  s.objects.push_back(box);
  const scene::SceneOccupancy occ(s);
  const auto samples = BodySamplePoints(*Humanoid());
  EXPECT_EQ(MotionPenetration(Standing(0.0), occ, samples).fraction_inside, 0.0);
  // The whole body inside the box, centred 0.7 m from its x faces.
  const auto inside = MotionPenetration(Standing(0.0, 5, {2.5, 0, 0.89}), occ, samples);
  EXPECT_GT(inside.fraction_inside, 0.99);
  EXPECT_GT(inside.max_depth, 0.5);
  EXPECT_LT(inside.max_depth, 1.0 + 1e-6);
}

TEST(MotionMetricsTest, FidAndApdOnKnownSets) {
  Eigen::MatrixXd a(4, 2), b(4, 2);
  a << 0, 0, 1, 0, 0, 1, 1, 1;
  b = a.rowwise() + Eigen::RowVector2d(3, 4);
  EXPECT_NEAR(FrechetDistance(a, a), 0.0, 1e-9);
  EXPECT_NEAR(FrechetDistance(a, b), 25.0, 1e-9) << "same covariance: squared mean distance";
  Eigen::MatrixXd two(2, 2);
  two << 0, 0, 0, 2;
  EXPECT_DOUBLE_EQ(AveragePairwiseDistance(two), 2.0);
  EXPECT_EQ(PoseFeatures(Standing(0.0), 3).rows(), 11);
}

}  // namespace
}  // namespace sims::eval
