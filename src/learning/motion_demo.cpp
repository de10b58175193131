#include "sims/learning/motion_demo.h"

#include "sims/sim/features.h"

namespace sims::learning {

MotionDemoSource::MotionDemoSource(std::shared_ptr<const motion::MotionLibrary> library,
                                   std::shared_ptr<const task::StyleTable> styles, int threads)
    : library_(std::move(library)), threads_(threads) {
  if (styles) z_ = styles->all();
}

int MotionDemoSource::amp_obs_dim() const {
  return library_->options().amp_steps * sim::kAmpObsStepDim;
}

void MotionDemoSource::Sample(int n, Rng& rng, float* amp_out, int* style_out) const {
  library_->SampleAmpDemos(rng, n, amp_out, style_out, threads_);
}

}  // namespace sims::learning
