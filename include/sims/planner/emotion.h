// Emotion detection for themes: a lexicon (configs/planner/emotion_lexicon.json) of words and
// phrases per emotion, negation ("not happy" → sad via the opposites table) and the theme's
// emotional arc: the theme is cut into clauses at punctuation and sequencing words ("then",
// "later", "but", ...), each clause gets its dominant emotion, and consecutive equal emotions
// merge ("happy at first, then depressed" → [happy, sad]).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sims/core/config.h"

namespace sims::planner {

/// One step of a theme's emotional arc.
struct ArcSegment {
  std::string emotion = "neutral";  ///< Canonical emotion ("neutral" when none detected).
  std::string text;                 ///< The theme text of this step (for retrieval).
  double score = 0.0;               ///< Lexicon evidence (number of matches).
};

/// The emotion lexicon.
struct EmotionLexicon {
  std::map<std::string, std::vector<std::string>> emotions;  ///< emotion → words ('*' = prefix).
  std::vector<std::string> negators;                         ///< Words that negate what follows.
  std::map<std::string, std::string> opposites;  ///< Emotion a negated emotion turns into.
  std::vector<std::string> separators;           ///< Words/phrases that start a new arc step.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(emotions));
    a->Visit(SIMS_NVP(negators));
    a->Visit(SIMS_NVP(opposites));
    a->Visit(SIMS_NVP(separators));
  }
  /// At least one emotion with words; opposites refer to listed emotions.
  void Validate() const;

  /// Loads configs/planner/emotion_lexicon.json (or `path`).
  static EmotionLexicon Load(const std::filesystem::path& path = {});
  /// The default lexicon, loaded once.
  static const EmotionLexicon& Default();

  /// Evidence per emotion in `text` (only emotions with a positive score).
  std::map<std::string, double> Scores(const std::string& text) const;
  /// Dominant emotion of `text`, or "neutral".
  std::string Detect(const std::string& text) const;
  /// The emotional arc of a theme, in order; never empty (a theme without emotion words is
  /// one neutral segment).
  std::vector<ArcSegment> Arc(const std::string& theme) const;
};

}  // namespace sims::planner
