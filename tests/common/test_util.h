// Shared test helpers: fixture paths and a guard for tests that expect MuJoCo warnings.
#pragma once

#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sims::testing {

/// tests/testdata/<relative>.
std::filesystem::path TestData(const std::string& relative);

/// The message of the sims::Error `f` throws, or "" when it throws none.
std::string ErrorOf(const std::function<void()>& f);

/// A fresh empty temporary directory, unique per call.
std::filesystem::path TempDir(const std::string& tag);

/// Where a config file disagrees with its struct's defaults (`defaults`, ConfigToJson of a
/// default-constructed struct): one line per differing value ("spawn_radius: file 2.0, default
/// 0.0"), per field the file lacks and per key that is no field. Dotted paths in `allowed`
/// (intentional differences) are skipped.
std::vector<std::string> ConfigFileDifferences(const std::filesystem::path& file,
                                               const nlohmann::json& defaults,
                                               const std::set<std::string>& allowed = {});

/// While alive, MuJoCo warnings are counted instead of failing the current test.
class ScopedAllowMujocoWarnings {
 public:
  ScopedAllowMujocoWarnings();
  ~ScopedAllowMujocoWarnings();
  /// Warnings seen since construction.
  int count() const;

 private:
  int start_;
};

}  // namespace sims::testing
