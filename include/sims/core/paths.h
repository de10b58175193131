// Locating the project's assets/ and configs/ at run time.
#pragma once

#include <filesystem>
#include <string>

namespace sims {

/// The project root: $SIMS_ROOT if set, else the source tree the binary was built from.
std::filesystem::path ProjectRoot();

/// ProjectRoot()/assets/<relative>.
std::filesystem::path AssetPath(const std::string& relative);

/// ProjectRoot()/configs/<relative>.
std::filesystem::path ConfigPath(const std::string& relative);

/// Setup-time data (npm tarballs, converted vectors): $SIMS_DATA_DIR, else ProjectRoot()/data.
std::filesystem::path DataPath(const std::string& relative);

}  // namespace sims
