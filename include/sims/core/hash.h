// Content hashes for provenance (which checkpoint an evaluation measured).
#pragma once

#include <filesystem>
#include <string>

namespace sims {

/// SHA-256 (FIPS 180-4) of a byte string, as 64 lowercase hex digits.
std::string Sha256Hex(const std::string& bytes);

/// SHA-256 of a file's contents; throws sims::Error naming the file when it cannot be read.
std::string Sha256OfFile(const std::filesystem::path& path);

}  // namespace sims
