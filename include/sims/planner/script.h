// SIMS short scripts (SIMS §3.1): the JSON an LLM or a person writes, its tolerant loader,
// the keyframe grammar, and the short-script database shipped in assets/scripts/.
//
//   {"summary": "...", "emotion": "sad", "scene": "bedroom",
//    "keyframes": [{"skill": "loco|sitdown|standup|liedown|getup|touch",
//                   "emotion/style": "tired, sad", "caption": "head bowed while walking",
//                   "furniture": "floor|armchair|sofa|bed|...",
//                   "style": "slow_bowed" (optional), "instance": 0 (optional)}]}
//
// Accepted variants: "furniture" or "furnitures" (string or one-element list), "emotion/style",
// "emotion", "emotions" or "style" for the keyframe mood, emotion lists as strings ("tired, sad")
// or arrays, skill aliases (loco→walk, sitdown→sit, liedown→lie, touch→reach, standup→getup, ...)
// and furniture aliases (couch→sofa, bookcase→bookshelf, ...). Single-quoted pseudo-JSON is
// rejected with a message that says how to fix it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/planner/vocabulary.h"

namespace sims::planner {

/// One keyframe of a short or long script.
struct Keyframe {
  Skill skill = Skill::kWalk;       ///< What the character does.
  std::string emotion = "neutral";  ///< Primary canonical emotion.
  std::vector<std::string> tags;    ///< Every emotion/style word as written ("tired", "sad").
  std::string style;                ///< Style id valid for the skill ("slow_bowed", "right_high").
  bool style_from_caption = false;  ///< The caption (or an explicit field) chose the style.
  std::string caption;              ///< Free-text description of the motion.
  std::string furniture = "floor";  ///< Canonical furniture category ("floor": none).
  int instance = 0;                 ///< Which object of that category within its short script.
  std::string script_id;            ///< Short script it came from ("" if written directly).
  int segment = 0;                  ///< Index of that short script within a long script.
  bool inserted = false;            ///< Added by the composer to satisfy the grammar.
};

/// A short script: one emotion in one room, 3–7 keyframes.
struct ShortScript {
  std::string id;                     ///< File stem or given "id".
  std::string source;                 ///< File path or "LLM reply", for messages.
  std::string summary;                ///< One-sentence summary.
  std::string emotion = "neutral";    ///< Canonical emotion of the script.
  std::string scene = "living room";  ///< Canonical room type.
  std::vector<Keyframe> keyframes;    ///< Keyframes in order.

  /// Summary and captions joined (the BM25 document).
  std::string Text() const;
  /// Number of sit/lie/reach keyframes.
  int Interactions() const;
};

/// How strictly the loader applies the keyframe grammar.
enum class GrammarMode {
  kStrict,   ///< Missing walks/get-ups are errors (the shipped database must be complete).
  kLenient,  ///< Missing walks/get-ups are inserted later by InsertTransitions.
};

/// A grammar problem found in a keyframe sequence.
struct GrammarIssue {
  int index = 0;         ///< Keyframe index.
  std::string field;     ///< Offending field ("skill", "furniture").
  std::string message;   ///< What is wrong and what to do.
  bool fixable = false;  ///< InsertTransitions can repair it (missing walk / get-up).
};

/// Parses JSON text (not yet parsed) into a short script; `source` names the file in errors.
/// Rejects single-quoted pseudo-JSON and other parse errors with file, line and a fix hint.
ShortScript ParseShortScriptText(const std::string& text, const std::string& source,
                                 GrammarMode mode = GrammarMode::kLenient,
                                 const Vocabulary& vocab = Vocabulary::Default());

/// Parses an already parsed JSON object.
ShortScript ParseShortScript(const nlohmann::json& j, const std::string& source,
                             GrammarMode mode = GrammarMode::kLenient,
                             const Vocabulary& vocab = Vocabulary::Default());

/// Parses a keyframe array (the "keyframes" of a script or an LLM's long script); `field`
/// prefixes field names in errors ("keyframes").
std::vector<Keyframe> ParseKeyframes(const nlohmann::json& j, const std::string& source,
                                     const std::string& field, const std::string& script_emotion,
                                     const Vocabulary& vocab = Vocabulary::Default());

/// Loads one short script file (id = file stem unless the file gives one).
ShortScript LoadShortScript(const std::filesystem::path& path,
                            GrammarMode mode = GrammarMode::kLenient,
                            const Vocabulary& vocab = Vocabulary::Default());

/// Serialises a short script in the canonical SIMS format (canonical names, explicit style).
nlohmann::json ShortScriptToJson(const ShortScript& script);

/// Serialises keyframes in the canonical SIMS format.
nlohmann::json KeyframesToJson(const std::vector<Keyframe>& keyframes);

/// Checks the grammar: get-up only after sit/lie (never fixable), a walk before interacting with
/// a different object and before the first interaction, standing before walking/reaching/sitting
/// elsewhere (fixable). An empty result means the sequence is executable as is.
std::vector<GrammarIssue> CheckGrammar(const std::vector<Keyframe>& keyframes,
                                       const Vocabulary& vocab = Vocabulary::Default());

/// Repairs fixable issues by inserting styled walks and get-ups (marked `inserted`) and fixes
/// get-up styles; throws sims::Error (naming `source`) for unfixable ones.
std::vector<Keyframe> InsertTransitions(const std::vector<Keyframe>& keyframes,
                                        const std::string& source,
                                        const Vocabulary& vocab = Vocabulary::Default());

/// Throws sims::Error "<source>: field 'keyframes[i].<field>': expected ..." for the first
/// issue (all issues in strict mode, unfixable ones in lenient mode).
void ThrowOnGrammarIssues(const std::vector<GrammarIssue>& issues, const std::string& source,
                          const std::string& field_prefix, GrammarMode mode);

/// The short-script database (assets/scripts/ by default).
class ScriptDatabase {
 public:
  /// Loads every *.json below `dir` (sorted by path, so ids and order are deterministic);
  /// scripts must pass the strict grammar. Duplicate ids are an error.
  static ScriptDatabase Load(const std::filesystem::path& dir = {},
                             const Vocabulary& vocab = Vocabulary::Default());
  /// Loads the database at `dir` ("" = assets/scripts) and appends `extras` in order: each a
  /// folder of *.json short scripts (searched recursively, sorted) or one script file, e.g. the
  /// output of extract_script or imitate_scripts. Every script must pass the strict grammar;
  /// ids must be unique across all of them (errors name both files).
  static ScriptDatabase LoadWithExtras(const std::filesystem::path& dir,
                                       const std::vector<std::filesystem::path>& extras,
                                       const Vocabulary& vocab = Vocabulary::Default());
  /// Builds a database from scripts already in memory (tests).
  explicit ScriptDatabase(std::vector<ShortScript> scripts = {});

  /// All scripts.
  const std::vector<ShortScript>& scripts() const { return scripts_; }
  /// Script by id, or nullptr.
  const ShortScript* Find(const std::string& id) const;
  /// Number of scripts.
  std::size_t size() const { return scripts_.size(); }

 private:
  std::vector<ShortScript> scripts_;
};

}  // namespace sims::planner
