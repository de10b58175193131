// Small text utilities shared by the planner: normalisation, tokenising, light stemming,
// phrase matching and edit distance (all ASCII; captions and themes are English).
#pragma once

#include <string>
#include <vector>

namespace sims::planner {

/// ASCII lower case.
std::string ToLower(const std::string& s);

/// Lower case, every character that is not a letter, digit or apostrophe becomes a space, runs
/// of spaces collapse to one, no leading/trailing space.
std::string NormalizeSpaces(const std::string& s);

/// Strips leading and trailing white space.
std::string Trim(const std::string& s);

/// Words of NormalizeSpaces(s).
std::vector<std::string> Words(const std::string& s);

/// A light suffix-stripping stemmer (walking/walks/walked → walk, happily → happi → happy).
std::string Stem(const std::string& word);

/// True for common English function words that carry no retrieval signal.
bool IsStopWord(const std::string& word);

/// Stemmed content words of `s` (stop words removed).
std::vector<std::string> Tokens(const std::string& s);

/// True when `phrase` occurs in `padded_text` (NormalizeSpaces output wrapped in single spaces)
/// at word boundaries; a trailing '*' in the phrase matches any word continuation.
bool ContainsPhrase(const std::string& padded_text, const std::string& phrase);

/// Splits on a separator character and trims each piece (empty pieces dropped).
std::vector<std::string> SplitList(const std::string& s, const std::string& separators = ",;/");

/// Levenshtein distance.
std::size_t EditDistance(const std::string& a, const std::string& b);

/// Joins strings with a separator.
std::string Join(const std::vector<std::string>& parts, const std::string& sep);

}  // namespace sims::planner
