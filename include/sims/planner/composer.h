// The embedded planner: theme → long script without any network. It follows the theme's
// emotional arc in order, retrieves short scripts for each step, concatenates their keyframes up
// to the number of interactions the difficulty asks for (SIMS Table 2: simple 2, mid 3–4,
// hard 4–6), never repeats a keyframe, and repairs the grammar (walks, get-ups).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sims/planner/emotion.h"
#include "sims/planner/retrieval.h"
#include "sims/planner/script.h"

namespace sims::planner {

/// Story length class (SIMS Table 2).
enum class Difficulty { kSimple, kMid, kHard };

/// "simple", "mid" or "hard".
const char* DifficultyName(Difficulty d);

/// Parses "simple" | "mid" | "hard" (also "easy", "medium", "difficult"); errors name `source`.
Difficulty ParseDifficulty(const std::string& name, const std::string& source = "--difficulty");

/// Interaction-count ranges per difficulty.
struct DifficultyConfig {
  std::array<int, 2> simple{2, 2};  ///< [min, max] interactions for simple stories.
  std::array<int, 2> mid{3, 4};     ///< [min, max] for mid.
  std::array<int, 2> hard{4, 6};    ///< [min, max] for hard.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(simple));
    a->Visit(SIMS_NVP(mid));
    a->Visit(SIMS_NVP(hard));
  }
  /// 1 ≤ min ≤ max for each.
  void Validate() const;
  /// The range of a difficulty.
  std::array<int, 2> Range(Difficulty d) const;
};

/// A long script: keyframes from several short scripts plus how they were chosen.
struct LongScript {
  std::string theme;                         ///< The user's theme ("" for a given script).
  Difficulty difficulty = Difficulty::kMid;  ///< Requested length class.
  uint64_t seed = 0;                         ///< Seed that drew among near-best scripts.
  std::vector<ArcSegment> arc;               ///< The detected emotional arc.
  std::vector<std::string> script_ids;       ///< Short scripts used, one per segment.
  std::vector<std::string> segment_rooms;    ///< Room type of each segment.
  std::vector<Keyframe> keyframes;           ///< Executable keyframes (grammar repaired).
  std::string narrative;                     ///< Story text (filled by the planner or the LLM).

  /// Number of sit/lie/reach keyframes.
  int Interactions() const;
  /// The emotions of the interactions in order with consecutive repeats merged.
  std::vector<std::string> EmotionSequence() const;
};

/// Loads a user script: a short script object, an object with "keyframes" (a long script in
/// the same keyframe format), a bare keyframe array, or {"scripts": [short scripts...]}.
/// Missing walks/get-ups are inserted; errors name the file, keyframe index and field.
LongScript LoadLongScript(const std::filesystem::path& path,
                          const Vocabulary& vocab = Vocabulary::Default());

/// Builds a long script from a parsed JSON value of any of the LoadLongScript forms.
LongScript LongScriptFromJson(const nlohmann::json& j, const std::string& source,
                              const Vocabulary& vocab = Vocabulary::Default());

/// Concatenates short scripts into a long script (segments in order, grammar repaired).
LongScript ConcatenateScripts(const std::vector<ShortScript>& scripts, const std::string& source,
                              const Vocabulary& vocab = Vocabulary::Default());

/// The embedded theme planner.
class ThemePlanner {
 public:
  /// All references must outlive the planner.
  ThemePlanner(const ScriptDatabase& db, const Vocabulary& vocab, const EmotionLexicon& lexicon,
               RetrievalConfig retrieval = {}, DifficultyConfig difficulty = {},
               TextEmbedder embedder = {});
  /// Plans a long script; the same theme, difficulty and seed always give the same script.
  LongScript Plan(const std::string& theme, Difficulty difficulty, uint64_t seed) const;
  /// The retriever (for ranking tests and the LLM prompt's candidates).
  const ScriptRetriever& retriever() const { return retriever_; }
  /// Scripts ranked for a whole theme (each arc step's ranking merged, best first).
  std::vector<int> Candidates(const std::string& theme, int count) const;

 private:
  const ScriptDatabase& db_;
  const Vocabulary& vocab_;
  const EmotionLexicon& lexicon_;
  DifficultyConfig difficulty_;
  ScriptRetriever retriever_;
};

/// A template narrative naming the emotions, actions and furniture of a long script, one
/// sentence per arc step; `furniture_names` (optional, per keyframe) overrides the category
/// named for each keyframe (e.g. the bound object's category after substitution).
std::string TemplateNarrative(const LongScript& script,
                              const std::vector<std::string>& furniture_names = {},
                              const Vocabulary& vocab = Vocabulary::Default());

}  // namespace sims::planner
