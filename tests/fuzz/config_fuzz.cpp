// A JSON config → every torch-free config loader a user points a flag at: skill, env, planner,
// retarget map, dataset rules, synthetic catalogue, motion manifest.
#include "fuzz_util.h"
#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/motion/import.h"
#include "sims/motion/motion_library.h"
#include "sims/motion/retarget.h"
#include "sims/motion/synthetic_catalog.h"
#include "sims/planner/planner.h"
#include "sims/sim/env.h"
#include "sims/task/skill.h"

namespace {
template <class F>
void Expect(F f) {
  try {
    f();
  } catch (const sims::Error&) {
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = sims::fuzz::ScratchFile(data, size, "config.json");
  Expect([&] { sims::LoadConfig<sims::task::SkillConfig>(path); });
  Expect([&] { sims::LoadConfig<sims::sim::EnvConfig>(path); });
  Expect([&] { sims::LoadConfig<sims::motion::DatasetConfig>(path); });
  Expect([&] { sims::motion::LoadRetargetConfig(path); });
  Expect([&] { sims::motion::LoadSyntheticCatalog(path); });
  Expect([&] { sims::motion::LoadManifest(path); });
  Expect([&] { sims::planner::LoadPlannerConfig(path); });
  return 0;
}
