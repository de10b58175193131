#include "sims/planner/sentence.h"

#include <initializer_list>
#include <mutex>
#include <optional>
#include <vector>

#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/planner/text.h"
#include "sims/planner/vocabulary.h"

namespace sims::planner {

namespace {

bool HasAny(const std::vector<std::string>& words, std::initializer_list<const char*> keys) {
  for (const auto& w : words)
    for (const char* k : keys)
      if (w == k) return true;
  return false;
}

// The installed sentence config, read once (like Vocabulary::Default()).
const SentenceConfig& DefaultSentenceConfig() {
  static std::once_flag once;
  static const SentenceConfig* config = nullptr;
  std::call_once(once, [] { config = new SentenceConfig(LoadSentenceConfig()); });
  return *config;
}

}  // namespace

SentenceConfig LoadSentenceConfig(const std::filesystem::path& path) {
  const std::filesystem::path file = path.empty() ? ConfigPath("planner/sentence.json") : path;
  SentenceConfig config = LoadConfig<SentenceConfig>(file);
  for (const auto& [word, skill] : config.fallback_verbs)
    if (!Vocabulary::Default().FindSkill(skill))
      ThrowInputError(file.string(), "fallback_verbs." + word, "a skill name or alias",
                      "'" + skill + "'");
  return config;
}

nlohmann::json InstructionToScriptJson(const std::string& sentence) {
  const auto& vocab = Vocabulary::Default();
  const auto words = Words(sentence);
  std::optional<Skill> skill;
  std::string furniture = "floor";
  for (size_t i = 0; i < words.size(); ++i) {
    if (!skill) skill = vocab.FindSkill(words[i]);
    if (!skill && i + 1 < words.size()) skill = vocab.FindSkill(words[i] + " " + words[i + 1]);
    if (furniture == "floor") {
      if (i + 1 < words.size())
        if (auto f = vocab.FindFurniture(words[i] + " " + words[i + 1])) furniture = *f;
      if (furniture == "floor")
        if (auto f = vocab.FindFurniture(words[i])) furniture = *f;
    }
  }
  // Only when no alias matched anywhere: the first word that is a fallback verb wins.
  const auto& verbs = DefaultSentenceConfig().fallback_verbs;
  for (const auto& w : words) {
    if (skill) break;
    if (auto it = verbs.find(w); it != verbs.end()) skill = vocab.FindSkill(it->second);
  }
  if (!skill)
    ThrowInputError("--instruction", "",
                    "a sentence naming an action (walk, sit, lie, reach/touch, get up)",
                    "'" + sentence + "'");
  nlohmann::json k = {
      {"skill", SkillName(*skill)}, {"caption", sentence}, {"furniture", furniture}};
  return {{"keyframes", nlohmann::json::array({k})}};
}

std::string ReachHeightFromCaption(const std::string& caption) {
  const auto w = Words(caption);
  if (HasAny(w, {"low", "lower", "floor", "ground", "bottom", "down", "pick", "bend", "knee"}))
    return "low";
  if (HasAny(w, {"high", "higher", "top", "upper", "shelf", "up", "above", "overhead", "tiptoe"}))
    return "high";
  return "medium";
}

bool ReachUsesLeftHand(const std::string& caption) { return HasAny(Words(caption), {"left"}); }

}  // namespace sims::planner
