// eval_policy: success rate, contact error, success steps, time to success and falls of a
// trained skill policy over N trials on held-out objects, or on a UniHSI ScenePlan.
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/config.h"
#include "sims/core/hash.h"
#include "sims/eval/policy_eval.h"

int main(int argc, char** argv) {
  CLI::App app{"Evaluate a trained skill policy"};
  sims::eval::PolicyEvalOptions o;
  sims::AppFlags flags;
  std::string checkpoint, config, partnet, out;
  bool json = false;
  app.add_option("--checkpoint", checkpoint, "policy file written by train_policy (policy.pt)")
      ->required();
  app.add_option("--skill", o.skill, "expected skill (default: the policy's)");
  app.add_option("--trials", o.trials, "number of trials")->check(CLI::PositiveNumber);
  app.add_option("--seed", o.seed, "environment seed");
  app.add_option("--objects", o.num_objects,
                 "pieces in the evaluation ground, a fixed test set whatever the training used "
                 "(default 16; 0 = the policy's num_objects)");
  app.add_option("--config", config, "TrainConfig JSON instead of the policy's metadata");
  app.add_option("--scene-plan", o.scene_plan, "UniHSI ScenePlan plan.json[#id] (unified)");
  app.add_option("--partnet", partnet, "PartNet folder for --scene-plan");
  app.add_option("--envs", o.num_envs, "parallel environments (0 = min(trials, 16))");
  app.add_flag("--no-text", o.ablation.no_text, "ablation: zero the style z the policy sees");
  app.add_flag("--no-heightmap", o.ablation.no_heightmap,
               "ablation: zero the heightmap the policy sees");
  app.add_flag("--style-eval", o.style_eval,
               "style accuracy: each trial's z from a held-out caption, its motion classified");
  app.add_option("--style-captions", o.style_captions,
                 "captions for --style-eval (default configs/language/test_paraphrases.json)");
  app.add_option("--style-model", o.style_model,
                 "motion-text model for --style-eval (default: the policy's, else bundled)");
  app.add_option("--reference-starts", o.reference_starts,
                 "share of trials started from motion clips as in training (0-1; default 0: "
                 "standing starts)");
  app.add_option("--clutter", o.clutter,
                 "share of the evaluation pieces with a table in front, as the stories' rooms "
                 "have (0-1; default 0: lone pieces)");
  app.add_option("--action-smoothing", o.action_smoothing,
                 "action smoothing: each step's PD targets blended with the ones held before "
                 "by this factor (0-0.9), as a policy set's action_smoothing does (default: "
                 "the policy's own, from its training config)");
  app.add_flag("--training-starts", o.training_starts,
               "keep the skill's training start settings (get-up: the reach into the rise or "
               "the backplay window from level 0) instead of its evaluation ones");
  app.add_option("--record", o.record_dir,
                 "write the first --record-trials trials' motions (trial_K.json) and scenes with "
                 "the animated character (trial_K.glb) to this folder");
  app.add_option("--record-trials", o.record_trials, "trials --record keeps (default 4)")
      ->check(CLI::NonNegativeNumber);
  bool training_objects = false;
  app.add_flag("--training-objects", training_objects,
               "objects with the training dimensions instead of held-out ones (e.g. to record "
               "--end-states for training)");
  app.add_option("--end-states", o.end_states,
                 "write where each trial that did not fall ended (sit, lie: relative to the "
                 "seat or mattress) as hand-off states for get-up training");
  app.add_flag("--json", json, "print the report as JSON");
  app.add_option("--out", out, "also write the JSON report to this file");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  if (json) flags.default_log_level = "warn";
  return sims::RunApp(flags, [&] {
    o.threads = flags.threads;
    o.checkpoint = checkpoint;
    o.config = config;
    o.partnet_root = partnet;
    o.held_out = !training_objects;
    if (!o.record_dir.empty() && o.record_trials == 0) o.record_trials = 4;
    const auto report = sims::eval::EvaluatePolicy(o);
    auto j = report.ToJson();
    // Which weights were measured, whatever the path was called then.
    j["checkpoint_sha256"] = sims::Sha256OfFile(checkpoint);
    if (!out.empty()) sims::WriteJsonFile(out, j);
    if (json) {
      std::cout << j.dump(2) << "\n";
    } else {
      std::printf(
          "%s on %s: %d trials\n  success rate %.3f\n  falls %.3f\n  contact error %.3f m\n"
          "  success steps %.2f / %.2f\n  time to success %.2f s\n",
          report.skill.c_str(), report.scene.c_str(), report.trials, report.success_rate,
          report.fall_rate, report.contact_error, report.success_steps, report.mean_num_steps,
          report.time_to_success);
      for (const auto& [label, g] : report.by_start)
        std::printf("  from %s: %d trials, success %.3f, falls %.3f, time to success %.2f s\n",
                    label.c_str(), g.trials, g.success_rate, g.fall_rate, g.time_to_success);
    }
    return 0;
  });
}
