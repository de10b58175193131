// Logging through spdlog; the level comes from a flag or, in the apps, $SIMS_LOG_LEVEL (read by
// RunApp, not here).
#pragma once

#include <string>

#include <spdlog/spdlog.h>

namespace sims {

/// Sets the global level: `level`, or "info" when empty. Accepts trace, debug, info, warn,
/// error, critical, off; otherwise throws sims::Error naming `source` (the flag or variable
/// the level came from).
void InitLogging(const std::string& level = "", const std::string& source = "--log-level");

}  // namespace sims
