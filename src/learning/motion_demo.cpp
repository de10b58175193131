#include "sims/learning/motion_demo.h"

#include "sims/humanoid/features.h"

namespace sims::learning {

MotionDemoSource::MotionDemoSource(std::shared_ptr<const motion::MotionLibrary> library,
                                   std::shared_ptr<const task::StyleTable> styles, int steps,
                                   int threads, bool balance_emotions)
    : library_(std::move(library)),
      steps_(steps > 0 ? steps : library_->options().amp_steps),
      threads_(threads),
      balance_emotions_(balance_emotions) {
  if (styles) z_ = styles->all();
}

int MotionDemoSource::amp_obs_dim() const { return steps_ * humanoid::kAmpObsStepDim; }

void MotionDemoSource::Sample(int n, Rng& rng, float* amp_out, int* style_out) const {
  library_->SampleAmpDemos(rng, n, amp_out, style_out, threads_, steps_, balance_emotions_);
}

}  // namespace sims::learning
