#include "sims/core/config.h"

#include <atomic>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace sims {
namespace config_internal {

std::string JsonTypeName(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    case nlohmann::json::value_t::number_float:
      return "a number";
    default:
      return "an integer";
  }
}

std::string Abbreviate(const nlohmann::json& j) {
  std::string s = j.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

}  // namespace config_internal

void JsonReadArchive::CheckNoUnknownKeys() const {
  if (allow_unknown_ || !j_.is_object()) return;
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    if (seen_.count(it.key())) continue;
    std::string known;
    for (const auto& k : seen_) known += (known.empty() ? "" : ", ") + k;
    throw FieldError(it.key(), "a known field (one of: " + known + ")", "an unknown field");
  }
}

nlohmann::json ReadJsonFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in)
    ThrowInputError(path.string(), "", "a readable JSON file", "a missing or unreadable file");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // Turn the byte offset into line:column so a user can find the mistake.
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i < text.size() && i + 1 < e.byte; ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    std::string what = e.what();
    auto pos = what.find("syntax error");
    throw Error(path.string() + ":" + std::to_string(line) + ":" + std::to_string(col) +
                ": expected valid JSON (" + (pos == std::string::npos ? what : what.substr(pos)) +
                ")");
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond double range ("3e40000000000000") is not a parse_error in nlohmann.
    ThrowInputError(path.string(), "", "valid JSON with numbers a double can hold", e.what());
  }
}

void WriteFileAtomic(const std::filesystem::path& path, const std::string& content) {
  static std::atomic<int> counter{0};
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::filesystem::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) ThrowInputError(path.string(), "", "a writable location", "cannot create file");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      ThrowInputError(path.string(), "", "a writable location", "write failed (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    ThrowInputError(path.string(), "", "a writable location", "rename failed");
  }
}

void WriteJsonFile(const std::filesystem::path& path, const nlohmann::json& j) {
  WriteFileAtomic(path, j.dump(2) + "\n");
}

}  // namespace sims
