// BVH text → ParseBvh, then the CMU retarget map on what parsed (motion-capture files come
// from outside: CMU, 100STYLE, SAMP).
#include "fuzz_util.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/motion/bvh.h"
#include "sims/motion/retarget.h"
#include "sims/motion/skeleton.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const sims::motion::RetargetConfig map =
      sims::motion::LoadRetargetConfig(sims::ConfigPath("retarget/cmu.json"));
  try {
    const sims::motion::BvhMotion bvh =
        sims::motion::ParseBvh(sims::fuzz::Text(data, size), "fuzz");
    if (bvh.num_frames <= 2000)  // retargeting is linear in frames; keep executions short
      sims::motion::RetargetBvh(bvh, map, sims::motion::HumanoidSkeleton::Default(), nullptr,
                                "fuzz");
  } catch (const sims::Error&) {
  }
  return 0;
}
