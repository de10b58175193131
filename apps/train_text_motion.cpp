// Trains the motion–text auto-encoder (SIMS eq. 3–5) and writes its model and embedding bank.
//   train_text_motion --config configs/language/text_motion.json --data DIR [--out DIR] [--resume]
// DIR holds one JSON file per clip: {"clip", "fps", "captions": [...], "features": [[...], ...]}.
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/language/motion_clips.h"
#include "sims/language/motion_text.h"
#include "sims/language/text_encoder.h"

int main(int argc, char** argv) {
  CLI::App app{"Train the motion-text auto-encoder (caption -> 64-d style embedding z)"};
  std::string config_path = "configs/language/text_motion.json", data, out;
  int steps = 0;
  bool resume = false;
  sims::AppFlags flags;
  app.add_option("--config", config_path, "training config (JSON)");
  std::string manifest;
  app.add_option("--data", data, "folder of clip JSON files (overrides data_dir)");
  app.add_option("--manifest", manifest,
                 "motion manifest (e.g. data/motions/synthetic/manifest.json) instead of --data");
  app.add_option("--out", out, "output folder (overrides out_dir)");
  app.add_option("--steps", steps, "optimiser steps (overrides steps)");
  sims::AddAppFlags(&app, &flags);
  app.get_option("--threads")->description("threads (0 = all cores; overrides threads)");
  app.add_flag("--resume", resume, "continue from <out>/checkpoint.pt");
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    auto cfg = sims::LoadConfig<sims::language::MotionTextTrainConfig>(config_path);
    if (!data.empty()) cfg.data_dir = data;
    if (!out.empty()) cfg.out_dir = out;
    if (steps > 0) cfg.steps = steps;
    // Only an explicit --threads overrides the config; training applies cfg.threads itself.
    if (app.count("--threads") > 0) cfg.threads = flags.threads;
    if (cfg.data_dir.empty() && manifest.empty())
      sims::ThrowInputError(config_path, "data_dir",
                            "a folder of clip JSON files (or --data DIR / --manifest FILE)");
    sims::ValidateConfig(cfg, config_path);
    const auto clips = manifest.empty() ? sims::language::LoadCaptionedSequences(cfg.data_dir)
                                        : sims::language::SequencesFromManifest(manifest);
    const auto encoder = sims::language::MakeTextEncoder(cfg.text_encoder, config_path);
    const auto losses = sims::language::TrainMotionText(cfg, clips, *encoder, resume);
    std::cout << "final losses: total " << losses.total << ", recon " << losses.recon << ", align "
              << losses.align << ", text " << losses.text_recon << "\n"
              << "outputs in " << cfg.out_dir
              << " (try: text_to_style \"a person walks sadly\" --model " << cfg.out_dir << ")\n";
    return 0;
  });
}
