#include "sims/planner/emotion.h"

#include <algorithm>
#include <mutex>

#include "sims/core/paths.h"
#include "sims/planner/text.h"

namespace sims::planner {

void EmotionLexicon::Validate() const {
  Require(!emotions.empty(), "emotions", "at least one emotion with words");
  for (const auto& [from, to] : opposites) {
    Require(emotions.count(from) > 0, "opposites." + from, "an emotion listed under 'emotions'");
    Require(emotions.count(to) > 0, "opposites." + from, "an emotion listed under 'emotions'");
  }
}

EmotionLexicon EmotionLexicon::Load(const std::filesystem::path& path) {
  return LoadConfig<EmotionLexicon>(path.empty() ? ConfigPath("planner/emotion_lexicon.json")
                                                 : path);
}

const EmotionLexicon& EmotionLexicon::Default() {
  static std::once_flag once;
  static EmotionLexicon* lexicon = nullptr;
  std::call_once(once, [] { lexicon = new EmotionLexicon(Load()); });
  return *lexicon;
}

namespace {

struct Match {
  std::size_t pos;
  std::string emotion;
};

bool WordMatches(const std::string& word, const std::string& pattern) {
  if (!pattern.empty() && pattern.back() == '*')
    return word.compare(0, pattern.size() - 1, pattern, 0, pattern.size() - 1) == 0;
  return word == pattern;
}

// Entry words with apostrophes removed, as Words() produces them.
std::vector<std::string> EntryWords(const std::string& entry) {
  std::vector<std::string> out;
  for (const std::string& w : SplitList(entry, " ")) {
    std::string clean;
    for (char c : ToLower(w))
      if (c != '\'') clean += c;
    out.push_back(clean);
  }
  return out;
}

bool MatchesAt(const std::vector<std::string>& words, std::size_t p,
               const std::vector<std::string>& entry) {
  if (entry.empty() || p + entry.size() > words.size()) return false;
  for (std::size_t k = 0; k < entry.size(); ++k)
    if (!WordMatches(words[p + k], entry[k])) return false;
  return true;
}

std::vector<Match> FindMatches(const EmotionLexicon& lex, const std::vector<std::string>& words) {
  std::vector<std::vector<std::string>> negators;
  for (const std::string& n : lex.negators) negators.push_back(EntryWords(n));
  std::vector<Match> out;
  for (std::size_t p = 0; p < words.size(); ++p) {
    for (const auto& [emotion, entries] : lex.emotions) {
      bool hit = false;
      for (const std::string& e : entries)
        if (MatchesAt(words, p, EntryWords(e))) hit = true;
      if (!hit) continue;
      // A negator within the three preceding words flips or drops the match.
      bool negated = false;
      for (std::size_t back = 1; back <= 3 && back <= p; ++back)
        for (const auto& n : negators)
          if (MatchesAt(words, p - back, n) && p - back + n.size() <= p) negated = true;
      if (!negated) {
        out.push_back({p, emotion});
      } else if (auto it = lex.opposites.find(emotion); it != lex.opposites.end()) {
        out.push_back({p, it->second});
      }
    }
  }
  return out;
}

std::string Dominant(const std::vector<Match>& matches, double* score) {
  std::map<std::string, std::pair<double, std::size_t>> tally;  // count, first position
  for (const Match& m : matches) {
    auto [it, inserted] = tally.emplace(m.emotion, std::make_pair(0.0, m.pos));
    it->second.first += 1.0;
  }
  std::string best = "neutral";
  double best_score = 0.0;
  std::size_t best_pos = 0;
  for (const auto& [e, sp] : tally) {
    if (sp.first > best_score || (sp.first == best_score && sp.second < best_pos)) {
      best = e;
      best_score = sp.first;
      best_pos = sp.second;
    }
  }
  if (score) *score = best_score;
  return best;
}

}  // namespace

std::map<std::string, double> EmotionLexicon::Scores(const std::string& text) const {
  std::map<std::string, double> out;
  for (const Match& m : FindMatches(*this, Words(text))) out[m.emotion] += 1.0;
  return out;
}

std::string EmotionLexicon::Detect(const std::string& text) const {
  return Dominant(FindMatches(*this, Words(text)), nullptr);
}

std::vector<ArcSegment> EmotionLexicon::Arc(const std::string& theme) const {
  // Clauses: sentence punctuation and commas, then sequencing words inside each piece.
  std::vector<std::vector<std::string>> clauses;
  std::vector<std::vector<std::string>> separators;
  for (const std::string& s : this->separators) separators.push_back(EntryWords(s));
  for (const std::string& piece : SplitList(theme, ".;!?,:\n")) {
    std::vector<std::string> words = Words(piece), cur;
    for (std::size_t p = 0; p < words.size();) {
      std::size_t len = 0;
      for (const auto& sep : separators)
        if (MatchesAt(words, p, sep)) len = std::max(len, sep.size());
      if (len > 0) {
        if (!cur.empty()) clauses.push_back(cur);
        cur.clear();
        p += len;
      } else {
        cur.push_back(words[p++]);
      }
    }
    if (!cur.empty()) clauses.push_back(cur);
  }
  std::vector<ArcSegment> arc;
  std::string pending;  // neutral clauses before the first emotional one
  for (const auto& clause : clauses) {
    double score = 0.0;
    // Negation is resolved per clause so "not" never reaches across a comma.
    std::string emotion = Dominant(FindMatches(*this, clause), &score);
    std::string text = Join(clause, " ");
    if (emotion == "neutral") {
      if (arc.empty()) {
        pending += (pending.empty() ? "" : " ") + text;
      } else {
        arc.back().text += " " + text;
      }
      continue;
    }
    if (!arc.empty() && arc.back().emotion == emotion) {
      arc.back().text += " " + text;
      arc.back().score += score;
      continue;
    }
    ArcSegment seg;
    seg.emotion = emotion;
    seg.score = score;
    seg.text = text;
    if (arc.empty() && !pending.empty()) {
      seg.text = pending + " " + text;
      pending.clear();
    }
    arc.push_back(seg);
  }
  if (arc.empty()) {
    ArcSegment seg;
    seg.text = pending.empty() ? NormalizeSpaces(theme) : pending;
    arc.push_back(seg);
  }
  return arc;
}

}  // namespace sims::planner
