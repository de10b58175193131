// Internal helpers shared by the scene loaders (not installed; Assimp stays in the .cpp).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "sims/scene/mesh.h"
#include "sims/scene/scene.h"

namespace sims::scene::internal {

/// One mesh of an imported node, already in the file's world frame.
struct ImportedMesh {
  std::string name;      ///< aiMesh name.
  std::string material;  ///< Material name.
  TriangleMesh mesh;     ///< Triangles (file world frame, unit scale applied).
};

/// A node subtree of an imported file.
struct ImportedNode {
  std::string name;                                    ///< Node name.
  Eigen::Affine3d X_WN = Eigen::Affine3d::Identity();  ///< Global transform.
  std::vector<ImportedMesh> meshes;                    ///< This node's own meshes.
  std::vector<ImportedNode> children;                  ///< Child nodes.
};

/// Reads a file with Assimp (triangulated, points and lines dropped; PLY files with ReadPly).
/// Throws sims::Error naming the file when it is missing or unreadable. `up_axis_hint` receives the
/// file's declared up axis ('x', 'y', 'z') or 0 when it declares none.
ImportedNode ImportWithAssimp(const std::filesystem::path& path, double unit_scale,
                              char* up_axis_hint = nullptr);

/// Reads a PLY file's vertex positions and faces (fan-triangulated) in file order: ASCII and
/// binary (little- or big-endian). Throws sims::Error naming the file and the field.
TriangleMesh ReadPly(const std::filesystem::path& path);

/// Rotation taking a Y-up frame to Z-up: (x, y, z) -> (x, -z, y).
Eigen::Isometry3d YUpToZUp();

/// Required member of a JSON object; throws naming the file and the field path.
const nlohmann::json& JsonField(const nlohmann::json& j, const std::string& key,
                                const std::string& source, const std::string& path,
                                const std::string& expected);

/// A number array of exactly n values (n < 0: any multiple of -n); throws naming the field.
std::vector<double> NumberArray(const nlohmann::json& j, int n, const std::string& source,
                                const std::string& path);

/// Reads and parses a JSON file; errors name the file.
nlohmann::json ReadJson(const std::filesystem::path& path);

/// Deterministic per-scene sampling of part point clouds.
void SampleScenePoints(Scene* scene, int points_per_part, uint64_t seed = 0);

/// Closes the object's pose bookkeeping for meshes loaded directly in world frame: X_WO is
/// the translation to the footprint centre at the floor.
void SetPoseFromBounds(Object* object);

/// Lower-cased extension including the dot.
std::string LowerExtension(const std::filesystem::path& path);

}  // namespace sims::scene::internal
