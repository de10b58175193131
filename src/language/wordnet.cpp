#include "sims/language/wordnet.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"

namespace sims::language {

namespace {

constexpr const char* kPos[] = {"noun", "verb", "adj", "adv"};

// WordNet's morphy detachment rules (suffix -> replacement), all parts of speech together.
constexpr std::pair<const char*, const char*> kRules[] = {
    {"ies", "y"},   {"ses", "s"}, {"xes", "x"}, {"zes", "z"}, {"ches", "ch"}, {"shes", "sh"},
    {"men", "man"}, {"es", "e"},  {"es", ""},   {"s", ""},    {"ed", "e"},    {"ed", ""},
    {"ing", "e"},   {"ing", ""},  {"er", ""},   {"est", ""},  {"er", "e"},    {"est", "e"},
};

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// "bad(a)" -> "bad": adjective syntactic markers in data.adj.
std::string StripMarker(std::string w) {
  const std::size_t p = w.find('(');
  if (p != std::string::npos) w.resize(p);
  return w;
}

std::ifstream OpenOrThrow(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in)
    ThrowInputError(path.string(), "", "a WordNet 3.0 dictionary file",
                    "not found (install Debian's wordnet-base: cmake/setup.sh)");
  return in;
}

}  // namespace

std::filesystem::path WordNetLexicon::DefaultPath() { return DataPath("language/wordnet.txt"); }

WordNetLexicon WordNetLexicon::FromDictDir(const std::filesystem::path& dir,
                                           const std::function<bool(const std::string&)>& known,
                                           int max_synonyms) {
  // lemma -> first-sense synset words (ordered: noun, verb, adj, adv)
  std::map<std::string, std::vector<std::string>> first_sense;
  for (const char* pos : kPos) {
    std::unordered_map<uint64_t, std::vector<std::string>> synsets;
    {
      auto in = OpenOrThrow(dir / (std::string("data.") + pos));
      std::string line;
      while (std::getline(in, line)) {
        if (line.empty() || line[0] == ' ') continue;  // license header
        std::istringstream ls(line);
        uint64_t offset = 0;
        std::string lex_filenum, ss_type, w_cnt_hex;
        if (!(ls >> offset >> lex_filenum >> ss_type >> w_cnt_hex)) continue;
        const int w_cnt = static_cast<int>(std::strtol(w_cnt_hex.c_str(), nullptr, 16));
        std::vector<std::string> words;
        for (int i = 0; i < w_cnt; ++i) {
          std::string w, lex_id;
          if (!(ls >> w >> lex_id)) break;
          words.push_back(Lower(StripMarker(w)));
        }
        synsets.emplace(offset, std::move(words));
      }
    }
    auto in = OpenOrThrow(dir / (std::string("index.") + pos));
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == ' ') continue;
      std::istringstream ls(line);
      std::string lemma, p;
      int synset_cnt = 0, p_cnt = 0;
      if (!(ls >> lemma >> p >> synset_cnt >> p_cnt)) continue;
      std::string skip;
      for (int i = 0; i < p_cnt; ++i) ls >> skip;
      int sense_cnt = 0, tagsense_cnt = 0;
      uint64_t first = 0;
      if (!(ls >> sense_cnt >> tagsense_cnt >> first)) continue;
      lemma = Lower(lemma);
      if (lemma.find('_') != std::string::npos) continue;  // multi-word lemma
      auto& syns = first_sense[lemma];
      const auto it = synsets.find(first);
      if (it == synsets.end()) continue;
      for (const std::string& w : it->second) {
        if (w == lemma || w.find('_') != std::string::npos) continue;
        if (std::find(syns.begin(), syns.end(), w) == syns.end()) syns.push_back(w);
      }
    }
  }

  WordNetLexicon lex;
  for (auto& [lemma, syns] : first_sense) {
    std::vector<std::string> kept;
    for (const std::string& s : syns) {
      if (static_cast<int>(kept.size()) >= max_synonyms) break;
      if (known(s)) kept.push_back(s);
    }
    if (known(lemma) || !kept.empty()) lex.lemmas_.emplace(lemma, std::move(kept));
  }
  for (const char* pos : kPos) {
    const auto path = dir / (std::string(pos) + ".exc");
    auto in = OpenOrThrow(path);
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string form, base;
      if (!(ls >> form)) continue;
      auto& bases = lex.exceptions_[Lower(form)];
      while (ls >> base) {
        base = Lower(base);
        if (lex.IsLemma(base) && std::find(bases.begin(), bases.end(), base) == bases.end())
          bases.push_back(base);
      }
      if (bases.empty()) lex.exceptions_.erase(Lower(form));
    }
  }
  return lex;
}

void WordNetLexicon::Save(const std::filesystem::path& path) const {
  std::ostringstream out;
  out << "# SIMS WordNet subset v1: 'l lemma synonyms...', 'x inflected bases...'\n";
  const std::map<std::string, std::vector<std::string>> lemmas(lemmas_.begin(), lemmas_.end());
  for (const auto& [lemma, syns] : lemmas) {
    out << "l " << lemma;
    for (const auto& s : syns) out << ' ' << s;
    out << '\n';
  }
  const std::map<std::string, std::vector<std::string>> exc(exceptions_.begin(), exceptions_.end());
  for (const auto& [form, bases] : exc) {
    out << "x " << form;
    for (const auto& b : bases) out << ' ' << b;
    out << '\n';
  }
  WriteFileAtomic(path, out.str());
}

WordNetLexicon WordNetLexicon::Load(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in)
    ThrowInputError(path.string(), "", "the WordNet subset file",
                    "file not found (run `prepare_assets --only wordnet`)");
  WordNetLexicon lex;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    std::string kind, key, w;
    ls >> kind >> key;
    if ((kind != "l" && kind != "x") || key.empty())
      ThrowInputError(path.string(), "line " + std::to_string(line_no),
                      "'l <lemma> ...' or 'x <form> <base> ...'", line.substr(0, 60));
    std::vector<std::string> rest;
    while (ls >> w) rest.push_back(w);
    (kind == "l" ? lex.lemmas_ : lex.exceptions_)[key] = std::move(rest);
  }
  return lex;
}

std::vector<std::string> WordNetLexicon::BaseForms(const std::string& word) const {
  std::vector<std::string> out;
  auto add = [&](const std::string& b) {
    if (b != word && !b.empty() && std::find(out.begin(), out.end(), b) == out.end())
      out.push_back(b);
  };
  if (const auto it = exceptions_.find(word); it != exceptions_.end())
    for (const auto& b : it->second) add(b);
  for (const auto& [suffix, repl] : kRules) {
    const std::size_t n = std::char_traits<char>::length(suffix);
    if (word.size() <= n + 1 || word.compare(word.size() - n, n, suffix) != 0) continue;
    std::string cand = word.substr(0, word.size() - n) + repl;
    if (IsLemma(cand)) add(cand);
  }
  return out;
}

const std::vector<std::string>& WordNetLexicon::Synonyms(const std::string& lemma) const {
  static const std::vector<std::string> kEmpty;
  const auto it = lemmas_.find(lemma);
  return it == lemmas_.end() ? kEmpty : it->second;
}

}  // namespace sims::language
