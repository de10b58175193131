#include "sims/planner/vocabulary.h"

#include <algorithm>
#include <cctype>
#include <mutex>
#include <set>

#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/core/skill_vocabulary.h"
#include "sims/planner/text.h"

namespace sims::planner {

namespace {
// The planner's script grammar (Skill) names the skill vocabulary's scripted skills in order.
const std::vector<const SkillTraits*>& GrammarSkills() {
  static const std::vector<const SkillTraits*> skills = [] {
    std::vector<const SkillTraits*> s = ScriptedSkills();
    SIMS_CHECK_MSG(s.size() >= kNumSkills, "the skill vocabulary lacks scripted skills");
    s.resize(kNumSkills);
    return s;
  }();
  return skills;
}

const SkillTraits& TraitsOf(Skill skill) { return *GrammarSkills()[static_cast<int>(skill)]; }
}  // namespace

const char* SkillName(Skill skill) {
  const int k = static_cast<int>(skill);
  return k >= 0 && k < kNumSkills ? TraitsOf(skill).name.c_str() : "?";
}

std::string Vocabulary::Squash(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == ' ' || c == '_' || c == '-' || c == '\t') continue;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

void Vocabulary::Validate() const {
  // The skills are the skill vocabulary's scripted ones (core/skill_vocabulary.h), each once.
  const std::string scripted = SkillNames([](const SkillTraits& t) { return t.scripted; });
  const std::vector<const SkillTraits*> known = ScriptedSkills();
  Require(skills.size() == known.size(), "skills", "exactly the scripted skills " + scripted);
  for (const SkillTraits* t : known) {
    bool found = std::any_of(skills.begin(), skills.end(),
                             [&](const SkillSpec& k) { return k.name == t->name; });
    Require(found, "skills", "an entry named '" + t->name + "'");
  }
  for (std::size_t i = 0; i < skills.size(); ++i) {
    for (std::size_t a = 0; a < skills[i].axes.size(); ++a) {
      const StyleAxis& axis = skills[i].axes[a];
      std::string field = "skills[" + std::to_string(i) + "].axes[" + std::to_string(a) + "]";
      Require(!axis.values.empty(), field + ".values", "at least one value");
      bool has_default =
          std::any_of(axis.values.begin(), axis.values.end(),
                      [&](const StyleValue& v) { return v.id == axis.default_value; });
      Require(has_default, field + ".default_value", "one of the axis values");
    }
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < furniture.size(); ++i) {
    Require(names.insert(furniture[i].name).second, "furniture[" + std::to_string(i) + "].name",
            "a unique category name");
    for (const std::string& a : furniture[i].affordances) {
      const SkillTraits* t = FindSkillTraits(a);
      Require(t && t->affordance, "furniture[" + std::to_string(i) + "].affordances",
              "values among " + SkillNames([](const SkillTraits& s) { return s.affordance; }));
    }
  }
  for (std::size_t i = 0; i < substitutions.size(); ++i) {
    const auto& s = substitutions[i];
    std::string f = "substitutions[" + std::to_string(i) + "]";
    Require(names.count(s.a) && names.count(s.b), f, "two known furniture categories");
    Require(s.cost >= 0 && s.cost <= 1, f + ".cost", "a number in [0, 1]");
  }
  bool neutral = std::any_of(emotions.begin(), emotions.end(),
                             [](const EmotionSpec& e) { return e.name == "neutral"; });
  Require(neutral, "emotions", "an entry named 'neutral'");
}

void Vocabulary::BuildIndex() {
  skill_index_.clear();
  furniture_index_.clear();
  emotion_index_.clear();
  room_index_.clear();
  for (const SkillSpec& s : skills) {
    Skill skill = Skill::kWalk;
    for (int k = 0; k < kNumSkills; ++k)
      if (s.name == SkillName(static_cast<Skill>(k))) skill = static_cast<Skill>(k);
    skill_index_[Squash(s.name)] = skill;
    for (const auto& a : s.aliases) skill_index_[Squash(a)] = skill;
  }
  for (const FurnitureSpec& f : furniture) {
    furniture_index_[Squash(f.name)] = f.name;
    for (const auto& a : f.aliases) furniture_index_[Squash(a)] = f.name;
  }
  for (const EmotionSpec& e : emotions) {
    emotion_index_[Squash(e.name)] = e.name;
    for (const auto& a : e.aliases) emotion_index_[Squash(a)] = e.name;
  }
  for (const RoomTypeSpec& r : room_types) {
    room_index_[Squash(r.name)] = r.name;
    for (const auto& a : r.aliases) room_index_[Squash(a)] = r.name;
  }
}

Vocabulary Vocabulary::Load(const std::filesystem::path& path) {
  std::filesystem::path p = path.empty() ? ConfigPath("planner/vocabulary.json") : path;
  Vocabulary v = LoadConfig<Vocabulary>(p);
  v.BuildIndex();
  return v;
}

const Vocabulary& Vocabulary::Default() {
  static std::once_flag once;
  static Vocabulary* vocab = nullptr;
  std::call_once(once, [] { vocab = new Vocabulary(Load()); });
  return *vocab;
}

std::optional<Skill> Vocabulary::FindSkill(const std::string& name) const {
  auto it = skill_index_.find(Squash(name));
  if (it == skill_index_.end()) return std::nullopt;
  return it->second;
}

const SkillSpec& Vocabulary::Spec(Skill skill) const {
  for (const SkillSpec& s : skills)
    if (s.name == SkillName(skill)) return s;
  SIMS_CHECK_MSG(false, std::string("vocabulary lacks skill ") + SkillName(skill));
  return skills.front();
}

std::optional<std::string> Vocabulary::FindFurniture(const std::string& name) const {
  auto it = furniture_index_.find(Squash(name));
  if (it == furniture_index_.end()) return std::nullopt;
  return it->second;
}

const FurnitureSpec* Vocabulary::FurnitureByName(const std::string& category) const {
  for (const FurnitureSpec& f : furniture)
    if (f.name == category) return &f;
  return nullptr;
}

bool Vocabulary::Affords(const std::string& category, Skill skill) const {
  const SkillTraits& t = TraitsOf(skill);
  if (t.navigates) return true;  // walking goes anywhere
  const FurnitureSpec* f = FurnitureByName(category);
  if (!f) return false;
  auto has = [&](const std::string& a) {
    return std::find(f->affordances.begin(), f->affordances.end(), a) != f->affordances.end();
  };
  if (has(t.name)) return true;
  // A follow-up skill (getup) works where a skill it follows (sit, lie) does.
  for (const SkillTraits& s : SkillVocabulary())
    if (s.follow_up == t.name && has(s.name)) return true;
  return false;
}

std::vector<std::string> Vocabulary::CategoriesAffording(Skill skill) const {
  std::vector<std::string> out;
  for (const FurnitureSpec& f : furniture)
    if (f.name != "floor" && Affords(f.name, skill)) out.push_back(f.name);
  return out;
}

bool Vocabulary::IsImportant(const std::string& category) const {
  const FurnitureSpec* f = FurnitureByName(category);
  return f ? f->important : true;
}

std::optional<double> Vocabulary::SubstitutionCost(const std::string& a,
                                                   const std::string& b) const {
  if (a == b) return 0.0;
  std::optional<double> best;
  for (const SubstitutionSpec& s : substitutions) {
    if ((s.a == a && s.b == b) || (s.a == b && s.b == a))
      if (!best || s.cost < *best) best = s.cost;
  }
  return best;
}

std::vector<std::string> Vocabulary::Substitutes(const std::string& category) const {
  std::vector<std::pair<double, std::string>> found;
  for (const SubstitutionSpec& s : substitutions) {
    if (s.a == category) found.emplace_back(s.cost, s.b);
    if (s.b == category) found.emplace_back(s.cost, s.a);
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> out;
  for (auto& [c, name] : found)
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  return out;
}

std::optional<std::string> Vocabulary::FindEmotion(const std::string& word) const {
  auto it = emotion_index_.find(Squash(word));
  if (it == emotion_index_.end()) return std::nullopt;
  return it->second;
}

const EmotionSpec* Vocabulary::EmotionByName(const std::string& name) const {
  for (const EmotionSpec& e : emotions)
    if (e.name == name) return &e;
  return nullptr;
}

std::optional<std::string> Vocabulary::FindRoomType(const std::string& name) const {
  auto it = room_index_.find(Squash(name));
  if (it == room_index_.end()) return std::nullopt;
  return it->second;
}

StyleChoice Vocabulary::ResolveStyle(Skill skill, const std::string& caption,
                                     const std::string& emotion) const {
  const SkillSpec& spec = Spec(skill);
  std::string text = " " + NormalizeSpaces(ToLower(caption)) + " ";
  // The emotion's default style, split back into axis values.
  std::vector<std::string> emotion_values;
  if (const EmotionSpec* e = EmotionByName(emotion)) {
    auto it = e->styles.find(spec.name);
    if (it != e->styles.end() && IsValidStyle(skill, it->second)) {
      std::string rest = it->second;
      for (std::size_t a = 0; a < spec.axes.size(); ++a) {
        // Axis values never contain the separator of the following axis' first value, so a
        // greedy match against the allowed ids recovers each value.
        const StyleAxis& axis = spec.axes[a];
        std::string match;
        for (const StyleValue& v : axis.values) {
          bool last = a + 1 == spec.axes.size();
          if (last ? rest == v.id : rest.rfind(v.id + "_", 0) == 0)
            if (v.id.size() > match.size()) match = v.id;
        }
        emotion_values.push_back(match);
        rest = rest.size() > match.size() ? rest.substr(match.size() + 1) : "";
      }
    }
  }
  StyleChoice choice;
  choice.from_caption = true;
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    const StyleAxis& axis = spec.axes[a];
    std::string best;
    std::size_t best_len = 0;
    for (const StyleValue& v : axis.values) {
      for (const std::string& phrase : v.phrases) {
        if (phrase.size() > best_len && ContainsPhrase(text, phrase)) {
          best = v.id;
          best_len = phrase.size();
        }
      }
    }
    bool from_caption = !best.empty();
    if (best.empty() && a < emotion_values.size()) best = emotion_values[a];
    if (best.empty()) best = axis.default_value;
    choice.axis_from_caption.push_back(from_caption);
    if (!from_caption) choice.from_caption = false;
    if (!choice.id.empty()) choice.id += "_";
    choice.id += best;
  }
  return choice;
}

bool Vocabulary::IsValidStyle(Skill skill, const std::string& style) const {
  const SkillSpec& spec = Spec(skill);
  // Enumerate the product of axis values (at most a few dozen).
  std::vector<std::string> ids = {""};
  for (const StyleAxis& axis : spec.axes) {
    std::vector<std::string> next;
    for (const std::string& prefix : ids)
      for (const StyleValue& v : axis.values)
        next.push_back(prefix.empty() ? v.id : prefix + "_" + v.id);
    ids = std::move(next);
  }
  return std::find(ids.begin(), ids.end(), style) != ids.end();
}

std::string Vocabulary::StyleText(Skill skill, const std::string& style) const {
  const SkillSpec& spec = Spec(skill);
  std::string rest = style, out;
  for (const StyleAxis& axis : spec.axes) {
    std::string match;
    const StyleValue* value = nullptr;
    for (const StyleValue& v : axis.values) {
      if ((rest == v.id || rest.rfind(v.id + "_", 0) == 0) && v.id.size() > match.size()) {
        match = v.id;
        value = &v;
      }
    }
    if (!value) break;
    if (!value->text.empty()) out += (out.empty() ? "" : " ") + value->text;
    rest = rest.size() > match.size() ? rest.substr(match.size() + 1) : "";
  }
  return out;
}

namespace {
std::string JoinNames(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}
}  // namespace

std::string Vocabulary::SkillList() const {
  std::vector<std::string> v;
  for (const SkillSpec& s : skills) v.push_back(s.name);
  return JoinNames(v);
}

std::string Vocabulary::FurnitureList() const {
  std::vector<std::string> v;
  for (const FurnitureSpec& f : furniture) v.push_back(f.name);
  return JoinNames(v);
}

std::string Vocabulary::EmotionList() const {
  std::vector<std::string> v;
  for (const EmotionSpec& e : emotions) v.push_back(e.name);
  return JoinNames(v);
}

std::string Vocabulary::RoomTypeList() const {
  std::vector<std::string> v;
  for (const RoomTypeSpec& r : room_types) v.push_back(r.name);
  return JoinNames(v);
}

std::string Vocabulary::Closest(const std::string& word, const std::vector<std::string>& names) {
  std::string w = Squash(word), best;
  std::size_t best_d = std::max<std::size_t>(2, w.size() / 3) + 1;
  for (const std::string& n : names) {
    std::size_t d = EditDistance(w, Squash(n));
    if (d < best_d) {
      best_d = d;
      best = n;
    }
  }
  return best;
}

namespace {

// English plural → singular for one word (chairs, benches, shelves, libraries).
std::string Singular(const std::string& w) {
  auto ends = [&](const std::string& suf) {
    return w.size() > suf.size() + 1 && w.compare(w.size() - suf.size(), suf.size(), suf) == 0;
  };
  if (ends("ies")) return w.substr(0, w.size() - 3) + "y";
  if (ends("ves")) return w.substr(0, w.size() - 3) + "f";
  if (ends("ches") || ends("shes") || ends("xes") || ends("sses")) return w.substr(0, w.size() - 2);
  if (ends("s") && !ends("ss")) return w.substr(0, w.size() - 1);
  return w;
}

// Past and other forms the light stemmer and the aliases do not cover.
const std::map<std::string, std::string>& IrregularVerbs() {
  static const std::map<std::string, std::string> kForms = {
      {"sat", "sit"},     {"laid", "lie"},    {"lain", "lie"},     {"lying", "lie"},
      {"stood", "stand"}, {"rose", "rise"},   {"risen", "rise"},   {"got", "get"},
      {"went", "go"},     {"ran", "run"},     {"took", "take"},    {"running", "run"},
      {"getting", "get"}, {"sitting", "sit"}, {"walking", "walk"}, {"touched", "touch"}};
  return kForms;
}

}  // namespace

std::optional<TermMatch> Vocabulary::Nearest(const std::string& text,
                                             const std::map<std::string, std::string>& index) {
  auto find = [&](const std::string& s) -> const std::string* {
    auto it = index.find(Squash(s));
    return it == index.end() ? nullptr : &it->second;
  };
  if (const std::string* c = find(text)) return TermMatch{*c, "known"};
  std::vector<std::string> words = Words(text);
  if (words.empty()) return std::nullopt;
  std::vector<std::string> singular, base;
  for (const std::string& w : words) {
    singular.push_back(Singular(w));
    auto irr = IrregularVerbs().find(w);
    base.push_back(irr != IrregularVerbs().end() ? irr->second : Stem(w));
  }
  auto joined = [](const std::vector<std::string>& v, std::size_t from, std::size_t n) {
    std::string s;
    for (std::size_t i = from; i < from + n; ++i) s += (s.empty() ? "" : " ") + v[i];
    return s;
  };
  // Longest sub-phrase first; among equally long ones the rightmost, because English puts the
  // head noun last ("dining room chair" is a chair, not a room).
  for (std::size_t n = words.size(); n >= 1; --n) {
    for (std::size_t from = words.size() - n + 1; from-- > 0;) {
      for (const auto* forms : {&words, &singular, &base}) {
        std::string phrase = joined(*forms, from, n);
        if (const std::string* c = find(phrase)) {
          std::string how = n == words.size() ? (forms == &words ? "known" : "base form")
                                              : "part '" + joined(words, from, n) + "'";
          return TermMatch{*c, how};
        }
      }
    }
  }
  // Spelling: the whole text, then each word (rightmost first). Stricter than Closest's
  // suggestion threshold, because a mapping is applied silently: one edit per four letters
  // ("armchiar" → armchair, but not "fly" → lay).
  std::vector<std::string> names;
  for (const auto& [key, canonical] : index) names.push_back(key);
  auto spelling = [&](const std::string& word) -> std::optional<TermMatch> {
    std::string closest = Closest(word, names);
    if (closest.empty()) return std::nullopt;
    std::string w = Squash(word);
    if (EditDistance(w, closest) > std::max<std::size_t>(1, w.size() / 4)) return std::nullopt;
    return TermMatch{index.at(closest), "spelling '" + closest + "'"};
  };
  if (auto m = spelling(text)) return m;
  for (std::size_t i = words.size(); i-- > 0;) {
    if (words[i].size() < 4 || IsStopWord(words[i])) continue;
    if (auto m = spelling(words[i])) return m;
  }
  return std::nullopt;
}

std::optional<TermMatch> Vocabulary::NearestFurniture(const std::string& text) const {
  return Nearest(text, furniture_index_);
}

std::optional<TermMatch> Vocabulary::NearestSkill(const std::string& text) const {
  std::map<std::string, std::string> names;
  for (const auto& [key, skill] : skill_index_) names[key] = SkillName(skill);
  return Nearest(text, names);
}

std::optional<TermMatch> Vocabulary::NearestEmotion(const std::string& text) const {
  return Nearest(text, emotion_index_);
}

std::optional<TermMatch> Vocabulary::NearestRoomType(const std::string& text) const {
  return Nearest(text, room_index_);
}

}  // namespace sims::planner
