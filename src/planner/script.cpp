#include "sims/planner/script.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <spdlog/spdlog.h>

#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/planner/text.h"

namespace sims::planner {

using nlohmann::json;

std::string ShortScript::Text() const {
  std::string t = summary;
  for (const Keyframe& k : keyframes) {
    t += ". " + k.caption;
    if (k.furniture != "floor") {
      std::string f = k.furniture;
      std::replace(f.begin(), f.end(), '_', ' ');
      t += " " + f;
    }
  }
  return t;
}

int ShortScript::Interactions() const {
  return static_cast<int>(std::count_if(keyframes.begin(), keyframes.end(),
                                        [](const Keyframe& k) { return IsInteraction(k.skill); }));
}

namespace {

std::string Quote(const std::string& s) { return "'" + s + "'"; }

std::string Abbrev(const json& j) {
  std::string s = j.dump();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

std::string WithSuggestion(const std::string& expected, const std::string& got,
                           const std::vector<std::string>& names) {
  std::string closest = Vocabulary::Closest(got, names);
  return closest.empty() ? expected : expected + " (did you mean " + Quote(closest) + "?)";
}

// Collects strings from a string ("tired, sad") or an array of strings.
std::vector<std::string> StringList(const json& j, const std::string& source,
                                    const std::string& field) {
  std::vector<std::string> out;
  auto add = [&](const std::string& s) {
    for (std::string part : SplitList(s, ",;/|")) {
      // "tired and sad" → two tags.
      std::string lower = ToLower(part);
      std::size_t pos;
      while ((pos = lower.find(" and ")) != std::string::npos) {
        out.push_back(Trim(part.substr(0, pos)));
        part = part.substr(pos + 5);
        lower = lower.substr(pos + 5);
      }
      if (!Trim(part).empty()) out.push_back(Trim(part));
    }
  };
  if (j.is_string()) {
    add(j.get<std::string>());
  } else if (j.is_array()) {
    for (const json& e : j) {
      if (!e.is_string())
        ThrowInputError(source, field, "a string or a list of strings", Abbrev(j));
      add(e.get<std::string>());
    }
  } else if (!j.is_null()) {
    ThrowInputError(source, field, "a string or a list of strings", Abbrev(j));
  }
  return out;
}

std::vector<std::string> FurnitureNames(const Vocabulary& vocab) {
  std::vector<std::string> v;
  for (const auto& f : vocab.furniture) {
    v.push_back(f.name);
    for (const auto& a : f.aliases) v.push_back(a);
  }
  return v;
}

std::vector<std::string> SkillNames(const Vocabulary& vocab) {
  std::vector<std::string> v;
  for (const auto& s : vocab.skills) {
    v.push_back(s.name);
    for (const auto& a : s.aliases) v.push_back(a);
  }
  return v;
}

std::string CanonicalEmotion(const json& j, const std::string& source, const std::string& field,
                             const Vocabulary& vocab) {
  std::vector<std::string> words = StringList(j, source, field);
  if (words.empty())
    ThrowInputError(source, field, "an emotion (" + vocab.EmotionList() + ")", "an empty value");
  for (const std::string& w : words)
    if (auto e = vocab.FindEmotion(w)) return *e;
  std::vector<std::string> names;
  for (const auto& e : vocab.emotions) names.push_back(e.name);
  ThrowInputError(source, field,
                  WithSuggestion("one of " + vocab.EmotionList(), words.front(), names),
                  Quote(Join(words, ", ")));
}

// A furniture value: a string or a list whose first string is used.
std::string FurnitureValue(const json& j, const std::string& source, const std::string& field) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_array() && !j.empty() && j[0].is_string()) {
    if (j.size() > 1)
      spdlog::warn("{}: field '{}': several furniture items given, using the first ('{}')", source,
                   field, j[0].get<std::string>());
    return j[0].get<std::string>();
  }
  ThrowInputError(source, field, "a furniture category string", Abbrev(j));
}

const json* FindKey(const json& obj, std::initializer_list<const char*> keys, std::string* used) {
  for (const char* k : keys) {
    auto it = obj.find(k);
    if (it != obj.end()) {
      if (used) *used = k;
      return &*it;
    }
  }
  return nullptr;
}

}  // namespace

