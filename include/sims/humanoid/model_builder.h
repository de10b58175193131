// Builds the MuJoCo model of the humanoid in a scene: the humanoid MJCF plus static world
// geometry (boxes and convex meshes) inserted at the file's SIMS_SCENE_* markers. MuJoCo 2.2.2
// has no mjSpec, so composition happens at the XML level and loads through a virtual file system.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sims::humanoid {

/// One static collision geom attached to the world body.
struct StaticGeom {
  /// Box (pose + half sizes) or convex mesh (world-frame points; MuJoCo takes their hull).
  enum class Type { kBox, kConvexMesh };
  Type type = Type::kBox;                                  ///< Geometry kind.
  std::string name;                                        ///< Unique geom name.
  Eigen::Isometry3d X_WG = Eigen::Isometry3d::Identity();  ///< Box pose in world.
  Eigen::Vector3d half_size = Eigen::Vector3d::Zero();     ///< Box half extents.
  std::vector<Eigen::Vector3d> vertices;                   ///< Convex mesh points (world).
  double friction = 1.0;                                   ///< Sliding friction.
  Eigen::Vector4f rgba{0.55f, 0.45f, 0.35f, 1.0f};         ///< Display colour.
  /// Static body the geom is grouped into (one per object), empty = the world body. MuJoCo's
  /// broad phase bounds bodies, so world geoms would all be tested against every limb.
  std::string body;
};

/// The static part of a scene as MuJoCo sees it.
struct StaticGeometry {
  std::vector<StaticGeom> geoms;  ///< World geoms, humanoid-vs-scene collisions enabled.
};

/// Deleter for mjModel in smart pointers.
struct MjModelDeleter {
  /// Frees the model.
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
/// Deleter for mjData in smart pointers.
struct MjDataDeleter {
  /// Frees the data.
  void operator()(mjData* d) const { mj_deleteData(d); }
};
/// Owning model pointer (the model is shared read-only between environments).
using MjModelPtr = std::shared_ptr<const mjModel>;
/// Owning per-environment data pointer.
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;

/// Default humanoid MJCF (assets/humanoid/amp_humanoid.xml).
std::filesystem::path DefaultHumanoidPath();

/// Reads a text file; throws sims::Error naming the file when missing.
std::string ReadTextFile(const std::filesystem::path& path);

/// Inserts the static geometry into the humanoid MJCF text (throws if the markers are missing).
std::string ComposeModelXml(const std::string& humanoid_xml, const StaticGeometry& geometry,
                            const std::string& source = "humanoid MJCF");

/// Compiles MJCF text; compile errors throw sims::Error naming `source`.
MjModelPtr LoadModelFromXml(const std::string& xml, const std::string& source);

/// Humanoid from `humanoid_path` (default asset if empty) plus static geometry.
MjModelPtr BuildModel(const StaticGeometry& geometry = {},
                      const std::filesystem::path& humanoid_path = {});

/// New per-environment data for a model.
MjDataPtr MakeData(const mjModel* model);

}  // namespace sims::humanoid
