#include "sims/planner/composer.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "sims/core/error.h"
#include "sims/core/rng.h"
#include "sims/planner/text.h"

namespace sims::planner {

using nlohmann::json;

const char* DifficultyName(Difficulty d) {
  switch (d) {
    case Difficulty::kSimple:
      return "simple";
    case Difficulty::kMid:
      return "mid";
    case Difficulty::kHard:
      return "hard";
  }
  return "?";
}

Difficulty ParseDifficulty(const std::string& name, const std::string& source) {
  std::string n = Vocabulary::Squash(name);
  if (n == "simple" || n == "easy") return Difficulty::kSimple;
  if (n == "mid" || n == "medium" || n == "middle") return Difficulty::kMid;
  if (n == "hard" || n == "difficult" || n == "long") return Difficulty::kHard;
  ThrowInputError(source, "difficulty", "simple, mid or hard", "'" + name + "'");
}

void DifficultyConfig::Validate() const {
  for (const auto* r : {&simple, &mid, &hard})
    Require((*r)[0] >= 1 && (*r)[0] <= (*r)[1], "simple/mid/hard", "[min, max] with 1 ≤ min ≤ max");
}

std::array<int, 2> DifficultyConfig::Range(Difficulty d) const {
  return d == Difficulty::kSimple ? simple : d == Difficulty::kMid ? mid : hard;
}

int LongScript::Interactions() const {
  return static_cast<int>(std::count_if(keyframes.begin(), keyframes.end(),
                                        [](const Keyframe& k) { return IsInteraction(k.skill); }));
}

std::vector<std::string> LongScript::EmotionSequence() const {
  std::vector<std::string> out;
  for (const Keyframe& k : keyframes)
    if (IsInteraction(k.skill) && (out.empty() || out.back() != k.emotion))
      out.push_back(k.emotion);
  return out;
}

LongScript ConcatenateScripts(const std::vector<ShortScript>& scripts, const std::string& source,
                              const Vocabulary& vocab) {
  LongScript ls;
  std::vector<Keyframe> keyframes;
  for (std::size_t i = 0; i < scripts.size(); ++i) {
    ls.script_ids.push_back(scripts[i].id);
    ls.segment_rooms.push_back(scripts[i].scene);
    ArcSegment a;
    a.emotion = scripts[i].emotion;
    a.text = scripts[i].summary;
    if (ls.arc.empty() || ls.arc.back().emotion != a.emotion) ls.arc.push_back(a);
    for (Keyframe k : scripts[i].keyframes) {
      k.segment = static_cast<int>(i);
      k.script_id = scripts[i].id;
      keyframes.push_back(k);
    }
  }
  ls.keyframes = InsertTransitions(keyframes, source, vocab);
  return ls;
}

LongScript LongScriptFromJson(const json& j, const std::string& source, const Vocabulary& vocab) {
  std::vector<ShortScript> scripts;
  if (j.is_array()) {
    ShortScript s;
    s.id = "script";
    s.source = source;
    s.keyframes = ParseKeyframes(j, source, "", "neutral", vocab);
    ThrowOnGrammarIssues(CheckGrammar(s.keyframes, vocab), source, "", GrammarMode::kLenient);
    scripts.push_back(s);
  } else if (j.is_object() && j.contains("scripts")) {
    const json& arr = j["scripts"];
    if (!arr.is_array() || arr.empty())
      ThrowInputError(source, "scripts", "a non-empty list of short scripts",
                      arr.dump().substr(0, 60));
    for (std::size_t i = 0; i < arr.size(); ++i) {
      std::string sub = source + " scripts[" + std::to_string(i) + "]";
      ShortScript s = ParseShortScript(arr[i], sub, GrammarMode::kLenient, vocab);
      if (s.id.empty()) s.id = "script_" + std::to_string(i);
      scripts.push_back(s);
    }
  } else {
    ShortScript s = ParseShortScript(j, source, GrammarMode::kLenient, vocab);
    if (s.id.empty()) s.id = "script";
    scripts.push_back(s);
  }
  LongScript ls = ConcatenateScripts(scripts, source, vocab);
  if (j.is_object()) {
    if (auto it = j.find("theme"); it != j.end() && it->is_string())
      ls.theme = it->get<std::string>();
    if (auto it = j.find("narrative"); it != j.end() && it->is_string())
      ls.narrative = it->get<std::string>();
  }
  return ls;
}

LongScript LoadLongScript(const std::filesystem::path& path, const Vocabulary& vocab) {
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowInputError(path.string(), "", "a readable script JSON file", "no such file");
  std::stringstream ss;
  ss << in.rdbuf();
  // Reuse the short-script parser's diagnostics (single quotes, line numbers) for the text.
  json j;
  try {
    j = json::parse(ss.str());
  } catch (const json::exception&) {  // parse_error, or out_of_range for a huge number
    (void)ParseShortScriptText(ss.str(), path.string(), GrammarMode::kLenient, vocab);
    throw;  // not reached: the parser above throws a clearer sims::Error
  }
  return LongScriptFromJson(j, path.string(), vocab);
}

// ---------------------------------------------------------------------------------------------

ThemePlanner::ThemePlanner(const ScriptDatabase& db, const Vocabulary& vocab,
                           const EmotionLexicon& lexicon, RetrievalConfig retrieval,
                           DifficultyConfig difficulty, TextEmbedder embedder)
    : db_(db),
      vocab_(vocab),
      lexicon_(lexicon),
      difficulty_(difficulty),
      retriever_(db, vocab, retrieval, std::move(embedder)) {}

namespace {

// Two interactions are "the same keyframe" when they do the same thing in the same style on the
// same kind of furniture, whatever their wording; walks and get-ups repeat only verbatim.
std::string Signature(const Keyframe& k) {
  std::string s = std::string(SkillName(k.skill)) + "|" + k.furniture + "|";
  return IsInteraction(k.skill) ? s + k.style : s + NormalizeSpaces(k.caption);
}

// Spreads `n` interactions over `k` arc steps: every step gets at least one when n ≥ k (earlier
// steps get the remainder); otherwise n steps are kept, evenly spaced, first and last included.
std::vector<std::pair<int, int>> Allocate(int k, int n) {
  std::vector<std::pair<int, int>> out;  // (arc index, quota)
  if (k <= n) {
    for (int i = 0; i < k; ++i) out.push_back({i, n / k + (i < n % k ? 1 : 0)});
  } else if (n == 1) {
    out.push_back({0, 1});
  } else {
    for (int i = 0; i < n; ++i) {
      int idx = static_cast<int>(std::lround(static_cast<double>(i) * (k - 1) / (n - 1)));
      out.push_back({idx, 1});
    }
  }
  return out;
}

}  // namespace

LongScript ThemePlanner::Plan(const std::string& theme, Difficulty difficulty,
                              uint64_t seed) const {
  Rng rng(seed);
  LongScript ls;
  ls.theme = theme;
  ls.difficulty = difficulty;
  ls.seed = seed;
  ls.arc = lexicon_.Arc(theme);
  std::array<int, 2> range = difficulty_.Range(difficulty);
  int total = range[0] + static_cast<int>(rng.UniformInt(range[1] - range[0] + 1));
  std::vector<std::string> rooms = retriever_.RoomsIn(theme);
  const RetrievalConfig& rc = retriever_.config();

  std::set<int> used_scripts;
  std::set<std::string> used_keyframes;
  std::vector<Keyframe> keyframes;
  std::string previous_room;
  int segment = 0;
  for (auto [arc_index, quota] : Allocate(static_cast<int>(ls.arc.size()), total)) {
    const ArcSegment& step = ls.arc[arc_index];
    int remaining = quota;
    for (std::size_t attempt = 0; remaining > 0 && attempt < db_.size(); ++attempt) {
      // A room named in this step wins over rooms named elsewhere in the theme.
      std::vector<std::string> step_rooms = retriever_.RoomsIn(step.text);
      RetrievalQuery q{step.text, theme, step.emotion, step_rooms.empty() ? rooms : step_rooms,
                       previous_room};
      std::vector<ScoredScript> ranked;
      for (const ScoredScript& s : retriever_.Rank(q))
        if (!used_scripts.count(s.index)) ranked.push_back(s);
      if (ranked.empty()) break;
      std::vector<int> near;
      for (const ScoredScript& s : ranked)
        if (s.score >= ranked.front().score - rc.pick_margin &&
            static_cast<int>(near.size()) < rc.pick_top)
          near.push_back(s.index);
      int chosen =
          near[static_cast<std::size_t>(rng.UniformInt(static_cast<int64_t>(near.size())))];
      used_scripts.insert(chosen);
      const ShortScript& script = db_.scripts()[chosen];
      std::vector<Keyframe> taken;
      int got = 0;
      for (std::size_t i = 0; i < script.keyframes.size(); ++i) {
        const Keyframe& k = script.keyframes[i];
        if (got == remaining && k.skill != Skill::kGetUp) break;
        if (got == remaining && k.skill == Skill::kGetUp) {
          taken.push_back(k);  // leave the last seat the way the script does
          break;
        }
        if (used_keyframes.count(Signature(k))) continue;
        taken.push_back(k);
        if (IsInteraction(k.skill)) ++got;
      }
      if (got == 0) continue;
      for (Keyframe& k : taken) {
        used_keyframes.insert(Signature(k));
        k.segment = segment;
        k.script_id = script.id;
        keyframes.push_back(k);
      }
      ls.script_ids.push_back(script.id);
      ls.segment_rooms.push_back(script.scene);
      previous_room = script.scene;
      remaining -= got;
      ++segment;
    }
  }
  // Skipping duplicates can leave a get-up whose sit was skipped, and joining scripts can leave
  // a walk to the object the character already stands at: drop both before the grammar repair
  // (which would reject the first and not need the second).
  std::vector<Keyframe> cleaned;
  bool seated = false;
  std::string at;  // "category#instance" the character stands at ("" = unknown / walked away)
  for (const Keyframe& k : keyframes) {
    std::string ref = k.furniture + "#" + std::to_string(k.instance);
    if (k.skill == Skill::kGetUp && !seated) continue;
    if (k.skill == Skill::kWalk && !seated && !at.empty() && ref == at) continue;
    if (k.skill == Skill::kSit || k.skill == Skill::kLie) seated = true;
    if (k.skill == Skill::kGetUp || k.skill == Skill::kWalk || k.skill == Skill::kReach)
      seated = false;
    at = k.skill == Skill::kWalk && k.furniture == "floor" ? "" : ref;
    cleaned.push_back(k);
  }
  ls.keyframes = InsertTransitions(cleaned, "theme planner", vocab_);
  ls.narrative = TemplateNarrative(ls, {}, vocab_);
  return ls;
}

std::vector<int> ThemePlanner::Candidates(const std::string& theme, int count) const {
  std::vector<ArcSegment> arc = lexicon_.Arc(theme);
  std::vector<std::string> rooms = retriever_.RoomsIn(theme);
  std::vector<std::vector<ScoredScript>> lists;
  for (const ArcSegment& a : arc)
    lists.push_back(retriever_.Rank({a.text, theme, a.emotion, rooms, ""}));
  std::vector<int> out;
  std::set<int> seen;
  for (std::size_t r = 0; static_cast<int>(out.size()) < count && r < db_.size(); ++r)
    for (const auto& l : lists)
      if (r < l.size() && seen.insert(l[r].index).second && static_cast<int>(out.size()) < count)
        out.push_back(l[r].index);
  return out;
}

// ---------------------------------------------------------------------------------------------

std::string TemplateNarrative(const LongScript& script,
                              const std::vector<std::string>& furniture_names,
                              const Vocabulary& vocab) {
  auto pretty = [](std::string s) {
    std::replace(s.begin(), s.end(), '_', ' ');
    return s;
  };
  struct Group {
    std::string emotion;
    std::vector<std::string> phrases;
  };
  std::vector<Group> groups;
  for (std::size_t i = 0; i < script.keyframes.size(); ++i) {
    const Keyframe& k = script.keyframes[i];
    if (k.inserted && !IsInteraction(k.skill)) continue;  // transitions need no mention
    std::string phrase = k.caption.empty() ? std::string(SkillName(k.skill)) : k.caption;
    std::string requested = pretty(k.furniture);
    std::string used = i < furniture_names.size() && !furniture_names[i].empty()
                           ? pretty(furniture_names[i])
                           : requested;
    if (k.furniture != "floor") {
      if (used != requested) {
        phrase += " (a " + used + " serves as the " + requested + ")";
      } else if (NormalizeSpaces(phrase).find(NormalizeSpaces(requested)) == std::string::npos) {
        const char* prep = k.skill == Skill::kSit || k.skill == Skill::kLie ? " on the "
                           : k.skill == Skill::kWalk                        ? " towards the "
                           : k.skill == Skill::kGetUp                       ? " from the "
                                                                            : " at the ";
        phrase += prep + requested;
      }
    }
    if (groups.empty() || groups.back().emotion != k.emotion) groups.push_back({k.emotion, {}});
    groups.back().phrases.push_back(phrase);
  }
  std::string out;
  std::vector<std::string> rooms;
  for (const std::string& r : script.segment_rooms)
    if (std::find(rooms.begin(), rooms.end(), r) == rooms.end()) rooms.push_back(r);
  if (!rooms.empty()) {
    std::vector<std::string> named;
    for (const auto& r : rooms) named.push_back("the " + r);
    std::string list = named.size() == 1
                           ? named[0]
                           : Join(std::vector<std::string>(named.begin(), named.end() - 1), ", ") +
                                 " and " + named.back();
    out += "The story unfolds in " + list + ". ";
  }
  static const char* kConnectors[] = {"Then", "After that", "Later"};
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const EmotionSpec* e = vocab.EmotionByName(groups[g].emotion);
    std::string adjective = e && !e->adjective.empty() ? e->adjective : groups[g].emotion;
    std::string connector = groups.size() == 1 ? "Feeling " + adjective
                            : g == 0           ? "At first, feeling " + adjective
                            : g + 1 == groups.size()
                                ? "Finally, feeling " + adjective
                                : std::string(kConnectors[(g - 1) % 3]) + ", feeling " + adjective;
    const auto& p = groups[g].phrases;
    std::string actions =
        p.size() == 1
            ? p[0]
            : Join(std::vector<std::string>(p.begin(), p.end() - 1), ", ") + " and " + p.back();
    out += connector + ", the person " + actions + ". ";
  }
  if (groups.size() > 1) {
    std::vector<std::string> arc;
    for (const Group& g : groups)
      if (arc.empty() || arc.back() != g.emotion) arc.push_back(g.emotion);
    out += "The mood moves from " + Join(arc, " to ") + ".";
  }
  return Trim(out);
}

}  // namespace sims::planner
