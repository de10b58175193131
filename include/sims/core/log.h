// Logging through spdlog; the level comes from a flag or the SIMS_LOG_LEVEL environment variable.
#pragma once

#include <string>

#include <spdlog/spdlog.h>

namespace sims {

/// Sets the global level: `level` if non-empty, else $SIMS_LOG_LEVEL, else "info".
/// Accepts trace, debug, info, warn, error, critical, off; throws sims::Error otherwise.
void InitLogging(const std::string& level = "");

}  // namespace sims
