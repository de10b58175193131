// Short-script JSON text (the script database, LLM and VLM replies) → ParseShortScriptText in
// both grammar modes.
#include "fuzz_util.h"
#include "sims/core/error.h"
#include "sims/planner/script.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = sims::fuzz::Text(data, size);
  for (auto mode : {sims::planner::GrammarMode::kStrict, sims::planner::GrammarMode::kLenient}) {
    try {
      sims::planner::ParseShortScriptText(text, "fuzz.json", mode);
    } catch (const sims::Error&) {
    }
  }
  return 0;
}
