#include "sims/motion/motion_library.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "motion/motion_test_util.h"
#include "sims/core/error.h"
#include "sims/sim/env.h"

namespace sims::motion {
namespace {

using testing_util::WigglyClip;

MotionLibrary SmallLibrary(bool mirror = false) {
  std::vector<MotionClip> clips = {WigglyClip(40, 1, 0.1, true), WigglyClip(60, 2, 0.1, true),
                                   WigglyClip(5, 3, 0.1, true)};
  clips[1].mutable_meta().skill = "walk";
  clips[1].mutable_meta().emotion = "sad";
  MotionLibraryOptions o;
  o.mirror = mirror;
  return MotionLibrary(HumanoidSkeleton::DefaultHumanoid(), std::move(clips), {1.0, 3.0, 1.0}, o);
}

TEST(MotionLibraryTest, ManifestLoadOverridesLabelsAndMirrors) {
  const auto dir = testing::TempDir("lib");
  SaveClip(WigglyClip(20, 1), dir / "clips" / "a.json");
  SaveClip(WigglyClip(25, 2), dir / "clips" / "b.json");
  MotionManifest m;
  ManifestEntry a;
  a.file = "clips/a.json";
  a.weight = 2.0;
  a.captions = {"someone walks to the left"};
  a.skill = "walk";
  a.emotion = "tired";
  ManifestEntry b;
  b.file = "clips/b.json";
  m.clips = {a, b};
  SaveManifest(dir / "manifest.json", m);

  const MotionLibrary lib = MotionLibrary::Load(dir / "manifest.json", nullptr);
  ASSERT_EQ(lib.num_clips(), 2);
  EXPECT_EQ(lib.clip(0).meta().skill, "walk");
  EXPECT_EQ(lib.clip(0).meta().emotion, "tired");
  EXPECT_EQ(lib.clip(0).meta().captions[0], "someone walks to the left");
  EXPECT_EQ(lib.weight(0), 2.0);
  EXPECT_EQ(lib.clip(1).meta().emotion, "happy");

  MotionLibraryOptions o;
  o.mirror = true;
  const MotionLibrary mirrored = MotionLibrary::Load(dir / "manifest.json", nullptr, o);
  ASSERT_EQ(mirrored.num_clips(), 4);
  EXPECT_EQ(mirrored.clip(1).meta().captions[0], "someone walks to the right");
  EXPECT_TRUE(mirrored.clip(1).meta().mirrored);
  EXPECT_EQ(mirrored.weight(1), 2.0);

  o.mirror = false;
  o.skills = {"walk"};
  EXPECT_EQ(MotionLibrary::Load(dir / "manifest.json", nullptr, o).num_clips(), 1);
  o.skills = {"lie"};
  EXPECT_THROW(MotionLibrary::Load(dir / "manifest.json", nullptr, o), Error);

  // Bad manifest entries name the field.
  WriteJsonFile(dir / "bad.json",
                nlohmann::json{{"clips", {{{"file", "x.json"}, {"weight", -1}}}}});
  try {
    MotionLibrary::Load(dir / "bad.json", nullptr);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("clips[0].weight"), std::string::npos) << e.what();
  }
}

TEST(MotionLibraryTest, SamplingIsDeterministicAndWeighted) {
  const MotionLibrary lib = SmallLibrary();
  Rng r1(42), r2(42);
  std::vector<int> counts(3, 0);
  for (int i = 0; i < 3000; ++i) {
    const ReferenceState a = lib.SampleReferenceState(r1);
    const ReferenceState b = lib.SampleReferenceState(r2);
    ASSERT_EQ(a.clip, b.clip);
    ASSERT_EQ(a.time, b.time);
    ++counts[a.clip];
    ASSERT_GE(a.time, 0.0);
    ASSERT_LE(a.time, lib.clip(a.clip).duration());
  }
  EXPECT_NEAR(counts[1] / 3000.0, 0.6, 0.04);
  EXPECT_NEAR(counts[0] / 3000.0, 0.2, 0.04);
  // Demo windows: same seed, same numbers, at any thread count.
  std::vector<float> d1(20 * 1250), d2(20 * 1250);
  std::vector<int> c1(20), c2(20);
  Rng s1(7), s2(7);
  lib.SampleAmpDemos(s1, 20, d1.data(), c1.data(), 1);
  lib.SampleAmpDemos(s2, 20, d2.data(), c2.data(), 2);
  EXPECT_EQ(d1, d2);
  EXPECT_EQ(c1, c2);
  EXPECT_EQ(s1.NextU64(), s2.NextU64());
}

// Balanced draws: each emotion (here the default one and "sad") half the time, and within an
// emotion by weight; the demo windows follow the same draw.
TEST(MotionLibraryTest, BalancedEmotionsDrawEachEmotionEquallyOften) {
  const MotionLibrary lib = SmallLibrary();
  ASSERT_NE(lib.clip(0).meta().emotion, "sad");
  ASSERT_EQ(lib.clip(0).meta().emotion, lib.clip(2).meta().emotion);
  Rng rng(3);
  std::vector<int> counts(3, 0);
  const int n = 4000;
  for (int i = 0; i < n; ++i) ++counts[lib.SampleClip(rng, true)];
  EXPECT_NEAR(counts[1] / double(n), 0.5, 0.03);  // 0.6 by weight alone
  EXPECT_NEAR(counts[0] / double(n), 0.25, 0.03);
  EXPECT_NEAR(counts[2] / double(n), 0.25, 0.03);
  const int m = 1000;
  std::vector<float> windows(static_cast<size_t>(m) * 1250);
  std::vector<int> clips(m);
  lib.SampleAmpDemos(rng, m, windows.data(), clips.data(), 1, 0, true);
  EXPECT_NEAR(std::count(clips.begin(), clips.end(), 1) / double(m), 0.5, 0.06);
}

TEST(MotionLibraryTest, HistoryAndWindowOrder) {
  const MotionLibrary lib = SmallLibrary();
  const ReferenceState s = lib.StateAt(1, 1.0);
  ASSERT_EQ(s.history.size(), 9u);
  for (int k = 1; k <= 9; ++k)
    EXPECT_LT((s.history[k - 1].root_pos - lib.clip(1).SamplePose(1.0 - k / 30.0).root_pos).norm(),
              1e-12);
  // Near the start the history clamps at t = 0.
  const ReferenceState early = lib.StateAt(1, 0.05);
  EXPECT_LT((early.history[8].root_pos - lib.clip(1).SamplePose(0).root_pos).norm(), 1e-12);
  Rng rng(1);
  const ReferenceState drawn = lib.SampleReferenceState(rng);
  EXPECT_EQ(drawn.history.size(), 9u);

  humanoid::MjDataPtr d = humanoid::MakeData(lib.humanoid().model());
  std::vector<float> window(1250), step(125);
  lib.AmpWindow(1, 1.0, d.get(), window.data());
  for (int k = 0; k < 10; ++k) {
    lib.AmpObservation(1, 1.0 - k / 30.0, d.get(), step.data());
    for (int i = 0; i < 125; ++i) ASSERT_EQ(window[k * 125 + i], step[i]) << k;
  }
  // Shorter windows (an env with amp_history 2) are the first steps of the long one.
  std::vector<float> pair(250);
  lib.AmpWindow(1, 1.0, d.get(), pair.data(), 2);
  for (int i = 0; i < 250; ++i) ASSERT_EQ(pair[i], window[i]) << i;
  Rng demo_rng(4);
  std::vector<float> demos(3 * 250);
  std::vector<int> clips(3);
  lib.SampleAmpDemos(demo_rng, 3, demos.data(), clips.data(), 1, 2);
  for (int i = 0; i < 3; ++i) EXPECT_GE(clips[i], 0);
  const std::vector<float> feats = lib.ClipAmpFeatures(1);
  EXPECT_EQ(feats.size(), 60u * 125u);
  EXPECT_EQ(lib.Find("walk").size(), 1u);
  EXPECT_EQ(lib.Find("", "happy").size(), 2u);
}

// A task hook that starts env 0 from a clip state (reference init with AMP history).
class ReferenceInitHook : public sim::TaskHook {
 public:
  ReferenceInitHook(const MotionLibrary* lib, int clip, double t) : lib_(lib), clip_(clip), t_(t) {}
  int obs_dim() const override { return 0; }
  void SampleInitialState(int, Rng&, sim::InitialState* init) override {
    const ReferenceState s = lib_->StateAt(clip_, t_);
    init->pose = s.pose;
    init->history = s.history;
    init->reference = true;
  }
  void OnReset(const sim::EnvView&, Rng&) override {}
  sim::TaskStepResult Step(const sim::EnvView&) override { return {}; }
  void Observe(const sim::EnvView&, float*) const override {}

