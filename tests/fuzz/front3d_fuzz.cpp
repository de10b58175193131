// A 3D-FRONT house JSON → LoadFront3D with the test 3D-FUTURE models.
#include "fuzz_util.h"
#include "sims/core/error.h"
#include "sims/scene/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    sims::scene::LoadFront3D(sims::fuzz::ScratchFile(data, size, "house.json"),
                             sims::fuzz::TestData("scene/front3d/3D-FUTURE-model"));
  } catch (const sims::Error&) {
  }
  return 0;
}
