// Small synthetic clips for the motion tests.
#pragma once

#include <cmath>

#include "sims/core/rng.h"
#include "sims/motion/motion_clip.h"

namespace sims::motion::testing_util {

/// A smooth in-limit motion: every hinge oscillates within `amplitude` of its range around
/// the middle (or around zero when `around_zero`), the root drifts and turns.
inline MotionClip WigglyClip(int frames, uint64_t seed, double amplitude = 0.4,
                             bool around_zero = false) {
  const HumanoidSkeleton& s = HumanoidSkeleton::Default();
  Rng rng(seed);
  const DofVector mid = around_zero ? DofVector::Zero() : DofVector(0.5 * (s.lower + s.upper));
  const DofVector amp = amplitude * (s.upper - s.lower);
  DofVector phase, freq;
  for (int i = 0; i < humanoid::kNumDofs; ++i)
    phase[i] = rng.Uniform(0, 6.28), freq[i] = rng.Uniform(0.5, 2);
  std::vector<MotionFrame> fr(frames);
  for (int f = 0; f < frames; ++f) {
    const double t = f / 30.0;
    for (int i = 0; i < humanoid::kNumDofs; ++i) {
      const double v = mid[i] + amp[i] * std::sin(freq[i] * t + phase[i]);
      fr[f].dof_pos[i] = std::clamp(v, s.lower[i], s.upper[i]);
    }
    fr[f].root_pos = Eigen::Vector3d(0.5 * t, 0.2 * std::sin(t), 0.95 + 0.03 * std::sin(3 * t));
    fr[f].root_rot = Eigen::AngleAxisd(0.7 * t, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(0.1 * std::sin(t), Eigen::Vector3d::UnitX());
  }
  MotionMeta meta;
  meta.name = "wiggly_left_" + std::to_string(seed);
  meta.captions = {"a person wiggles the left arm", "wiggling to the right"};
  meta.skill = "other";
  meta.emotion = "happy";
  meta.params = {{"target_y", 0.3}, {"seat_height", 0.45}, {"turn_yaw", 0.5}};
  return MotionClip(30.0, std::move(fr), meta);
}

}  // namespace sims::motion::testing_util
