// Prompt templates shared by every model the planner talks to (the theme LLM, the video VLM,
// the imitation LLM): text files under configs/planner/ with {{placeholders}}, and the
// vocabulary placeholders every prompt offers ({{skills}}, {{furniture}}, {{emotions}},
// {{rooms}}, {{styles}}).
#pragma once

#include <map>
#include <string>

#include "sims/planner/vocabulary.h"

namespace sims::planner {

/// Reads a prompt template (a relative path is under configs/); errors name the file.
std::string ReadPromptTemplate(const std::string& file);

/// Replaces every {{key}} of `values` in `text`.
std::string FillPrompt(std::string text, const std::map<std::string, std::string>& values);

/// The vocabulary placeholders: skills (with one alias), furniture, emotions, rooms and the
/// style phrases per skill.
std::map<std::string, std::string> VocabularyPromptValues(const Vocabulary& vocab);

}  // namespace sims::planner
