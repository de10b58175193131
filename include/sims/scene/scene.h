// The scene model: rooms and furniture objects made of named parts. Frames: world W is Z-up,
// metres; X_WO places an object; part meshes and point clouds are stored in world frame.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sims/scene/mesh.h"

namespace sims::scene {

/// A named piece of an object ("seat surface", "back", "mattress", "pillow", ...).
struct Part {
  std::string name;                     ///< Part name (PartNet-like, e.g. "seat surface").
  int id = 0;                           ///< Part id within its object (UniHSI names carry it).
  TriangleMesh mesh;                    ///< World-frame triangles.
  std::vector<Eigen::Vector3d> points;  ///< World-frame surface samples, uniform by area.
};

/// One piece of furniture (or any object) in a scene.
struct Object {
  std::string category;   ///< Normalised category: chair, armchair, sofa, bed, table, ...
  std::string instance;   ///< Unique instance id within the scene (e.g. "chair_0").
  std::string source;     ///< Where it came from (file, model id, generator), for messages.
  std::string room;       ///< Id of the room that holds it ("" if none).
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();  ///< Object pose in world.
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();          ///< Scale applied before X_WO.
  std::vector<Part> parts;  ///< Named parts; an unsegmented object has one part "body".
  bool is_static = true;    ///< Static furniture becomes MuJoCo geometry.
  bool important = true;    ///< Lamps, vases and decor are less important scene-graph nodes.

  /// Bounds of all parts.
  Aabb Bounds() const;
  /// Part by name, or nullptr.
  const Part* FindPart(const std::string& name) const;
  /// All part meshes merged.
  TriangleMesh MergedMesh() const;
};

/// A room: type plus a floor polygon (xy, counter-clockwise) for layout composition.
struct Room {
  std::string id;                              ///< Unique room id.
  std::string type;                            ///< bedroom, living room, dining room, library.
  std::vector<Eigen::Vector2d> floor_polygon;  ///< Floor outline in world xy.
};

/// A whole scene: rooms, objects, and structural geometry (walls, floor).
struct Scene {
  std::string name;             ///< Scene name (file stem or built-in name).
  std::vector<Room> rooms;      ///< Rooms (may be empty for single-object scenes).
  std::vector<Object> objects;  ///< Furniture and props.
  TriangleMesh walls;           ///< Static non-furniture geometry (walls); floor is z = 0.

  /// Bounds of all objects and walls.
  Aabb Bounds() const;
  /// Object by instance id, or nullptr.
  const Object* FindObject(const std::string& instance) const;
  /// Indices of objects of a category.
  std::vector<int> ObjectsOfCategory(const std::string& category) const;
};

}  // namespace sims::scene
