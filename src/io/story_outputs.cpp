#include "sims/io/story_outputs.h"

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/sim/scene_physics.h"

namespace sims::io {

StoryOutputs WriteStoryOutputs(const std::filesystem::path& dir, const MotionRecord& record,
                               const scene::Scene& scene, const StoryOutputOptions& options) {
  record.Validate("motion record for " + dir.string());
  if (options.viewer && !(options.motion_json && options.gltf))
    ThrowInputError("StoryOutputOptions", "viewer",
                    "motion_json and gltf enabled too (it plays them)", "viewer without them");
  if (options.video) ValidateConfig(options.video_options, "StoryOutputOptions.video_options");
  std::filesystem::create_directories(dir);
  StoryOutputs out;
  if (options.motion_json) {
    SaveMotionRecord(record, dir / "motion.json");
    out.files.push_back(dir / "motion.json");
  }
  if (options.bvh && !record.frames.empty()) {
    motion::WriteHumanoidBvh(RecordToClip(record), dir / "motion.bvh", options.bvh_options);
    out.files.push_back(dir / "motion.bvh");
  }
  if (options.gltf) {
    ExportGltf(record, &scene, dir / "scene.glb", options.gltf_options);
    out.files.push_back(dir / "scene.glb");
  }
  if (options.viewer) {
    InstallViewer(dir, options.viewer_options);
    out.files.push_back(dir / "index.html");
  }
  if (options.video) {
    out.video =
        options.geometry
            ? RenderVideo(record, *options.geometry, dir / "story.mp4", options.video_options)
            : RenderVideo(record, scene, dir / "story.mp4", options.video_options);
    out.files.push_back(dir / "story.mp4");
  }
  spdlog::info("story outputs in {}: {} files{}", dir.string(), out.files.size(),
               options.viewer ? " (view: serve_viewer " + dir.string() + ")" : "");
  return out;
}

}  // namespace sims::io