std::vector<Keyframe> ParseKeyframes(const json& j, const std::string& source,
                                     const std::string& field, const std::string& script_emotion,
                                     const Vocabulary& vocab) {
  if (!j.is_array() || j.empty())
    ThrowInputError(source, field, "a non-empty list of keyframe objects", Abbrev(j));
  std::vector<Keyframe> out;
  static const std::set<std::string> kKnown = {
      "skill",  "action",        "furniture",     "furnitures", "object",
      "target", "emotion/style", "emotion_style", "emotion",    "emotions",
      "style",  "caption",       "description",   "instance"};
  for (std::size_t i = 0; i < j.size(); ++i) {
    const json& kj = j[i];
    std::string f = field + "[" + std::to_string(i) + "]";
    if (!kj.is_object())
      ThrowInputError(source, f, "a keyframe object {skill, emotion/style, caption, furniture}",
                      Abbrev(kj));
    for (auto it = kj.begin(); it != kj.end(); ++it)
      if (!kKnown.count(it.key()))
        spdlog::warn("{}: field '{}.{}' is not part of the keyframe format; ignored", source, f,
                     it.key());
    Keyframe k;
    // Skill.
    std::string key;
    const json* skill = FindKey(kj, {"skill", "action"}, &key);
    if (!skill || !skill->is_string())
      ThrowInputError(source, f + ".skill", "a skill name (" + vocab.SkillList() + ")",
                      skill ? Abbrev(*skill) : "nothing");
    std::string skill_name = skill->get<std::string>();
    auto s = vocab.FindSkill(skill_name);
    if (!s)
      ThrowInputError(
          source, f + "." + key,
          WithSuggestion("one of " + vocab.SkillList() +
                             " or an alias (loco, sitdown, liedown, touch, standup, getup)",
                         skill_name, SkillNames(vocab)),
          Quote(skill_name));
    k.skill = *s;
    // Caption.
    if (const json* c = FindKey(kj, {"caption", "description"}, &key)) {
      if (!c->is_string()) ThrowInputError(source, f + "." + key, "a string", Abbrev(*c));
      k.caption = Trim(c->get<std::string>());
    }
    // Emotion / style tags.
    std::string explicit_style;
    std::vector<std::string> hints;
    for (const char* mood_key :
         {"emotion/style", "emotion_style", "emotion", "emotions", "style"}) {
      auto it = kj.find(mood_key);
      if (it == kj.end()) continue;
      std::string mf = f + "." + mood_key;
      for (const std::string& tag : StringList(*it, source, mf)) {
        std::string squashed = Vocabulary::Squash(tag);
        std::string underscored = ToLower(tag);
        std::replace(underscored.begin(), underscored.end(), ' ', '_');
        if (auto e = vocab.FindEmotion(tag)) {
          k.tags.push_back(*e);
        } else if (vocab.IsValidStyle(k.skill, underscored)) {
          explicit_style = underscored;
          k.tags.push_back(tag);
        } else {
          hints.push_back(tag);
          k.tags.push_back(tag);
        }
      }
    }
    k.emotion = script_emotion;
    for (const std::string& t : k.tags)
      if (auto e = vocab.FindEmotion(t)) {
        k.emotion = *e;
        break;
      }
    // Furniture.
    const json* fur = FindKey(kj, {"furniture", "furnitures", "object", "target"}, &key);
    std::string fur_name;
    if (fur && !fur->is_null()) fur_name = Trim(FurnitureValue(*fur, source, f + "." + key));
    if (fur_name.empty()) {
      if (k.skill == Skill::kWalk || k.skill == Skill::kGetUp) {
        fur_name = "floor";
      } else {
        ThrowInputError(source, f + ".furniture",
                        std::string("a furniture category for '") + SkillName(k.skill) + "' (" +
                            Join(vocab.CategoriesAffording(k.skill), ", ") + ")",
                        "nothing");
      }
    }
    auto canonical = vocab.FindFurniture(fur_name);
    if (!canonical)
      ThrowInputError(source, f + "." + (key.empty() ? "furniture" : key),
                      WithSuggestion("a known furniture category (" + vocab.FurnitureList() +
                                         "; see configs/planner/vocabulary.json)",
                                     fur_name, FurnitureNames(vocab)),
                      Quote(fur_name));
    k.furniture = *canonical;
    if (k.skill != Skill::kWalk && k.skill != Skill::kGetUp && !vocab.Affords(k.furniture, k.skill))
      ThrowInputError(source, f + "." + (key.empty() ? "furniture" : key),
                      std::string("furniture that affords '") + SkillName(k.skill) + "' (" +
                          Join(vocab.CategoriesAffording(k.skill), ", ") + ")",
                      Quote(k.furniture));
    if (const json* inst = FindKey(kj, {"instance"}, nullptr)) {
      if (!inst->is_number_integer() || inst->get<int>() < 0)
        ThrowInputError(source, f + ".instance", "a non-negative integer", Abbrev(*inst));
      k.instance = inst->get<int>();
    }
    // Style: an explicit id wins, then caption and hint words, then the emotion's default.
    if (!explicit_style.empty()) {
      k.style = explicit_style;
      k.style_from_caption = true;
    } else {
      std::string text = k.caption;
      for (const std::string& h : hints) text += " " + h;
      StyleChoice c = vocab.ResolveStyle(k.skill, text, k.emotion);
      k.style = c.id;
      k.style_from_caption = c.from_caption;
    }
    out.push_back(std::move(k));
  }
  return out;
}

