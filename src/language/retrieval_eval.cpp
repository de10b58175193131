#include "sims/language/retrieval_eval.h"

#include <regex>

#include "sims/core/config.h"
#include "sims/core/error.h"

namespace sims::language {

std::string ClipStyleOf(const std::string& clip_name) {
  std::string s = clip_name;
  bool mirrored = false;
  for (const std::string suffix : {"#mirror", "_mirror"}) {
    const auto pos = s.find(suffix);
    if (pos != std::string::npos) {
      s.erase(pos, suffix.size());
      mirrored = true;
    }
  }
  s = std::regex_replace(s, std::regex("_v[0-9]+"), "");
  if (mirrored) {
    s = std::regex_replace(s, std::regex("left"), "#L#");
    s = std::regex_replace(s, std::regex("right"), "left");
    s = std::regex_replace(s, std::regex("#L#"), "right");
  }
  return s;
}

nlohmann::json EvaluateRetrieval(const StyleEmbedder& embedder, const std::filesystem::path& path) {
  const auto j = ReadJsonFile(path);
  if (!j.contains("queries") || !j["queries"].is_array())
    ThrowInputError(path.string(), "queries", "an array of {caption, clip}", "missing");
  nlohmann::json rows = nlohmann::json::array();
  int correct = 0, total = 0;
  for (size_t i = 0; i < j["queries"].size(); ++i) {
    const auto& q = j["queries"][i];
    if (!q.contains("caption") || !q.contains("clip"))
      ThrowInputError(path.string(), "queries[" + std::to_string(i) + "]", "{caption, clip}",
                      q.dump());
    const auto r = embedder.Lookup(q["caption"].get<std::string>(), 1);
    const std::string got = r.clips.empty() ? "" : r.clips.front().clip;
    const bool ok = ClipStyleOf(got) == q["clip"].get<std::string>();
    correct += ok;
    ++total;
    rows.push_back({{"caption", q["caption"]},
                    {"expected", q["clip"]},
                    {"retrieved", got},
                    {"cosine", r.clips.empty() ? 0.0 : r.clips.front().cosine},
                    {"correct", ok}});
  }
  return {{"accuracy", total ? static_cast<double>(correct) / total : 0.0},
          {"correct", correct},
          {"total", total},
          {"queries", rows}};
}

}  // namespace sims::language
