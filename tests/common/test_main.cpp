// GoogleTest main for every SIMS test binary. Like MuJoCo's own test fixture, any MuJoCo
// warning fails the running test unless a ScopedAllowMujocoWarnings is active.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "sims/core/environment.h"
#include "sims/core/log.h"

namespace sims::testing {
extern std::atomic<int> g_allow_warnings;
extern std::atomic<int> g_warning_count;
}  // namespace sims::testing

namespace {
void OnMujocoWarning(const char* msg) {
  ++sims::testing::g_warning_count;
  if (sims::testing::g_allow_warnings.load() == 0) ADD_FAILURE() << "MuJoCo warning: " << msg;
}
void OnMujocoError(const char* msg) {
  std::fprintf(stderr, "MuJoCo error: %s\n", msg);
  std::abort();
}
}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // As RunApp does for the apps: the environment is read here, once, and installed.
  sims::InstallEnvironment(sims::ReadEnvironment());
  const std::string& level = sims::InstalledEnvironment().log_level;
  sims::InitLogging(level.empty() ? "warn" : level, "SIMS_LOG_LEVEL");
  mju_user_warning = OnMujocoWarning;
  mju_user_error = OnMujocoError;
  return RUN_ALL_TESTS();
}
