// A UniHSI ScenePlan JSON → ScenePlanIds and LoadScenePlan against the test PartNet object.
#include "fuzz_util.h"
#include "sims/core/error.h"
#include "sims/scene/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = sims::fuzz::ScratchFile(data, size, "sceneplan.json");
  try {
    for (const auto& id : sims::scene::ScenePlanIds(path))
      sims::scene::LoadScenePlan(path, sims::fuzz::TestData("scene/partnet"), id);
  } catch (const sims::Error&) {
  }
  return 0;
}
