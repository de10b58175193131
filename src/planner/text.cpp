#include "sims/planner/text.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace sims::planner {

std::string ToLower(const std::string& s) {
  std::string out = s;
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string NormalizeSpaces(const std::string& s) {
  std::string out;
  bool space = true;  // suppresses leading spaces
  for (char c : s) {
    unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '\'') {
      out += static_cast<char>(std::tolower(u));
      space = false;
    } else if (!space) {
      out += ' ';
      space = true;
    }
  }
  if (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string Trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::vector<std::string> Words(const std::string& s) {
  std::vector<std::string> out;
  std::string n = NormalizeSpaces(s), cur;
  for (char c : n) {
    if (c == ' ') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else if (c != '\'') {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

namespace {
bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

std::string Stem(const std::string& w) {
  // Deliberately simple: enough to conflate the inflections themes and captions use
  // (sits/sitting/sat are not all conflated; the vocabulary aliases handle skills).
  std::string s = w;
  if (s.size() <= 3) return s;
  auto strip = [&](const std::string& suf, std::size_t min_stem, const std::string& add = "") {
    if (EndsWith(s, suf) && s.size() - suf.size() >= min_stem) {
      s = s.substr(0, s.size() - suf.size()) + add;
      return true;
    }
    return false;
  };
  if (strip("ies", 3, "y") || strip("ily", 3, "y") || strip("ness", 3) || strip("ing", 3) ||
      strip("edly", 3) || strip("ed", 3) || strip("ly", 3) || strip("es", 4) ||
      (!EndsWith(s, "ss") && strip("s", 3))) {
    // Undo doubled consonants left by -ing/-ed (sitting → sitt → sit, stopped → stopp → stop).
    if (s.size() >= 4 && s[s.size() - 1] == s[s.size() - 2] &&
        std::string("bdgmnprt").find(s.back()) != std::string::npos)
      s.pop_back();
  }
  return s;
}

bool IsStopWord(const std::string& w) {
  static const std::set<std::string> kStop = {
      "a",     "an",    "the",  "and",    "or",      "but",     "of",        "to",     "in",
      "on",    "at",    "by",   "for",    "with",    "from",    "into",      "onto",   "is",
      "are",   "was",   "were", "be",     "been",    "it",      "its",       "this",   "that",
      "these", "those", "he",   "she",    "they",    "him",     "her",       "his",    "their",
      "them",  "i",     "me",   "my",     "we",      "our",     "you",       "your",   "as",
      "so",    "very",  "then", "than",   "there",   "some",    "any",       "all",    "just",
      "up",    "down",  "over", "out",    "off",     "while",   "after",     "before", "when",
      "who",   "which", "what", "person", "someone", "man",     "woman",     "has",    "have",
      "had",   "does",  "do",   "did",    "will",    "would",   "can",       "could",  "s",
      "t",     "again", "also", "about",  "himself", "herself", "themselves"};
  return kStop.count(w) > 0;
}

std::vector<std::string> Tokens(const std::string& s) {
  std::vector<std::string> out;
  for (const std::string& w : Words(s))
    if (!IsStopWord(w)) out.push_back(Stem(w));
  return out;
}

bool ContainsPhrase(const std::string& padded_text, const std::string& phrase) {
  if (phrase.empty()) return false;
  if (phrase.back() == '*')
    return padded_text.find(" " + phrase.substr(0, phrase.size() - 1)) != std::string::npos;
  return padded_text.find(" " + phrase + " ") != std::string::npos;
}

std::vector<std::string> SplitList(const std::string& s, const std::string& separators) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (separators.find(c) != std::string::npos) {
      if (!Trim(cur).empty()) out.push_back(Trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!Trim(cur).empty()) out.push_back(Trim(cur));
  return out;
}

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] =
          std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1] ? 1u : 0u)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string Join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? sep : "") + parts[i];
  return out;
}

}  // namespace sims::planner
