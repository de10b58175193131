// Shared pieces of the libFuzzer harnesses (tools/fuzz.sh): the loaders under test read files,
// so each input is written to a per-process scratch file first; sims::Error is the expected
// answer to bad input, anything else that escapes (another exception, a crash, a sanitizer
// report, a leak, a hang) is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace sims::fuzz {

/// The input as text.
inline std::string Text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// <tmp>/sims_fuzz_<pid>: this process's scratch directory.
inline const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("sims_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

/// Writes the input to ScratchDir()/<name> (overwritten each call) and returns it.
inline std::filesystem::path ScratchFile(const uint8_t* data, size_t size,
                                         const std::string& name) {
  const auto path = ScratchDir() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// tests/testdata/<relative> (fixtures the loaders resolve references against).
inline std::filesystem::path TestData(const std::string& relative) {
  return std::filesystem::path(SIMS_TESTDATA_DIR) / relative;
}

}  // namespace sims::fuzz
