// Locating the project's assets/ and configs/ at run time.
#pragma once

#include <filesystem>
#include <string>

namespace sims {

/// The project root: the installed Environment's root ($SIMS_ROOT in the apps), else the source
/// tree the binary was built from.
std::filesystem::path ProjectRoot();

/// ProjectRoot()/assets/<relative>.
std::filesystem::path AssetPath(const std::string& relative);

/// ProjectRoot()/configs/<relative>.
std::filesystem::path ConfigPath(const std::string& relative);

/// Setup-time data (npm tarballs, converted vectors): the installed Environment's data_dir
/// ($SIMS_DATA_DIR in the apps), else ProjectRoot()/data.
std::filesystem::path DataPath(const std::string& relative);

}  // namespace sims
