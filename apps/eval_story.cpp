// eval_story: SIMS Table 2 protocol over generated stories (success rate, contact error,
// success steps, penetration, foot sliding, FID, APD); prints JSON and writes --out. Stories run
// through run_story's pipeline (story/story.h), captions → style z included; they run batched
// (one policy call per policy per control step over all stories) unless --sequential. With
// --out X.json a per-difficulty HTML table goes to X.html.
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/config.h"
#include "sims/core/environment.h"
#include "sims/core/paths.h"
#include "sims/story/story_eval.h"

int main(int argc, char** argv) {
  CLI::App app{"Evaluate stories per difficulty (SIMS Table 2 protocol)"};
  sims::story::StoryEvalOptions o;
  std::string policies, themes, outputs,
      reference = sims::DataPath("motions/synthetic/manifest.json").string(), out;
  sims::AppFlags flags;
  app.add_option("--policies", policies, "policy set (default assets/policies/policies.json)");
  app.add_option("--themes", themes, "theme list (default configs/eval/story_themes.json)");
  app.add_option("--reference", reference, "reference clip manifest for FID ('' = no FID)");
  app.add_option("--stories", o.stories_per_difficulty, "stories per difficulty")
      ->check(CLI::PositiveNumber);
  app.add_option("--difficulties", o.difficulties, "simple mid hard");
  app.add_option("--seed", o.seed, "seed of story 0");
  app.add_option("--style-model", o.style_model,
                 "motion-text model folder for caption -> z (default: data/language/text_motion, "
                 "else the bundled "
                 "assets/language/text_motion, "
                 "when present)");
  app.add_option("--outputs", outputs,
                 "also write each story's run_story outputs to DIR/<difficulty>_<i>");
  app.add_option("--out", out, "write the JSON report here too (and its table to .html)");
  bool sequential = false;
  app.add_flag("--sequential", sequential,
               "run the stories one after another instead of batched (same results)");
  app.add_option("--batch-size", o.batch_size,
                 "at most this many stories at once (default 32; 0 = all)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--no-text", o.story.ablation.no_text, "ablation: zero the style z policies see");
  app.add_flag("--no-heightmap", o.story.ablation.no_heightmap,
               "ablation: zero the heightmap policies see");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    o.policies = policies;
    o.themes = themes;
    o.batched = !sequential;
    o.outputs_dir = outputs;
    o.environment = sims::InstalledEnvironment();  // $SIMS_LLM_* for planning the themes
    if (!reference.empty() && std::filesystem::exists(reference)) o.reference_manifest = reference;
    const auto r = sims::story::EvaluateStories(o);
    if (!out.empty()) {
      sims::WriteJsonFile(out, r);
      std::filesystem::path html = out;
      html.replace_extension(".html");
      if (html != std::filesystem::path(out))
        sims::WriteFileAtomic(html, sims::story::StoryEvalHtml(r));
    }
    std::cout << r.dump(2) << std::endl;
    return 0;
  });
}
