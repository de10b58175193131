// WordNet-based word normalisation for the built-in text encoder: base forms of inflected words
// (WordNet's "morphy": exception lists, then suffix rules) and synonyms from each lemma's most
// frequent sense. Built by `prepare_assets` from Debian's wordnet-base (/usr/share/wordnet) into a
// small text file, restricted to lemmas that matter for the word-vector subset:
//   l <lemma> [synonym ...]     one line per lemma
//   x <inflected> <base> ...    one line per irregular form (from *.exc)
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

namespace sims::language {

/// Lemmas, synonyms and irregular forms; immutable once built.
class WordNetLexicon {
 public:
  /// Where Debian's wordnet-base installs the dictionary.
  static std::filesystem::path DefaultDictDir() { return "/usr/share/wordnet"; }
  /// DataPath("language/wordnet.txt").
  static std::filesystem::path DefaultPath();

  /// Parses a WordNet 3.0 dict folder (index.*, data.*, *.exc). Keeps a lemma if `known(lemma)`
  /// or one of its synonyms is known; synonyms are limited to known single words.
  static WordNetLexicon FromDictDir(const std::filesystem::path& dir,
                                    const std::function<bool(const std::string&)>& known,
                                    int max_synonyms = 8);
  /// Loads the text file written by Save(); throws sims::Error naming the file on defects.
  static WordNetLexicon Load(const std::filesystem::path& path);
  /// Writes the text file atomically (sorted, so identical inputs give identical files).
  void Save(const std::filesystem::path& path) const;

  /// True if `word` is a kept lemma.
  bool IsLemma(const std::string& word) const { return lemmas_.count(word) > 0; }
  /// True if `word` is listed as an irregular form (e.g. "sat").
  bool IsIrregularForm(const std::string& word) const { return exceptions_.count(word) > 0; }
  /// Base forms of `word` other than itself (irregular forms first, then suffix rules).
  std::vector<std::string> BaseForms(const std::string& word) const;
  /// Synonyms of a lemma (empty if none or unknown).
  const std::vector<std::string>& Synonyms(const std::string& lemma) const;
  /// Number of kept lemmas.
  int num_lemmas() const { return static_cast<int>(lemmas_.size()); }
  /// Number of irregular forms.
  int num_exceptions() const { return static_cast<int>(exceptions_.size()); }

 private:
  std::unordered_map<std::string, std::vector<std::string>> lemmas_;  // lemma -> synonyms
  std::unordered_map<std::string, std::vector<std::string>> exceptions_;
};

}  // namespace sims::language
