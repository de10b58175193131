#include "sims/planner/script_answer.h"

#include <set>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/planner/llm_client.h"
#include "sims/planner/text.h"

namespace sims::planner {

using nlohmann::json;

UnknownTerms ParseUnknownTerms(const std::string& name, const std::string& source) {
  if (name == "map") return UnknownTerms::kMap;
  if (name == "reject") return UnknownTerms::kReject;
  ThrowInputError(source, "", "'map' or 'reject'", "'" + name + "'");
}

namespace {

std::string Quote(const std::string& s) { return "'" + s + "'"; }

// The first present key among `keys`, or "".
std::string KeyOf(const json& obj, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (obj.contains(k)) return k;
  return "";
}

// Rewrites one string value (or the first string of a list) through `map`; returns the note.
template <class MapFn>
void MapString(json* value, const std::string& field, MapFn map, std::vector<std::string>* notes) {
  json* target = value;
  if (value->is_array() && !value->empty()) target = &(*value)[0];
  if (!target->is_string()) return;  // the loader reports the wrong type
  std::string text = target->get<std::string>();
  std::string canonical, how;
  if (!map(text, &canonical, &how)) return;
  *target = canonical;
  notes->push_back(field + ": '" + text + "' -> '" + canonical + "' (" + how + ")");
}

// Maps every out-of-vocabulary term of a script object in place.
void MapTerms(json* script, const std::string& source, const Vocabulary& vocab,
              std::vector<std::string>* notes) {
  if (std::string key = KeyOf(*script, {"emotion", "emotions"}); !key.empty()) {
    MapString(
        &(*script)[key], key,
        [&](const std::string& text, std::string* out, std::string* how) {
          for (const std::string& w : SplitList(text, ",;/|"))
            if (vocab.FindEmotion(w)) return false;
          auto m = vocab.NearestEmotion(text);
          if (!m) return false;
          *out = m->canonical;
          *how = m->how;
          return true;
        },
        notes);
  }
  if (std::string key = KeyOf(*script, {"scene", "room", "scene_type"}); !key.empty()) {
    MapString(
        &(*script)[key], key,
        [&](const std::string& text, std::string* out, std::string* how) {
          if (vocab.FindRoomType(text)) return false;
          auto m = vocab.NearestRoomType(text);
          if (!m) return false;
          *out = m->canonical;
          *how = m->how;
          return true;
        },
        notes);
  }
  auto kfs = script->find("keyframes");
  if (kfs == script->end() || !kfs->is_array()) return;
  for (std::size_t i = 0; i < kfs->size(); ++i) {
    json& k = (*kfs)[i];
    if (!k.is_object()) continue;
    std::string f = "keyframes[" + std::to_string(i) + "]";
    std::optional<Skill> skill;
    if (std::string key = KeyOf(k, {"skill", "action"}); !key.empty()) {
      MapString(
          &k[key], f + "." + key,
          [&](const std::string& text, std::string* out, std::string* how) {
            if (vocab.FindSkill(text)) return false;
            auto m = vocab.NearestSkill(text);
            if (!m) return false;
            *out = m->canonical;
            *how = m->how;
            return true;
          },
          notes);
      if (k[key].is_string()) skill = vocab.FindSkill(k[key].get<std::string>());
    }
    std::string key = KeyOf(k, {"furniture", "furnitures", "object", "target"});
    if (key.empty()) continue;
    std::string field = f + "." + key;
    MapString(
        &k[key], field,
        [&](const std::string& text, std::string* out, std::string* how) {
          if (Trim(text).empty() || vocab.FindFurniture(text)) return false;
          auto m = vocab.NearestFurniture(text);
          if (!m)
            ThrowInputError(source, field,
                            "a furniture category of the vocabulary (" + vocab.FurnitureList() +
                                ") or a name close to one; nothing close was found",
                            Quote(text));
          *out = m->canonical;
          *how = m->how;
          return true;
        },
        notes);
    // A category that cannot carry the skill ("sit" on a table) is swapped for its cheapest
    // substitute that can, when the vocabulary lists one.
    json* value = k[key].is_array() && !k[key].empty() ? &k[key][0] : &k[key];
    if (!skill || !IsInteraction(*skill) || !value->is_string()) continue;
    auto category = vocab.FindFurniture(value->get<std::string>());
    if (!category || vocab.Affords(*category, *skill)) continue;
    for (const std::string& sub : vocab.Substitutes(*category)) {
      if (!vocab.Affords(sub, *skill)) continue;
      notes->push_back(field + ": '" + *category + "' -> '" + sub + "' (a " + *category +
                       " cannot be used to " + SkillName(*skill) + "; nearest substitute)");
      *value = sub;
      break;
    }
  }
}

}  // namespace

ShortScript ValidateScriptAnswer(const json& answer, const std::string& source,
                                 UnknownTerms unknown, std::vector<std::string>* notes,
                                 const Vocabulary& vocab) {
  std::vector<std::string> local_notes;
  if (!notes) notes = &local_notes;
  json script = answer;
  // Models sometimes wrap the one script they were asked for.
  if (script.is_object() && !script.contains("keyframes")) {
    if (auto it = script.find("script"); it != script.end() && it->is_object()) {
      script = *it;
    } else if (auto s = script.find("scripts");
               s != script.end() && s->is_array() && s->size() == 1 && (*s)[0].is_object()) {
      script = (*s)[0];
    }
  }
  if (!script.is_object())
    ThrowInputError(source, "", "one JSON object {summary, emotion, scene, keyframes}",
                    config_internal::JsonTypeName(script));
  script.erase("id");  // the caller names the file; a model's id would collide
  if (unknown == UnknownTerms::kMap) MapTerms(&script, source, vocab, notes);
  ShortScript s = ParseShortScript(script, source, GrammarMode::kLenient, vocab);
  std::size_t before = s.keyframes.size();
  s.keyframes = InsertTransitions(s.keyframes, source, vocab);
  if (s.keyframes.size() > before)
    notes->push_back("inserted " + std::to_string(s.keyframes.size() - before) +
                     " walk/get-up keyframe(s) the grammar needs");
  CheckDatabaseScript(s, source, vocab);
  return s;
}

ShortScript ParseScriptAnswer(const std::string& text, const std::string& source,
                              UnknownTerms unknown, std::vector<std::string>* notes,
                              const Vocabulary& vocab) {
  std::string stripped = StripToJson(text);
  json j;
  try {
    j = json::parse(stripped);
  } catch (const json::exception&) {  // parse_error, or out_of_range for a huge number
    // The loader's message explains single quotes and other common defects.
    (void)ParseShortScriptText(stripped, source, GrammarMode::kLenient, vocab);
    ThrowInputError(source, "", "a JSON object", "unparsable text");
  }
  return ValidateScriptAnswer(j, source, unknown, notes, vocab);
}

void CheckDatabaseScript(const ShortScript& s, const std::string& source, const Vocabulary& vocab) {
  if (Trim(s.summary).empty())
    ThrowInputError(source, "summary", "a one-sentence summary of the clip", "nothing");
  ThrowOnGrammarIssues(CheckGrammar(s.keyframes, vocab), source, "keyframes", GrammarMode::kStrict);
  if (s.Interactions() < 1)
    ThrowInputError(source, "keyframes", "at least one sit, lie or reach keyframe",
                    "only walks and get-ups");
  if (static_cast<int>(s.keyframes.size()) > kMaxShortScriptKeyframes)
    ThrowInputError(source, "keyframes",
                    "at most " + std::to_string(kMaxShortScriptKeyframes) +
                        " keyframes including inserted walks and get-ups (a short script: one "
                        "emotion in one room)",
                    std::to_string(s.keyframes.size()));
}

std::string KeyframeSignature(const std::vector<Keyframe>& keyframes) {
  std::string sig;
  for (const Keyframe& k : keyframes)
    sig += std::string(SkillName(k.skill)) + ":" + k.furniture + "#" + std::to_string(k.instance) +
           ":" + k.style + ";";
  return sig;
}

void WriteShortScript(const std::filesystem::path& path, ShortScript script,
                      const json& provenance) {
  script.id = path.stem().string();
  json j = ShortScriptToJson(script);
  if (!provenance.is_null()) j["provenance"] = provenance;
  WriteJsonFile(path, j);
}

}  // namespace sims::planner
