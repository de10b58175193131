#include "sims/core/paths.h"

#include <cstdlib>

namespace sims {

std::filesystem::path ProjectRoot() {
  if (const char* env = std::getenv("SIMS_ROOT"); env && *env) return env;
  return SIMS_SOURCE_ROOT;
}

std::filesystem::path AssetPath(const std::string& relative) {
  return ProjectRoot() / "assets" / relative;
}

std::filesystem::path ConfigPath(const std::string& relative) {
  return ProjectRoot() / "configs" / relative;
}

std::filesystem::path DataPath(const std::string& relative) {
  if (const char* env = std::getenv("SIMS_DATA_DIR"); env && *env)
    return std::filesystem::path(env) / relative;
  return ProjectRoot() / "data" / relative;
}

}  // namespace sims