ShortScript ParseShortScript(const json& j, const std::string& source, GrammarMode mode,
                             const Vocabulary& vocab) {
  if (!j.is_object())
    ThrowInputError(source, "", "a JSON object {summary, emotion, scene, keyframes}", Abbrev(j));
  // "provenance" (where a script came from: video frames, imitated sources) is kept for people
  // and ignored by the planner.
  static const std::set<std::string> kKnown = {"id",    "summary",     "emotion",    "emotions",
                                               "scene", "room",        "scene_type", "keyframes",
                                               "title", "description", "provenance"};
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!kKnown.count(it.key()))
      spdlog::warn("{}: field '{}' is not part of the short-script format; ignored", source,
                   it.key());
  ShortScript s;
  s.source = source;
  std::string key;
  if (const json* id = FindKey(j, {"id"}, nullptr)) {
    if (!id->is_string()) ThrowInputError(source, "id", "a string", Abbrev(*id));
    s.id = id->get<std::string>();
  }
  if (const json* sum = FindKey(j, {"summary", "description", "title"}, &key)) {
    if (!sum->is_string()) ThrowInputError(source, key, "a string", Abbrev(*sum));
    s.summary = Trim(sum->get<std::string>());
  }
  if (const json* e = FindKey(j, {"emotion", "emotions"}, &key))
    s.emotion = CanonicalEmotion(*e, source, key, vocab);
  if (const json* sc = FindKey(j, {"scene", "room", "scene_type"}, &key)) {
    if (!sc->is_string()) ThrowInputError(source, key, "a room type string", Abbrev(*sc));
    auto room = vocab.FindRoomType(sc->get<std::string>());
    if (!room) {
      std::vector<std::string> names;
      for (const auto& r : vocab.room_types) names.push_back(r.name);
      ThrowInputError(source, key,
                      WithSuggestion("a room type (" + vocab.RoomTypeList() + ")",
                                     sc->get<std::string>(), names),
                      Quote(sc->get<std::string>()));
    }
    s.scene = *room;
  }
  const json* kfs = FindKey(j, {"keyframes"}, nullptr);
  if (!kfs) ThrowInputError(source, "keyframes", "a non-empty list of keyframes", "nothing");
  s.keyframes = ParseKeyframes(*kfs, source, "keyframes", s.emotion, vocab);
  ThrowOnGrammarIssues(CheckGrammar(s.keyframes, vocab), source, "keyframes", mode);
  return s;
}

