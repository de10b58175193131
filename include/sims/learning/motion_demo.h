// DemoSource over the motion library: AMP windows of the clips and their style embeddings.
#pragma once

#include <memory>

#include "sims/learning/vec_env.h"
#include "sims/motion/motion_library.h"
#include "sims/task/styles.h"

namespace sims::learning {

/// Demo windows from a MotionLibrary (style id = clip index).
class MotionDemoSource : public DemoSource {
 public:
  /// `styles` may be null (unconditional AMP); windows hold `steps` AMP observations (the
  /// env's amp_history; 0 = the library's amp_steps); `balance_emotions` draws each emotion's
  /// clips equally often (as the skill's episodes do with its balance_emotions).
  MotionDemoSource(std::shared_ptr<const motion::MotionLibrary> library,
                   std::shared_ptr<const task::StyleTable> styles, int steps = 0, int threads = 1,
                   bool balance_emotions = false);
  int amp_obs_dim() const override;
  void Sample(int n, Rng& rng, float* amp_out, int* style_out) const override;
  const std::vector<Eigen::VectorXf>& style_embeddings() const override { return z_; }

 private:
  std::shared_ptr<const motion::MotionLibrary> library_;
  std::vector<Eigen::VectorXf> z_;
  int steps_;
  int threads_;
  bool balance_emotions_;
};

}  // namespace sims::learning
