// extract_script: video → sampled JPEG frames (ffmpeg) → OpenAI-compatible vision-language
// endpoint → validated SIMS short script (+ the frames it used), ready for plan_story --db.
#include <unistd.h>

#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/environment.h"
#include "sims/io/video_frames.h"
#include "sims/planner/video_script.h"

namespace {

// Removes the scratch frames whatever happens.
struct ScratchDir {
  std::filesystem::path path;
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Extract a SIMS short script from a video with a vision-language model"};
  std::string video, out, unknown = "map";
  bool dry_run = false;
  sims::io::FrameSamplingOptions sampling;
  sims::planner::VideoScriptOptions options;
  sims::AppFlags flags;
  app.add_option("video", video, "video file (anything ffmpeg reads)")->required();
  app.add_option("--vlm-endpoint", options.endpoint,
                 "OpenAI-compatible http:// base URL of a model that accepts images");
  app.add_option("--model", options.model, "model name sent with the request");
  app.add_option("--api-key", options.api_key,
                 "API key (default $SIMS_LLM_API_KEY, then $OPENAI_API_KEY)");
  app.add_option("--out", out, "script to write; frames go to <stem>_frames/ next to it")
      ->required();
  app.add_option("--frames", sampling.count, "number of frames sent (1-64)");
  app.add_option("--sampling", sampling.mode, "fixed (evenly spaced) | scene (scene changes)");
  app.add_option("--scene-threshold", sampling.scene_threshold, "ffmpeg scene score for a cut");
  app.add_option("--width", sampling.width, "frame width in pixels (JPEG, aspect kept)");
  app.add_option("--timeout", options.timeout_s, "request time-out in seconds");
  app.add_option("--unknown", unknown,
                 "furniture/skills outside the vocabulary: map (nearest known) | reject");
  app.add_flag("--dry-run", dry_run, "write the request JSON to --out instead of sending it");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    options.unknown = sims::planner::ParseUnknownTerms(unknown, "--unknown");
    if (options.api_key.empty()) options.api_key = sims::InstalledEnvironment().LlmApiKey();
    options.video = std::filesystem::path(video).filename().string();
    if (!dry_run && options.endpoint.empty())
      sims::ThrowInputError("extract_script", "--vlm-endpoint",
                            "an http:// base URL (or --dry-run to only write the request)",
                            "nothing");
    ScratchDir scratch{std::filesystem::temp_directory_path() /
                       ("sims_extract_script." + std::to_string(::getpid()))};
    std::vector<sims::planner::ScriptFrame> frames;
    for (const auto& f : sims::io::SampleVideoFrames(video, sampling, scratch.path))
      frames.push_back({f.path, f.time_s});
    if (dry_run) {
      auto r = sims::planner::WriteVideoScriptRequest(frames, options, out);
      std::cout << "dry run: wrote the request (" << frames.size() << " frames) to " << out
                << " and the frames to " << r.frames_dir.string() << "/\n";
      return 0;
    }
    auto r = sims::planner::ExtractVideoScript(frames, options, out);
    std::cout << "wrote " << out << ": " << r.script.keyframes.size() << " keyframes, "
              << r.script.emotion << ", " << r.script.scene << " (\"" << r.script.summary
              << "\")\n";
    for (const std::string& n : r.notes) std::cout << "  note: " << n << "\n";
    std::cout << "frames: " << r.frames_dir.string() << "/ (" << frames.size() << ")\n";
    return 0;
  });
}
