#include "sims/sim/action_filter.h"

#include <fmt/format.h>

#include <algorithm>

#include "sims/core/error.h"

namespace sims::sim {

ActionFilter::ActionFilter(int dim) : previous_(static_cast<size_t>(dim), 0.0f) {}

void ActionFilter::Apply(double alpha, float* action) {
  SIMS_DCHECK(alpha >= 0 && alpha <= kMaxActionSmoothing);
  if (has_previous_ && alpha > 0) {
    const float a = static_cast<float>(alpha), b = static_cast<float>(1.0 - alpha);
    for (size_t k = 0; k < previous_.size(); ++k) action[k] = a * previous_[k] + b * action[k];
  }
  // Remembered at α = 0 too: a skill that smooths blends from what the one before it applied.
  std::copy_n(action, previous_.size(), previous_.begin());
  has_previous_ = true;
}

void ActionFilter::Reset() { has_previous_ = false; }

void CheckActionSmoothing(double alpha, const std::string& source, const std::string& field) {
  if (!(alpha >= 0 && alpha <= kMaxActionSmoothing))
    ThrowInputError(source, field,
                    fmt::format("a smoothing factor in [0, {}]", kMaxActionSmoothing),
                    fmt::format("{}", alpha));
}

}  // namespace sims::sim
