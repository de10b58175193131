// What every command-line app shares: the --threads and --log-level flags, and the rule that
// any failure ends the program with one error line (user errors name file, field and
// expectation) and exit code 1.
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace sims {

/// The flags every app takes.
struct AppFlags {
  int threads = 0;        ///< --threads: OpenMP and libtorch threads (0 = all hardware threads).
  std::string log_level;  ///< --log-level (empty: default_log_level).
  std::string default_log_level;  ///< Used without --log-level ("": $SIMS_LOG_LEVEL, else info).
};

/// Adds --threads and --log-level to `app`, bound to `flags`.
void AddAppFlags(CLI::App* app, AppFlags* flags);

/// Reads the process environment once and installs it (InstallEnvironment; the app's body gets
/// it from InstalledEnvironment()), sets logging and threads from `flags`, then runs `body`;
/// returns its exit code, or 1 after logging the message of any exception it throws.
int RunApp(const AppFlags& flags, const std::function<int()>& body);

}  // namespace sims