ShortScript ParseShortScriptText(const std::string& text, const std::string& source,
                                 GrammarMode mode, const Vocabulary& vocab) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    // Python-style dicts are the most common non-JSON an LLM or a person produces.
    std::string squeezed;
    for (char c : text)
      if (!std::isspace(static_cast<unsigned char>(c))) squeezed += c;
    bool single_quoted =
        squeezed.find("{'") != std::string::npos || squeezed.find("':") != std::string::npos ||
        squeezed.find("['") != std::string::npos || squeezed.find("','") != std::string::npos;
    if (single_quoted)
      ThrowInputError(source, "",
                      "JSON with double-quoted keys and strings; this file uses single quotes "
                      "(a Python dict?): replace ' by \" around every key and string value",
                      "single-quoted text");
    std::string what = e.what();
    auto pos = what.find("parse error");
    ThrowInputError(source, "", "valid JSON", pos == std::string::npos ? what : what.substr(pos));
  } catch (const json::out_of_range& e) {
    // A number too large for a double (found by the script fuzzer: "3e40000000000000").
    ThrowInputError(source, "", "valid JSON with numbers a double can hold", e.what());
  }
  return ParseShortScript(j, source, mode, vocab);
}

ShortScript LoadShortScript(const std::filesystem::path& path, GrammarMode mode,
                            const Vocabulary& vocab) {
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowInputError(path.string(), "", "a readable short-script JSON file", "no such file");
  std::stringstream ss;
  ss << in.rdbuf();
  ShortScript s = ParseShortScriptText(ss.str(), path.string(), mode, vocab);
  if (s.id.empty()) s.id = path.stem().string();
  for (Keyframe& k : s.keyframes) k.script_id = s.id;
  return s;
}

json KeyframesToJson(const std::vector<Keyframe>& keyframes) {
  json arr = json::array();
  for (const Keyframe& k : keyframes) {
    json kj;
    kj["skill"] = SkillName(k.skill);
    // The style is written on its own; repeating it (or a tag twice) among the mood words would
    // make every load/save round trip grow the list.
    std::vector<std::string> tags;
    for (const std::string& t : k.tags)
      if (t != k.style && std::find(tags.begin(), tags.end(), t) == tags.end()) tags.push_back(t);
    if (tags.empty()) tags.push_back(k.emotion);
    kj["emotion/style"] = Join(tags, ", ");
    kj["style"] = k.style;
    kj["caption"] = k.caption;
    kj["furniture"] = k.furniture;
    if (k.instance != 0) kj["instance"] = k.instance;
    arr.push_back(kj);
  }
  return arr;
}

json ShortScriptToJson(const ShortScript& s) {
  json j;
  j["id"] = s.id;
  j["summary"] = s.summary;
  j["emotion"] = s.emotion;
  j["scene"] = s.scene;
  j["keyframes"] = KeyframesToJson(s.keyframes);
  return j;
}

// ---------------------------------------------------------------------------------------------
// Grammar.

