// glTF 2.0 export (own writer): the scene's furniture, walls and a floor as meshes, and the
// humanoid as a 15-node hierarchy named and parented exactly like the BVH export
// (motion::HumanoidClipToBvh: pelvis → torso → head, ...), each node carrying its capsule /
// sphere / box shapes, animated by one animation ("motion") with the pelvis translation and
// every body's local rotation per recorded frame (LINEAR). Blender, three.js and Assimp read it.
//
// Node tree: "sims_world" (Z-up → glTF Y-up rotation) → {"pelvis" → ..., "scene" → objects →
// parts ("<instance>/<part>"), "walls", "floor"}. The scene node carries the record's keyframes
// and fps in its extras.
#pragma once

#include <filesystem>
#include <string>

#include "sims/io/motion_record.h"
#include "sims/scene/scene.h"

namespace sims::io {

/// What goes into the file.
struct GltfOptions {
  bool character = true;      ///< The animated humanoid.
  bool furniture = true;      ///< Scene objects.
  bool walls = true;          ///< scene.walls.
  bool floor = true;          ///< A floor quad under the scene and the motion.
  double floor_margin = 1.0;  ///< Floor extends this far beyond scene and motion bounds (m).
  int sphere_segments = 16;   ///< Tessellation of the character's round shapes.
};

/// Writes `path`: ".glb" = one binary file; ".gltf" = JSON plus "<stem>.bin" beside it. Both
/// are written atomically (the .bin before the .gltf). `scene` may be null (character only);
/// an empty record exports the scene without animation.
void ExportGltf(const MotionRecord& record, const scene::Scene* scene,
                const std::filesystem::path& path, const GltfOptions& options = {});

}  // namespace sims::io
