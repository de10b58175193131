// Everything a story run leaves for people to look at, written in one call by run_story:
//   DIR/motion.json  the motion record (io/motion_record.h)
//   DIR/motion.bvh   the humanoid motion as BVH (motion::HumanoidClipToBvh, Y-up centimetres)
//   DIR/scene.glb    scene meshes + animated 15-node character (io/gltf_export.h)
//   DIR/index.html   web viewer (+ viewer.js, three/) playing scene.glb with motion.json
//   DIR/story.mp4    optional video (io/video.h)
// Every file is written to a temporary name and renamed, so a failed run never leaves a
// half-written file (earlier complete outputs stay until replaced).
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "sims/humanoid/model_builder.h"
#include "sims/io/gltf_export.h"
#include "sims/io/motion_record.h"
#include "sims/io/video.h"
#include "sims/io/viewer.h"
#include "sims/motion/retarget.h"
#include "sims/scene/scene.h"

namespace sims::io {

/// Which outputs to write and how.
struct StoryOutputOptions {
  bool motion_json = true;   ///< DIR/motion.json.
  bool bvh = true;           ///< DIR/motion.bvh.
  bool gltf = true;          ///< DIR/scene.glb.
  bool viewer = true;        ///< DIR/index.html (+ viewer.js, three/); needs motion_json and gltf.
  bool video = false;        ///< DIR/story.mp4 (run_story --video).
  GltfOptions gltf_options;  ///< glTF content.
  VideoOptions video_options;              ///< Video settings.
  ViewerOptions viewer_options;            ///< Viewer file sources.
  motion::HumanoidBvhOptions bvh_options;  ///< BVH axes and units.
  /// The run's physics geometry, reused for the video instead of compiling the scene again.
  const humanoid::StaticGeometry* geometry = nullptr;
};

/// What was written.
struct StoryOutputs {
  std::vector<std::filesystem::path> files;  ///< Paths written (top-level files).
  std::optional<VideoStats> video;           ///< Video statistics when rendered.
};

/// Writes the outputs into `dir` (created if needed). Throws sims::Error naming the file
/// that could not be produced; files finished before the error are complete.
StoryOutputs WriteStoryOutputs(const std::filesystem::path& dir, const MotionRecord& record,
                               const scene::Scene& scene, const StoryOutputOptions& options = {});

}  // namespace sims::io
