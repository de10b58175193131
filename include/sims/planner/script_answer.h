// Short scripts written by a model (a vision-language model describing video frames, an LLM
// imitating the database) turned into database-ready scripts. The answer goes through the one
// short-script loader (ParseShortScript); before that, furniture, skills, emotions and rooms
// outside the vocabulary are mapped to the nearest known ones (Vocabulary::Nearest*) or
// rejected; after it, missing walks/get-ups are inserted and the strict database grammar is
// checked, so every file written can be loaded by ScriptDatabase::Load.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/planner/script.h"

namespace sims::planner {

/// What to do with names outside the vocabulary.
enum class UnknownTerms {
  kMap,     ///< Use the nearest known name and record a note (rejects when nothing is close).
  kReject,  ///< Throw the loader's error (it names the field and suggests the closest name).
};

/// Parses "map" | "reject"; errors name `source`.
UnknownTerms ParseUnknownTerms(const std::string& name, const std::string& source);

/// Largest short script the database holds (after inserted walks and get-ups).
inline constexpr int kMaxShortScriptKeyframes = 7;

/// Validates a model's answer text (code fences and chatter around the JSON object are removed)
/// and returns a database-ready short script; `notes` (optional) receives one line per mapped
/// term or inserted transition. Throws sims::Error naming `source`, the field and what was
/// expected.
ShortScript ParseScriptAnswer(const std::string& text, const std::string& source,
                              UnknownTerms unknown, std::vector<std::string>* notes = nullptr,
                              const Vocabulary& vocab = Vocabulary::Default());

/// The same for an already parsed JSON object ({summary, emotion, scene, keyframes}, or
/// {"scripts": [one such object]}).
ShortScript ValidateScriptAnswer(const nlohmann::json& answer, const std::string& source,
                                 UnknownTerms unknown, std::vector<std::string>* notes = nullptr,
                                 const Vocabulary& vocab = Vocabulary::Default());

/// Throws sims::Error unless the script could join the database: a summary, strict grammar,
/// at least one sit/lie/reach keyframe and at most kMaxShortScriptKeyframes keyframes.
void CheckDatabaseScript(const ShortScript& script, const std::string& source,
                         const Vocabulary& vocab = Vocabulary::Default());

/// What duplicate detection compares: skill, furniture, instance and style of every keyframe
/// (captions and summaries are ignored: the same motions reworded are the same script).
std::string KeyframeSignature(const std::vector<Keyframe>& keyframes);

/// Writes a script atomically in the database format (id = file stem), with a "provenance"
/// object when `provenance` is not null.
void WriteShortScript(const std::filesystem::path& path, ShortScript script,
                      const nlohmann::json& provenance = nullptr);

}  // namespace sims::planner