namespace {

enum class Posture { kStanding, kSeated, kLying };

// Objects are identified by category and instance index; the segment (short script) is carried
// along for inserted keyframes but does not distinguish objects, matching the required graph's
// consolidation (the sofa of one short script is the sofa of the next).
struct ObjectRef {
  std::string category;
  int instance = 0;
  int segment = 0;
  bool operator==(const ObjectRef& o) const {
    return category == o.category && instance == o.instance;
  }
};

ObjectRef RefOf(const Keyframe& k) { return {k.furniture, k.instance, k.segment}; }

std::string Pretty(const std::string& category) {
  std::string s = category;
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

struct GrammarState {
  Posture posture = Posture::kStanding;
  ObjectRef on;             // object sat/lain on
  bool near_any = false;    // last walk went to "the floor": it approaches whatever comes next
  bool near_known = false;  // `near` holds an object
  ObjectRef near;
};

}  // namespace

std::vector<GrammarIssue> CheckGrammar(const std::vector<Keyframe>& keyframes,
                                       const Vocabulary& vocab) {
  (void)vocab;
  std::vector<GrammarIssue> issues;
  GrammarState st;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const Keyframe& k = keyframes[i];
    int idx = static_cast<int>(i);
    const char* where = st.posture == Posture::kSeated ? "sitting on" : "lying on";
    switch (k.skill) {
      case Skill::kWalk:
        if (st.posture != Posture::kStanding)
          issues.push_back({idx, "skill",
                            std::string("a get-up before walking (the character is still ") +
                                where + " the " + Pretty(st.on.category) + ")",
                            true});
        st.posture = Posture::kStanding;
        st.near_any = k.furniture == "floor";
        st.near_known = !st.near_any;
        st.near = RefOf(k);
        break;
      case Skill::kGetUp:
        // A get-up from the floor right after a walk is what a script writes after a fall (a
        // drunk character has fallen): the FSM's get-up succeeds at once if it stands.
        if (st.posture == Posture::kStanding && k.furniture == "floor" && i > 0 &&
            keyframes[i - 1].skill == Skill::kWalk) {
          st.near_any = false;
          st.near_known = false;
          break;
        }
        if (st.posture == Posture::kStanding) {
          issues.push_back({idx, "skill",
                            "get-up only after sit or lie, or from the floor right after a walk "
                            "(the character is already standing)",
                            false});
          break;
        }
        if (k.furniture != "floor" && k.furniture != st.on.category) {
          issues.push_back(
              {idx, "furniture",
               "the object the character is " + std::string(where) + " ('" + st.on.category + "')",
               false});
        }
        st.posture = Posture::kStanding;
        st.near_any = false;
        st.near_known = true;
        st.near = st.on;
        break;
      case Skill::kSit:
      case Skill::kLie:
      case Skill::kReach: {
        ObjectRef target = RefOf(k);
        if (st.posture != Posture::kStanding) {
          bool same = st.on == target && k.skill != Skill::kReach;
          if (!same) {
            issues.push_back(
                {idx, "skill",
                 std::string("a get-up") +
                     (st.on == target ? "" : " and a walk to the " + Pretty(k.furniture)) +
                     " first (the character is still " + where + " the " + Pretty(st.on.category) +
                     ")",
                 true});
          }
        } else if (!st.near_any && !(st.near_known && st.near == target)) {
          std::string why = st.near_known ? "the character is at the " + Pretty(st.near.category)
                                          : "the character has not walked anywhere yet";
          issues.push_back(
              {idx, "skill",
               "a walk to the " + Pretty(k.furniture) + " before this keyframe (" + why + ")",
               true});
        }
        if (k.skill == Skill::kReach) {
          st.posture = Posture::kStanding;
        } else {
          st.posture = k.skill == Skill::kSit ? Posture::kSeated : Posture::kLying;
          st.on = target;
        }
        st.near_any = false;
        st.near_known = true;
        st.near = target;
        break;
      }
    }
  }
  return issues;
}

void ThrowOnGrammarIssues(const std::vector<GrammarIssue>& issues, const std::string& source,
                          const std::string& field_prefix, GrammarMode mode) {
  for (const GrammarIssue& g : issues) {
    if (g.fixable && mode == GrammarMode::kLenient) continue;
    ThrowInputError(source, field_prefix + "[" + std::to_string(g.index) + "]." + g.field,
                    g.message);
  }
}

