// A PLY mesh (ScanNet scans, user meshes) → LoadTriangleMesh.
#include "fuzz_util.h"
#include "sims/core/error.h"
#include "sims/scene/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    sims::scene::LoadTriangleMesh(sims::fuzz::ScratchFile(data, size, "mesh.ply"));
  } catch (const sims::Error&) {
  }
  return 0;
}
