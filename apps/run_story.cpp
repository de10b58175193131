// run_story: plan (if needed) and simulate a story; writes result.json, motion.json,
// motion.bvh, scene.glb + index.html viewer, story.txt, plan.json, config.json (+ story.mp4).
#include <CLI/CLI.hpp>

#include <optional>

#include "sims/core/app.h"
#include "sims/core/config.h"
#include "sims/core/environment.h"
#include "sims/fsm/story_job.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Run a story: script.json | plan.json | --theme \"...\" | --instruction \"...\" | "
      "--scene-plan plan.json#id"};
  sims::fsm::StoryJob job;
  std::string out = job.out_dir.string(), options_file;
  std::vector<double> goal;
  sims::AppFlags flags;
  app.add_option("input", job.input, "SIMS script or plan JSON");
  app.add_option("--theme", job.theme, "plan a story for this theme first");
  app.add_option("--instruction", job.instruction, "one sentence, e.g. \"sit on the armchair\"");
  app.add_option("--goal", goal, "goal location x y z for --instruction")->expected(3);
  app.add_option("--scene-plan", job.scene_plan, "UniHSI ScenePlan plan.json[#id] (its own scene)");
  app.add_option("--partnet", job.partnet_root, "PartNet folder for --scene-plan");
  app.add_option("--difficulty", job.difficulty, "simple | mid | hard (themes)");
  app.add_option("--scene", job.scene, "built-in scene name or scene file");
  app.add_option("--policies", job.policies, "policy set (default assets/policies/policies.json)");
  app.add_option("--options", options_file, "FSM options JSON (e.g. configs/story.json)");
  std::optional<uint64_t> seed;
  app.add_option("--seed", seed, "seed");
  app.add_option("--out", out, "output directory");
  app.add_flag("--video", job.video, "also render DIR/story.mp4");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    if (!options_file.empty())
      job.options = sims::LoadConfig<sims::fsm::StoryOptions>(options_file);
    if (seed) job.options.seed = *seed;
    job.out_dir = out;
    job.environment = sims::InstalledEnvironment();  // $SIMS_LLM_* for --theme
    if (!goal.empty()) job.goal = Eigen::Vector3d(goal[0], goal[1], goal[2]);
    sims::fsm::RunStoryJob(job);
    return 0;
  });
}