std::vector<Keyframe> InsertTransitions(const std::vector<Keyframe>& keyframes,
                                        const std::string& source, const Vocabulary& vocab) {
  ThrowOnGrammarIssues(CheckGrammar(keyframes, vocab), source, "keyframes", GrammarMode::kLenient);
  std::vector<Keyframe> out;
  GrammarState st;
  auto make = [&](Skill skill, const Keyframe& like, const ObjectRef& obj) {
    Keyframe k;
    k.skill = skill;
    k.emotion = like.emotion;
    k.tags = {like.emotion};
    k.furniture = obj.category;
    k.instance = obj.instance;
    k.segment = obj.segment;
    k.script_id = like.script_id;
    k.inserted = true;
    k.style = vocab.ResolveStyle(skill, "", k.emotion).id;
    return k;
  };
  auto get_up = [&](const Keyframe& like) {
    Keyframe g = make(Skill::kGetUp, like, st.on);
    g.style = st.posture == Posture::kLying ? "bed" : "seat";
    g.caption = "gets up from the " + Pretty(st.on.category);
    out.push_back(g);
    st.posture = Posture::kStanding;
    st.near_any = false;
    st.near_known = true;
    st.near = st.on;
  };
  for (const Keyframe& in : keyframes) {
    Keyframe k = in;
    if (k.skill == Skill::kWalk) {
      if (st.posture != Posture::kStanding) get_up(k);
      st.near_any = k.furniture == "floor";
      st.near_known = !st.near_any;
      st.near = RefOf(k);
    } else if (k.skill == Skill::kGetUp && st.posture == Posture::kStanding) {
      // (CheckGrammar let it through: from the floor right after a walk.)
      k.style = "floor";  // from the floor, where the character is (see CheckGrammar)
      k.furniture = "floor";
      st.near_any = false;
      st.near_known = false;
    } else if (k.skill == Skill::kGetUp) {
      k.style = st.posture == Posture::kLying ? "bed" : "seat";
      k.furniture = st.on.category;
      k.instance = st.on.instance;
      k.segment = st.on.segment;
      st.posture = Posture::kStanding;
      st.near_any = false;
      st.near_known = true;
      st.near = st.on;
    } else {
      ObjectRef target = RefOf(k);
      if (st.posture != Posture::kStanding && !(st.on == target && k.skill != Skill::kReach))
        get_up(k);
      if (st.posture == Posture::kStanding && !st.near_any &&
          !(st.near_known && st.near == target)) {
        Keyframe w = make(Skill::kWalk, k, target);
        std::string style_text = vocab.StyleText(Skill::kWalk, w.style);
        w.caption =
            "walks to the " + Pretty(k.furniture) + (style_text.empty() ? "" : " " + style_text);
        out.push_back(w);
      }
      if (k.skill == Skill::kReach) {
        st.posture = Posture::kStanding;
      } else {
        st.posture = k.skill == Skill::kSit ? Posture::kSeated : Posture::kLying;
        st.on = target;
      }
      st.near_any = false;
      st.near_known = true;
      st.near = target;
    }
    out.push_back(std::move(k));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------

ScriptDatabase::ScriptDatabase(std::vector<ShortScript> scripts) : scripts_(std::move(scripts)) {}

ScriptDatabase ScriptDatabase::Load(const std::filesystem::path& dir, const Vocabulary& vocab) {
  return LoadWithExtras(dir, {}, vocab);
}

ScriptDatabase ScriptDatabase::LoadWithExtras(const std::filesystem::path& dir_in,
                                              const std::vector<std::filesystem::path>& extras,
                                              const Vocabulary& vocab) {
  std::filesystem::path dir = dir_in.empty() ? AssetPath("scripts") : dir_in;
  if (!std::filesystem::is_directory(dir))
    ThrowInputError(dir.string(), "", "a folder of short-script JSON files", "no such folder");
  auto json_files = [](const std::filesystem::path& root) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root))
      if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
  };
  std::vector<std::filesystem::path> files = json_files(dir);
  for (const auto& extra : extras) {
    if (std::filesystem::is_directory(extra)) {
      std::vector<std::filesystem::path> more = json_files(extra);
      if (more.empty())
        ThrowInputError(extra.string(), "", "a folder holding *.json short scripts", "none");
      files.insert(files.end(), more.begin(), more.end());
    } else if (std::filesystem::is_regular_file(extra)) {
      files.push_back(extra);
    } else {
      ThrowInputError(extra.string(), "", "a short-script file or a folder of them",
                      "no such file or folder");
    }
  }
  std::vector<ShortScript> scripts;
  std::map<std::string, std::string> ids;
  for (const auto& f : files) {
    ShortScript s = LoadShortScript(f, GrammarMode::kStrict, vocab);
    auto [it, inserted] = ids.emplace(s.id, f.string());
    if (!inserted)
      ThrowInputError(f.string(), "id", "an id not used by " + it->second, Quote(s.id));
    scripts.push_back(std::move(s));
  }
  if (scripts.empty())
    ThrowInputError(dir.string(), "", "at least one *.json short script", "none");
  return ScriptDatabase(std::move(scripts));
}

const ShortScript* ScriptDatabase::Find(const std::string& id) const {
  for (const ShortScript& s : scripts_)
    if (s.id == id) return &s;
  return nullptr;
}

}  // namespace sims::planner
