// render_motion: a motion record (run_story's motion.json) or a motion clip → MP4 video of the
// character in its scene (MuJoCo offscreen through OSMesa, ffmpeg), optionally a glTF too.
#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/log.h"
#include "sims/io/gltf_export.h"
#include "sims/io/motion_record.h"
#include "sims/io/video.h"
#include "sims/scene/loaders.h"

int main(int argc, char** argv) {
  CLI::App app{"Render a motion record or clip to MP4 (software rendering, no display needed)"};
  std::string input, scene_spec, out = "story.mp4", gltf, config;
  sims::io::VideoOptions v;
  bool no_captions = false, no_shadows = false;
  sims::AppFlags flags;
  app.add_option("motion", input, "motion.json (run_story) or a motion clip .json")->required();
  app.add_option("--scene", scene_spec, "scene (built-in name or file); default: the record's");
  app.add_option("--out", out, "MP4 to write");
  app.add_option("--config", config, "video options JSON (VideoOptions fields)");
  app.add_option("--width", v.width, "frame width");
  app.add_option("--height", v.height, "frame height");
  app.add_option("--fps", v.fps, "video frame rate (0 = the record's)");
  app.add_option("--max-frames", v.max_frames, "render at most this many frames");
  app.add_option("--distance", v.camera_distance, "camera distance (m)");
  app.add_flag("--no-captions", no_captions, "no keyframe overlay");
  app.add_flag("--no-shadows", no_shadows, "skip the shadow pass (faster)");
  app.add_option("--gltf", gltf, "also export scene + animated character (.glb or .gltf)");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    if (!config.empty()) {
      const sims::io::VideoOptions defaults = v;
      v = sims::LoadConfig<sims::io::VideoOptions>(config, defaults);
    }
    v.captions = v.captions && !no_captions;
    v.shadows = v.shadows && !no_shadows;
    const sims::io::MotionRecord record = sims::io::LoadMotionRecordOrClip(input);
    if (scene_spec.empty())
      scene_spec = record.scene.source.empty() ? "empty" : record.scene.source;
    const sims::scene::Scene scene = sims::scene::LoadSceneFile(scene_spec);
    if (!gltf.empty()) sims::io::ExportGltf(record, &scene, gltf);
    const auto stats = sims::io::RenderVideo(record, scene, out, v);
    spdlog::info("wrote {} ({} frames, {:.1f} frames/s)", out, stats.frames, stats.render_fps);
    return 0;
  });
}
