// Shared test helpers: fixture paths and a guard for tests that expect MuJoCo warnings.
#pragma once

#include <filesystem>
#include <string>

namespace sims::testing {

/// tests/testdata/<relative>.
std::filesystem::path TestData(const std::string& relative);

/// A fresh empty temporary directory, unique per call.
std::filesystem::path TempDir(const std::string& tag);

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
