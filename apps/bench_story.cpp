// bench_story: the protocol's stories run one after another and batched (one policy call per
// policy per control step over all of them); prints both times, the speed-up and whether the
// results are identical.
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/config.h"
#include "sims/story/story_eval.h"

int main(int argc, char** argv) {
  CLI::App app{"Time stories run sequentially vs batched"};
  sims::story::StoryEvalOptions o;
  o.difficulties = {"simple"};
  o.stories_per_difficulty = 8;
  std::string policies, themes, options, out;
  sims::AppFlags flags;
  app.add_option("--policies", policies, "policy set (default assets/policies/policies.json)");
  app.add_option("--themes", themes, "theme list (default configs/eval/story_themes.json)");
  app.add_option("--stories", o.stories_per_difficulty, "stories per difficulty")
      ->check(CLI::PositiveNumber);
  app.add_option("--difficulties", o.difficulties, "simple mid hard (default simple)");
  app.add_option("--seed", o.seed, "seed of story 0");
  app.add_option("--style-model", o.style_model, "motion-text model folder (as eval_story)");
  app.add_option("--options", options, "FSM options JSON (configs/story.json format)");
  app.add_option("--out", out, "write the JSON here too");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    o.policies = policies;
    o.themes = themes;
    if (!options.empty()) o.story = sims::LoadConfig<sims::fsm::StoryOptions>(options);
    const auto r = sims::story::BenchStories(o);
    if (!out.empty()) sims::WriteJsonFile(out, r);
    std::cout << r.dump(2) << std::endl;
    return 0;
  });
}
