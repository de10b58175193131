// A policy file (what eval_policy, run_story and --init-policy read: a torch archive with the
// network weights, the observation normaliser and a JSON metadata record) → learning::Policy,
// then one action for a zero observation when it loads.
#include <vector>

#include "fuzz_util.h"
#include "sims/core/error.h"
#include "sims/learning/trainer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = sims::fuzz::ScratchFile(data, size, "policy.pt");
  try {
    const sims::learning::Policy policy(path);
    const std::vector<float> obs(static_cast<size_t>(policy.obs_dim()), 0.f);
    std::vector<float> action(static_cast<size_t>(policy.action_dim()));
    policy.Act(obs.data(), 1, action.data());
  } catch (const sims::Error&) {
  }
  return 0;
}
