#include "sims/core/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>

#include "sims/core/error.h"

namespace sims {

void InitLogging(const std::string& level, const std::string& source) {
  const std::string name = level.empty() ? "info" : level;
  const auto lvl = spdlog::level::from_str(name);
  if (lvl == spdlog::level::off && name != "off")
    ThrowInputError(source, "", "one of trace, debug, info, warn, error, critical, off", name);
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
