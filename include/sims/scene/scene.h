// The scene model: rooms and furniture objects made of named parts. Frames: world W is Z-up,
// metres; X_WO places an object; part meshes and point clouds are stored in world frame.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sims/core/rng.h"
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
  std::string category;  ///< Normalised category: chair, armchair, sofa, bed, table, ...
  std::string instance;  ///< Unique instance id within the scene (e.g. "chair_0").
  std::string source;    ///< Where it came from (file, model id, generator), for messages.
  std::string room;      ///< Id of the room that holds it ("" if none).
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();  ///< Object pose in world.
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();         ///< Scale applied before X_WO.
  std::vector<Part> parts;  ///< Named parts; an unsegmented object has one part "body".
  bool is_static = true;    ///< Static furniture becomes MuJoCo geometry.
  bool important = true;    ///< Lamps, vases and decor are less important scene-graph nodes.

  /// Bounds of all parts.
  Aabb Bounds() const;
  /// Bounds of all parts expressed in the object frame (X_WO⁻¹ applied), i.e. the footprint.
  Aabb LocalBounds() const;
  /// Part by name, or nullptr.
  const Part* FindPart(const std::string& name) const;
  /// Part by a dataset key: "seat surface", "seat_surface", or UniHSI's name+id
  /// ("seat_soft_surface16", "pillow20"); nullptr when none matches.
  const Part* FindPartByKey(const std::string& key) const;
  /// All parts with this name (beds may have several pillows).
  std::vector<const Part*> PartsNamed(const std::string& name) const;
  /// All part meshes merged.
  TriangleMesh MergedMesh() const;
  /// Moves the object: meshes and points are transformed and X_WO becomes X * X_WO.
  void ApplyTransform(const Eigen::Isometry3d& X);
  /// Re-samples every part's point cloud uniformly by area (`points_per_part` each).
  void ResamplePoints(Rng& rng, int points_per_part = kDefaultPointsPerPart);

  /// Default number of surface samples per part.
  static constexpr int kDefaultPointsPerPart = 256;
};

/// UniHSI's part key: the name with spaces as underscores followed by the id ("pillow20").
std::string UniHsiPartKey(const Part& part);

/// Lower-case, trimmed, '_' and '-' as spaces ("Seat_Surface" -> "seat surface").
std::string NormalizeName(const std::string& name);

/// A room: type plus a floor polygon (xy, counter-clockwise) for layout composition.
struct Room {
  std::string id;                              ///< Unique room id.
  std::string type;                            ///< bedroom, living room, dining room, library.
  std::vector<Eigen::Vector2d> floor_polygon;  ///< Floor outline in world xy.

  /// True when p lies inside the floor polygon (even-odd rule).
  bool Contains(const Eigen::Vector2d& p) const;
  /// Area-weighted centroid of the floor polygon.
  Eigen::Vector2d Centroid() const;
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
  /// Index of the object with this instance id, or -1.
  int ObjectIndex(const std::string& instance) const;
  /// Indices of objects of a category.
  std::vector<int> ObjectsOfCategory(const std::string& category) const;
  /// Room by id, or nullptr.
  const Room* FindRoom(const std::string& id) const;
  /// The room whose floor contains (x, y), or nullptr.
  const Room* RoomAt(double x, double y) const;
  /// An instance id "<category>_<n>" not used yet (spaces become '_').
  std::string UniqueInstanceId(const std::string& category) const;
  /// Appends an object, replacing an empty or duplicate instance id by UniqueInstanceId.
  Object& AddObject(Object object);
  /// Total number of triangles (objects and walls).
  std::size_t TriangleCount() const;
};

}  // namespace sims::scene
