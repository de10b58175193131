#include "sims/eval/style_classifier.h"

#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "sims/core/error.h"
#include "sims/motion/mirror.h"
#include "sims/motion/synthetic.h"

namespace sims::eval {
namespace {

// The shipped walk catalogue (two variants per recipe) and the mirrors, as the loader gives them.
const std::vector<motion::MotionClip>& WalkClips() {
  static const std::vector<motion::MotionClip> clips = [] {
    motion::SyntheticOptions o;
    o.variants = 2;
    o.skills = {"walk"};
    std::vector<motion::MotionClip> out = motion::GenerateSyntheticClips(o);
    const size_t n = out.size();
    for (size_t i = 0; i < n; ++i) out.push_back(motion::MirrorClip(out[i]));
    return out;
  }();
  return clips;
}

std::vector<const motion::MotionClip*> Pick(bool variants) {
  std::vector<const motion::MotionClip*> out;
  for (const auto& c : WalkClips())
    if (IsClipVariant(c.meta()) == variants) out.push_back(&c);
  return out;
}

TEST(StyleClassifierTest, FeaturesIgnoreWherePlacedAndWhichSide) {
  const motion::MotionClip& clip = WalkClips().front();
  std::vector<motion::MotionFrame> moved = clip.frames();
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()));
  for (auto& f : moved) {
    f.root_pos = yaw * f.root_pos + Eigen::Vector3d(3, -2, 0);
    f.root_rot = yaw * f.root_rot;
  }
  const Eigen::VectorXd a = StyleFeatures(clip.frames(), 0, 60, clip.fps());
  const Eigen::VectorXd b = StyleFeatures(moved, 0, 60, clip.fps());
  ASSERT_EQ(a.size(), kStyleFeatureDim);
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-9);
  // A mirrored walk moves the same way: the first nine (body-level) values agree.
  const Eigen::VectorXd m = StyleFeatures(motion::MirrorClip(clip).frames(), 0, 60, clip.fps());
  EXPECT_LT((a.head(9) - m.head(9)).cwiseAbs().maxCoeff(), 1e-6);
  // A faster walk has a larger forward speed.
  EXPECT_GT(a[0], 0.3);
}

// Trained on the first variant of every walk recipe, scored on the second (never seen): the
// accuracy the README's style figures rest on, per emotion, printed here.
TEST(StyleClassifierTest, RecognisesHeldOutWalkVariants) {
  const auto train = Pick(false), test = Pick(true);
  ASSERT_FALSE(train.empty());
  ASSERT_FALSE(test.empty());
  const StyleClassifier c = StyleClassifier::Train(train);
  EXPECT_GE(c.labels().size(), 6u);
  const StyleAccuracy a = c.Score(test, /*segment_frames=*/90);
  std::cout << "style classifier, held-out walk variants in 3 s pieces: " << a.total
            << " pieces, accuracy " << a.accuracy << " (chance " << 1.0 / c.labels().size()
            << ")\n";
  for (const auto& [label, acc] : a.per_label)
    std::cout << "  " << label << ": " << acc << " of " << a.motions.at(label) << "\n";
  EXPECT_GT(a.accuracy, 0.8);
  for (const auto& [label, acc] : a.per_label) EXPECT_GT(acc, 0.5) << label;
  // The training clips themselves are (nearly) all recognised.
  EXPECT_GT(c.Score(train, 90).accuracy, 0.9);
}

TEST(StyleClassifierTest, DeterministicAndLabelsAMotionOnlyWhenLongEnough) {
  const auto train = Pick(false);
  const StyleClassifier a = StyleClassifier::Train(train), b = StyleClassifier::Train(train);
  const auto& frames = train.front()->frames();
  const Eigen::VectorXd f = StyleFeatures(frames, 0, 60, 30.0);
  EXPECT_EQ(a.LogProbabilities(f), b.LogProbabilities(f));
  EXPECT_NEAR(a.LogProbabilities(f).array().exp().sum(), 1.0, 1e-9);
  // 30 skipped frames + one 60-frame window.
  EXPECT_EQ(a.Classify({frames.begin(), frames.begin() + 89}), -1);
  EXPECT_EQ(a.Classify({frames.begin(), frames.begin() + 90}),
            a.LabelIndex(train.front()->meta().emotion));
}

TEST(StyleClassifierTest, NeedsTwoEmotionsAndLongEnoughClips) {
  std::vector<const motion::MotionClip*> one;
  for (const auto& c : WalkClips())
    if (c.meta().emotion == "angry") one.push_back(&c);
  ASSERT_FALSE(one.empty());
  EXPECT_THROW(StyleClassifier::Train(one), Error);
  std::vector<const motion::MotionClip*> two = one;
  const motion::MotionClip short_clip = WalkClips().front().Slice(0, 20);
  two.push_back(&short_clip);
  EXPECT_THROW(StyleClassifier::Train(two), Error);
}

}  // namespace
}  // namespace sims::eval
