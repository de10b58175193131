// Reading one English sentence: which skill and furniture a LINGO-style instruction names
// ("sit on the armchair with legs crossed"), and where a reach caption puts the hand. The story
// pipeline and the FSM's instruction binding ask here instead of splitting words themselves.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "sims/core/config.h"

namespace sims::planner {

/// How sentences are read (configs/planner/sentence.json).
struct SentenceConfig {
  std::string description;  ///< Free text.
  /// Word → skill name (a vocabulary skill or alias) for sentences whose words match no skill
  /// alias; data rather than code so that no planner code names a skill.
  std::map<std::string, std::string> fallback_verbs;

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(description));
    a->Visit(SIMS_NVP(fallback_verbs));
  }
};

/// Loads configs/planner/sentence.json (or `path`); every fallback verb must map to a skill the
/// default vocabulary knows.
SentenceConfig LoadSentenceConfig(const std::filesystem::path& path = {});

/// Turns a sentence into a one-interaction long-script JSON (skill and furniture found by the
/// default vocabulary, then configs/planner/sentence.json's fallback verbs; the caption is the
/// sentence); throws sims::Error naming --instruction when the sentence names no known skill.
nlohmann::json InstructionToScriptJson(const std::string& sentence);

/// Reach height a caption asks for: "low" (floor, bottom, pick up, ...), "high" (top, shelf,
/// overhead, ...), else "medium".
std::string ReachHeightFromCaption(const std::string& caption);

/// True when a reach caption says "left" (the left hand reaches), else the right hand does.
bool ReachUsesLeftHand(const std::string& caption);

}  // namespace sims::planner