 private:
  const MotionLibrary* lib_;
  int clip_;
  double t_;
};

// The AMP observations the library computes from a clip equal the environment's for the
// same states: per frame via SetState, and through a reference-init reset's history.
TEST(MotionLibraryTest, AmpFeaturesEqualTheEnvironments) {
  const MotionLibrary lib = SmallLibrary();
  const auto h = HumanoidSkeleton::DefaultHumanoid();
  sim::EnvConfig c;
  c.num_envs = 1;
  c.threads = 1;
  c.early_termination = false;
  const double t0 = 1.2;
  auto hook = std::make_shared<ReferenceInitHook>(&lib, 1, t0);
  sim::BatchedEnv env(h, c, hook);
  humanoid::MjDataPtr d = humanoid::MakeData(h->model());
  std::vector<float> from_env(125), from_clip(125);
  testing::ScopedAllowMujocoWarnings allow;
  for (int f = 0; f < lib.clip(1).num_frames(); f += 3) {
    env.SetState(0, lib.clip(1).FramePose(f));
    humanoid::ComputeAmpObservation(env.pose(0), env.bodies(0), lib.obs_options(), from_env.data());
    lib.AmpObservation(1, f / 30.0, d.get(), from_clip.data());
    for (int i = 0; i < 125; ++i)
      ASSERT_NEAR(from_env[i], from_clip[i], 2e-5) << "frame " << f << " i " << i;
  }
  // Reset from the clip at t0, hold the pose for one step: the env's history slots 1..9 are
  // the clip's window at t0 (slots 0..8).
  env.Reset();
  std::vector<float> hold(28);
  h->TargetsToAction(lib.clip(1).SamplePose(t0).dof_pos.data(), hold.data());
  env.Step(hold.data());
  std::vector<float> window(1250);
  lib.AmpWindow(1, t0, d.get(), window.data());
  const float* amp = env.amp_observations();
  for (int k = 1; k < 10; ++k)
    for (int i = 0; i < 125; ++i)
      ASSERT_NEAR(amp[k * 125 + i], window[(k - 1) * 125 + i], 2e-5) << "slot " << k << " i " << i;
}

}  // namespace
}  // namespace sims::motion
