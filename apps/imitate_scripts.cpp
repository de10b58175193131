// imitate_scripts: N new short scripts in the style of the database (an OpenAI-compatible LLM
// with few-shot examples, or the offline template imitation), one validated JSON file each.
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/environment.h"
#include "sims/planner/imitation.h"

int main(int argc, char** argv) {
  CLI::App app{"Write new short scripts in the style of the short-script database"};
  std::vector<std::string> extras;
  std::string out, unknown = "map";
  sims::planner::ImitationOptions options;
  sims::AppFlags flags;
  app.add_option("--db", extras,
                 "extra scripts (folder of *.json or one file) appended to the built-in "
                 "database before sampling examples; repeatable");
  app.add_option("--llm-endpoint", options.endpoint,
                 "OpenAI-compatible http:// base URL (default: offline template imitation)");
  app.add_option("--model", options.model, "model name sent with the requests");
  app.add_option("--api-key", options.api_key,
                 "API key (default $SIMS_LLM_API_KEY, then $OPENAI_API_KEY)");
  app.add_option("--count", options.count, "number of new scripts")->required();
  app.add_option("--seed", options.seed, "seed (same database + seed = same scripts)");
  app.add_option("--out", out, "folder for the scripts (one <id>.json each)")->required();
  app.add_option("--examples", options.examples, "database scripts shown per LLM request");
  app.add_option("--temperature", options.temperature, "LLM sampling temperature");
  app.add_option("--timeout", options.timeout_s, "per-request time-out in seconds");
  app.add_option("--max-attempts", options.max_attempts,
                 "requests/recombinations before giving up (0 = 4 x count)");
  app.add_option("--unknown", unknown,
                 "furniture/skills outside the vocabulary in LLM answers: map | reject");
  app.add_option("--id-prefix", options.id_prefix, "ids are <prefix>_s<seed>_<NNN>");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    options.unknown = sims::planner::ParseUnknownTerms(unknown, "--unknown");
    if (options.api_key.empty()) options.api_key = sims::InstalledEnvironment().LlmApiKey();
    std::vector<std::filesystem::path> extra_paths(extras.begin(), extras.end());
    auto db = sims::planner::ScriptDatabase::LoadWithExtras({}, extra_paths);
    auto result = sims::planner::ImitateScripts(db, options);
    auto paths = sims::planner::WriteImitatedScripts(result, out);
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const auto& s = result.scripts[i];
      std::cout << paths[i].string() << ": " << s.script.emotion << ", " << s.script.scene << ", "
                << s.script.keyframes.size() << " keyframes (from "
                << s.provenance["sources"].dump() << ")\n";
    }
    for (const std::string& d : result.dropped) std::cout << "  dropped: " << d << "\n";
    std::cout << "wrote " << paths.size() << " of " << options.count << " scripts to " << out
              << " (" << result.attempts << " attempts, " << result.dropped.size() << " dropped)\n";
    if (static_cast<int>(paths.size()) < options.count) {
      std::cerr << "imitate_scripts: only " << paths.size() << " distinct valid scripts after "
                << result.attempts << " attempts (raise --max-attempts or add scripts)\n";
      return 3;
    }
    return 0;
  });
}
