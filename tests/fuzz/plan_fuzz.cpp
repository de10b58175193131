// A plan file (plan_story's output, run_story's input) → LoadPlan.
#include "fuzz_util.h"
#include "sims/core/error.h"
#include "sims/planner/plan.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    sims::planner::LoadPlan(sims::fuzz::ScratchFile(data, size, "plan.json"));
  } catch (const sims::Error&) {
  }
  return 0;
}
