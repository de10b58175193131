// New short scripts "in the style of" the database (SIMS §3.1: the LLM imitates extracted
// scripts to grow the database). With an endpoint, an LLM gets a few same-emotion scripts as
// examples and writes one new script per request; offline, a template imitation recombines the
// interaction units (walk to an object, use it, get up) of same-emotion scripts. Every result
// passes ValidateScriptAnswer (script_answer.h) and scripts whose keyframe sequence already
// exists (in the database or earlier in the run) are dropped. Both are deterministic by seed
// (the LLM as far as the server honours its seed).
//
//   ImitationOptions o;  o.count = 5;  o.seed = 0;
//   ImitationResult r = ImitateScripts(ScriptDatabase::Load(), o);
//   WriteImitatedScripts(r, "my_scripts/");  // my_scripts/imitated_s0_000.json ...
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/planner/script_answer.h"

namespace sims::planner {

/// How many scripts to write and with which back-end. Nothing here reads the environment.
struct ImitationOptions {
  int count = 5;                  ///< Scripts wanted.
  uint64_t seed = 0;              ///< Seed (same database + options + seed = same scripts).
  std::string endpoint;           ///< OpenAI-compatible http:// base URL ("" = offline).
  std::string model = "default";  ///< Model name sent in requests.
  std::string api_key;            ///< Bearer key ("" = none).
  double timeout_s = 60.0;        ///< Per-request time-out.
  int max_tokens = 1024;          ///< Answer length limit.
  double temperature = 0.7;       ///< Sampling temperature (some variety is the point).
  int examples = 3;               ///< Database scripts shown per request (few-shot).
  int max_attempts = 0;           ///< Requests / recombinations before giving up (0 = 4 × count).
  std::string system_prompt = "planner/imitation_system_prompt.txt";  ///< Under configs/.
  std::string user_prompt = "planner/imitation_user_prompt.txt";      ///< Under configs/.
  UnknownTerms unknown = UnknownTerms::kMap;  ///< Out-of-vocabulary terms in LLM answers.
  std::string id_prefix = "imitated";         ///< Ids are <prefix>_s<seed>_<NNN>.

  /// Throws sims::Error naming the option when a value is out of range.
  void Validate() const;
};

/// One new script and where it came from.
struct ImitatedScript {
  ShortScript script;         ///< Validated, database-ready script.
  nlohmann::json provenance;  ///< method, model, endpoint, seed, attempt, sources, notes.
};

/// What a run produced.
struct ImitationResult {
  std::vector<ImitatedScript> scripts;  ///< At most `count` distinct new scripts.
  std::vector<std::string> dropped;     ///< One line per rejected answer or duplicate.
  int attempts = 0;                     ///< Requests or recombinations made.
};

/// Writes `count` new scripts (fewer only when max_attempts ran out; `dropped` says why).
/// Throws LlmError naming the endpoint on connection failures, time-outs and HTTP errors.
ImitationResult ImitateScripts(const ScriptDatabase& db, const ImitationOptions& options,
                               const Vocabulary& vocab = Vocabulary::Default());

/// Writes one <id>.json per script into `dir` (created; each file atomic) and returns the paths.
/// The folder can be passed to plan_story --db or copied into a database folder.
std::vector<std::filesystem::path> WriteImitatedScripts(const ImitationResult& result,
                                                        const std::filesystem::path& dir);

}  // namespace sims::planner
