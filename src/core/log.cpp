#include "sims/core/log.h"

#include <cstdlib>

#include <spdlog/sinks/stdout_color_sinks.h>

#include "sims/core/error.h"

namespace sims {

void InitLogging(const std::string& level) {
  std::string name = level;
  if (name.empty()) {
    const char* env = std::getenv("SIMS_LOG_LEVEL");
    name = env ? env : "info";
  }
  const auto lvl = spdlog::level::from_str(name);
  if (lvl == spdlog::level::off && name != "off")
    ThrowInputError(level.empty() ? "SIMS_LOG_LEVEL" : "--log-level", "",
                    "one of trace, debug, info, warn, error, critical, off", name);
  static bool initialised = false;
  if (!initialised) {
    // Logs go to stderr so stdout stays clean for --json outputs.
    auto logger = spdlog::stderr_color_mt("sims");
    logger->set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
    spdlog::set_default_logger(logger);
    initialised = true;
  }
  spdlog::set_level(lvl);
}

}  // namespace sims
