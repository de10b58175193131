// run_story: plan (if needed) and simulate a story; writes result.json, motion.json,
// motion.bvh, scene.glb + index.html viewer, story.txt, plan.json, config.json (+ story.mp4).
// The pipeline is story/story.h's, the one eval_story measures.
#include <CLI/CLI.hpp>

#include <optional>

#include "sims/core/app.h"
#include "sims/core/config.h"
#include "sims/core/environment.h"
#include "sims/story/story.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Run a story: script.json | plan.json | --theme \"...\" | --instruction \"...\" | "
      "--scene-plan plan.json#id"};
  sims::story::StoryInput input;
  sims::fsm::StoryOptions options;
  sims::story::StoryWriteOptions write;
  std::string out = "out/story", options_file, policies;
  std::vector<double> goal;
  sims::AppFlags flags;
  app.add_option("input", input.input, "SIMS script or plan JSON");
  app.add_option("--theme", input.theme, "plan a story for this theme first");
  app.add_option("--instruction", input.instruction, "one sentence, e.g. \"sit on the armchair\"");
  app.add_option("--goal", goal, "goal location x y z for --instruction")->expected(3);
  app.add_option("--scene-plan", input.scene_plan,
                 "UniHSI ScenePlan plan.json[#id] (its own scene)");
  app.add_option("--partnet", input.partnet_root, "PartNet folder for --scene-plan");
  app.add_option("--difficulty", input.difficulty, "simple | mid | hard (themes)");
  app.add_option("--scene", input.scene,
                 "built-in scene name or scene file ('' = retrieve a built-in layout, as "
                 "eval_story does)");
  app.add_option("--style-model", input.style_model,
                 "motion-text model folder for caption -> z (default: data/language/text_motion, "
                 "else the bundled "
                 "assets/language/text_motion, "
                 "when present)");
  app.add_option("--policies", policies, "policy set (default assets/policies/policies.json)");
  app.add_option("--options", options_file, "FSM options JSON (e.g. configs/story.json)");
  std::optional<uint64_t> seed;
  app.add_option("--seed", seed, "seed");
  app.add_option("--out", out, "output directory");
  app.add_flag("--video", write.video, "also render DIR/story.mp4");
  bool no_text = false, no_heightmap = false;
  app.add_flag("--no-text", no_text, "ablation: zero the style z every policy sees");
  app.add_flag("--no-heightmap", no_heightmap, "ablation: zero the heightmap every policy sees");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    if (!options_file.empty()) options = sims::LoadConfig<sims::fsm::StoryOptions>(options_file);
    if (seed) options.seed = *seed;
    options.ablation.no_text |= no_text;
    options.ablation.no_heightmap |= no_heightmap;
    input.seed = options.seed;                         // the theme is planned with the story's seed
    input.environment = sims::InstalledEnvironment();  // $SIMS_LLM_* for --theme
    if (!goal.empty()) input.goal = Eigen::Vector3d(goal[0], goal[1], goal[2]);
    const auto policy_set = sims::fsm::LoadPolicySet(
        policies.empty() ? sims::fsm::DefaultPolicySetPath() : std::filesystem::path(policies));
    const auto prepared = sims::story::PrepareStory(input);
    sims::story::WriteStoryRun(out, sims::story::RunStory(prepared, policy_set, options), write);
    return 0;
  });
}
