// plan_story: theme or script → long script (embedded planner or an OpenAI-compatible LLM with
// automatic fall-back) → layout retrieval and object binding → plan.json for run_story.
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/environment.h"
#include "sims/planner/planner.h"

int main(int argc, char** argv) {
  CLI::App app{"Plan a story: keyframes bound to furniture of a retrieved layout (plan.json)"};
  sims::planner::PlanRequest r;
  std::string out = "plan.json";
  sims::AppFlags flags;
  auto* theme =
      app.add_option("--theme", r.theme, "story theme, e.g. \"happy at first, then sad\"");
  app.add_option("--script", r.script, "short/long script JSON instead of a theme")
      ->excludes(theme);
  app.add_option("--difficulty", r.difficulty, "simple (2 interactions) | mid (3-4) | hard (4-6)");
  app.add_option("--seed", r.seed, "seed (same theme + seed = same plan)");
  app.add_option("--layouts", r.layouts, "layout database from index_layouts (default: built-in)");
  app.add_option("--scene", r.scene, "bind to this scene (built-in name or file) instead");
  app.add_option("--config", r.config, "planner config (default configs/planner/planner.json)");
  app.add_option("--db", r.extra_scripts,
                 "extra short scripts appended to the built-in database: a folder of *.json "
                 "(extract_script / imitate_scripts output) or one script file; repeatable");
  app.add_option("--llm-endpoint", r.llm_endpoint, "OpenAI-compatible http:// base URL");
  app.add_option("--llm-model", r.llm_model, "model name");
  app.add_option("--llm-key", r.llm_key, "API key (default $SIMS_LLM_API_KEY / $OPENAI_API_KEY)");
  app.add_option("--llm-timeout", r.llm_timeout_s, "LLM time-out in seconds");
  app.add_option("--out", out, "plan file to write");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    r.environment = sims::InstalledEnvironment();  // $SIMS_LLM_* where config and flags are silent
    sims::planner::Plan plan = sims::planner::PlanStory(r);
    sims::planner::SavePlan(out, plan);
    std::cout << sims::planner::DescribePlan(plan) << "wrote " << out << "\n";
    return plan.AllPlaced() ? 0 : 3;  // 3: plan written, but some keyframes are unplaced
  });
}
