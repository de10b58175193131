#include "common/test_util.h"

#include <atomic>
#include <cstdlib>
#include <random>

#include <unistd.h>

#include "sims/core/config.h"
#include "sims/core/error.h"

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

namespace {

void Compare(const nlohmann::json& file, const nlohmann::json& defaults, const std::string& path,
             const std::set<std::string>& allowed, std::vector<std::string>* out) {
  if (allowed.count(path)) return;
  const std::string name = path.empty() ? "(root)" : path;
  if (file.is_object() && defaults.is_object()) {
    const std::string prefix = path.empty() ? "" : path + ".";
    for (const auto& [key, value] : defaults.items()) {
      if (allowed.count(prefix + key)) continue;
      if (!file.contains(key))
        out->push_back(prefix + key + ": missing from the file (default " + value.dump() + ")");
      else
        Compare(file[key], value, prefix + key, allowed, out);
    }
    for (const auto& [key, value] : file.items())
      if (!defaults.contains(key) && !allowed.count(prefix + key))
        out->push_back(prefix + key + ": in the file but not a field of the struct");
    return;
  }
  // json compares integers and floats by value, so 2 and 2.0 agree.
  if (file != defaults)
    out->push_back(name + ": file " + file.dump() + ", default " + defaults.dump());
}

}  // namespace

std::vector<std::string> ConfigFileDifferences(const std::filesystem::path& file,
                                               const nlohmann::json& defaults,
                                               const std::set<std::string>& allowed) {
  std::vector<std::string> out;
  Compare(ReadJsonFile(file), defaults, "", allowed, &out);
  return out;
}

ScopedAllowMujocoWarnings::ScopedAllowMujocoWarnings() : start_(g_warning_count.load()) {
  ++g_allow_warnings;
}
ScopedAllowMujocoWarnings::~ScopedAllowMujocoWarnings() { --g_allow_warnings; }
int ScopedAllowMujocoWarnings::count() const { return g_warning_count.load() - start_; }

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace sims::testing
