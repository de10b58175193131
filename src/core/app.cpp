#include "sims/core/app.h"

#include <limits>

#include "sims/core/environment.h"
#include "sims/core/log.h"
#include "sims/core/parallel.h"

namespace sims {

void AddAppFlags(CLI::App* app, AppFlags* flags) {
  app->add_option("--threads", flags->threads, "threads (0 = all hardware threads)")
      // Int bounds: with CLI::NonNegativeNumber the error message would print DBL_MAX in full.
      ->check(CLI::Range(0, std::numeric_limits<int>::max(), "NONNEGATIVE"));
  app->add_option("--log-level", flags->log_level, "trace|debug|info|warn|error");
}

int RunApp(const AppFlags& flags, const std::function<int()>& body) {
  try {
    // The only place the apps read the process environment; everything below gets it from the
    // installed settings or from option fields the app fills.
    InstallEnvironment(ReadEnvironment());
    if (!flags.log_level.empty())
      InitLogging(flags.log_level, "--log-level");
    else if (!flags.default_log_level.empty())
      InitLogging(flags.default_log_level, "--log-level");
    else
      InitLogging(InstalledEnvironment().log_level, "SIMS_LOG_LEVEL");
    SetThreadCount(flags.threads);
    return body();
  } catch (const std::exception& e) {
    // A bad level throws before InitLogging installs the stderr logger; install it so the error
    // does not reach stdout through spdlog's default logger.
    if (!spdlog::get("sims")) InitLogging("error");
    spdlog::error("{}", e.what());
    return 1;
  }
}

}  // namespace sims
