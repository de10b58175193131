#include "common/test_util.h"

#include <atomic>
#include <cstdlib>
#include <random>

#include <unistd.h>

namespace sims::testing {

std::atomic<int> g_allow_warnings{0};
std::atomic<int> g_warning_count{0};

std::filesystem::path TestData(const std::string& relative) {
  return std::filesystem::path(SIMS_TESTDATA_DIR) / relative;
}

std::filesystem::path TempDir(const std::string& tag) {
  static std::atomic<int> counter{0};
  auto dir =
      std::filesystem::temp_directory_path() /
      ("sims_test_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

ScopedAllowMujocoWarnings::ScopedAllowMujocoWarnings() : start_(g_warning_count.load()) {
  ++g_allow_warnings;
}
ScopedAllowMujocoWarnings::~ScopedAllowMujocoWarnings() { --g_allow_warnings; }
int ScopedAllowMujocoWarnings::count() const { return g_warning_count.load() - start_; }

}  // namespace sims::testing
