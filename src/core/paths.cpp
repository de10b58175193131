#include "sims/core/paths.h"

#include "sims/core/environment.h"

namespace sims {

std::filesystem::path ProjectRoot() {
  const std::filesystem::path& root = InstalledEnvironment().root;
  return root.empty() ? std::filesystem::path(SIMS_SOURCE_ROOT) : root;
}

std::filesystem::path AssetPath(const std::string& relative) {
  return ProjectRoot() / "assets" / relative;
}

std::filesystem::path ConfigPath(const std::string& relative) {
  return ProjectRoot() / "configs" / relative;
}

std::filesystem::path DataPath(const std::string& relative) {
  const std::filesystem::path& data = InstalledEnvironment().data_dir;
  return (data.empty() ? ProjectRoot() / "data" : data) / relative;
}

}  // namespace sims
