// Built-in procedural furniture with PartNet-like named parts, built-in furnished rooms and a
// multi-room house. Object frame convention: origin at the centre of the footprint on the
// floor, +z up, +x is the front (a person sitting on a chair faces +x), +y is the object's left.
#pragma once

#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/core/rng.h"
#include "sims/scene/scene.h"

namespace sims::scene {

/// Dimensions of one procedural furniture piece (metres). Which fields matter depends on the
/// category; DefaultFurnitureParams gives sensible values for each.
struct FurnitureParams {
  double width = 0.46;            ///< Extent along the object's y axis (left-right).
  double depth = 0.46;            ///< Extent along x (front-back; bed: length).
  double height = 0.9;            ///< Overall height (chair: top of the back; table: top).
  double seat_height = 0.45;      ///< Top of the seat / mattress.
  double seat_thickness = 0.05;   ///< Seat slab, cushion or mattress thickness.
  double back_thickness = 0.04;   ///< Back rest / headboard thickness.
  double arm_height = 0.22;       ///< Arm rest top above the seat top.
  double arm_width = 0.05;        ///< Arm rest width.
  double leg_width = 0.04;        ///< Square leg side.
  double board_thickness = 0.03;  ///< Table tops, shelf boards, cabinet panels.
  bool has_back = true;           ///< Chairs: back rest present.
  bool has_arms = false;          ///< Chairs: arm rests present.
  int pillows = 1;                ///< Beds: number of pillows.
  int cushions = 3;               ///< Sofas: number of seat cushions.
  int shelves = 4;                ///< Shelves: number of boards between bottom and top.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(width));
    a->Visit(SIMS_NVP(depth));
    a->Visit(SIMS_NVP(height));
    a->Visit(SIMS_NVP(seat_height));
    a->Visit(SIMS_NVP(seat_thickness));
    a->Visit(SIMS_NVP(back_thickness));
    a->Visit(SIMS_NVP(arm_height));
    a->Visit(SIMS_NVP(arm_width));
    a->Visit(SIMS_NVP(leg_width));
    a->Visit(SIMS_NVP(board_thickness));
    a->Visit(SIMS_NVP(has_back));
    a->Visit(SIMS_NVP(has_arms));
    a->Visit(SIMS_NVP(pillows));
    a->Visit(SIMS_NVP(cushions));
    a->Visit(SIMS_NVP(shelves));
  }
  /// Positive sizes, seat below the overall height, non-negative counts.
  void Validate() const;
};

/// Categories MakeFurniture knows: chair, armchair, sofa, bed, stool, table, desk, cabinet,
/// wardrobe, shelf, lamp.
std::vector<std::string> ProceduralCategories();

/// Nominal dimensions of a category (throws sims::Error listing the categories if unknown).
FurnitureParams DefaultFurnitureParams(const std::string& category);
/// A low coffee table (category "table"): the living room's, also the training ground's clutter.
FurnitureParams CoffeeTableParams();

/// Builds a piece at the origin (X_WO = identity) with named parts and sampled point clouds.
/// Part names: chair "seat surface", "legs", "back", "left arm", "right arm"; armchair/sofa
/// "base", "seat surface", "back", "left arm", "right arm"; bed "legs", "frame", "headboard",
/// "mattress", "pillow" (one part per pillow); stool "seat surface", "legs"; table "top", "legs";
/// desk "top", "legs", "drawers"; cabinet "body", "top", "door"; wardrobe "body", "door";
/// shelf "side panel", "back panel", "board"; lamp "base", "pole", "shade".
Object MakeFurniture(const std::string& category, const FurnitureParams& params,
                     const std::string& instance = "");

/// The factor range training pieces draw each nominal dimension from; the held-out bands
/// [0.76, 0.86] and [1.14, 1.24] are cut out of it, so a wider range still never gives a
/// training piece a held-out value.
struct TrainingScale {
  double min = 0.9;  ///< Smallest factor (> 0, ≤ 0.9).
  double max = 1.1;  ///< Largest factor (≥ 1.1).
};

/// Random dimensions: training pieces scale each nominal dimension by a factor uniform over
/// `training` minus the held-out bands (default U[0.9, 1.1]); held-out pieces by U[0.76, 0.86]
/// or U[1.14, 1.24], so the two sets never share a dimension value.
FurnitureParams RandomFurnitureParams(const std::string& category, Rng& rng, bool held_out,
                                      const TrainingScale& training = {});

/// MakeFurniture(category, RandomFurnitureParams(category, rng, held_out, training), instance).
Object RandomFurniture(const std::string& category, Rng& rng, bool held_out,
                       const std::string& instance = "", const TrainingScale& training = {});

/// Rotates an object by `yaw` (radians, about +z through its origin) and moves its origin to
/// (x, y) on the floor.
void PlaceObject(Object* object, double x, double y, double yaw);

/// Furnished single rooms with walls: "bedroom", "living_room", "dining_room", "library".
std::vector<Scene> BuiltinRooms();

/// A 10 m x 10 m house of four furnished rooms (living room, dining room, bedroom, library)
/// with door openings between them and free floor around the furniture.
Scene BuiltinHouse();

/// `count` closed 5 m × 5 m rooms with walls, 1 m apart on a grid, each furnished with 4–7
/// random pieces (RandomFurniture: held-out dimensions when `held_out`) against the walls or
/// free-standing, without overlaps and covering at most 35 % of the floor; rooms are
/// "room_<k>". For training and evaluating walks among furniture.
Scene RandomRooms(int count, Rng& rng, bool held_out);

/// Names accepted by BuiltinScene.
std::vector<std::string> BuiltinSceneNames();

/// A built-in scene by name: "house", a room name, "empty", or a procedural category (one
/// default piece at the origin). Spaces and '_' are interchangeable; unknown names throw
/// sims::Error listing the valid ones.
Scene BuiltinScene(const std::string& name);

}  // namespace sims::scene
