// Hand-off states: where one skill's policy leaves the character on a piece of furniture, kept
// relative to the furniture part, so another skill can train from them on other objects.
//
// Why: in stories a get-up starts where the sit or lie policy stopped (slumped, half on the
// seat, lying askew), not in a get-up clip's seated pose. Over `eval_story --stories 30` the
// bundled get-up fell in 47 of 73 keyframes that followed a sit (34 of 43 after a sit that
// timed out, with the head at ~0.67 m), while it rose in 21 of 26 clip-seated evaluation
// trials. `eval_policy --end-states F` records such states; an object skill's handoff_states
// trains from them (a share of its reference starts): get-up from sit and lie end states, lie
// from sit end states (in stories most lie keyframes follow a sit on the same bed or sofa).
//
// Frames: O is the object frame (yaw-only; a seat's front is +x, a bed's headboard at −x). A
// state is stored with the part's object-frame box; its anchor A is a seat's front-edge
// centre on top, a mattress's head-end centre on top. Placing a state on another object's
// part of the same name keeps p_AP (the pose relative to the anchor) and raises the pose by
// max(Δtop, 0): a lower seat leaves the pelvis hovering, a higher one lifts the feet, never
// into the floor.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sims/humanoid/state.h"
#include "sims/scene/mesh.h"
#include "sims/task/object_skill.h"

namespace sims::task {

/// One recorded end state, in the object frame.
struct HandoffState {
  std::string skill;            ///< Skill whose episode ended here ("sit", "lie").
  std::string part;             ///< Object part the state rests on (kSeatPart, kMattressPart).
  scene::Aabb part_O;           ///< That part's box in the source object's frame.
  humanoid::HumanoidPose pose;  ///< Character state in the source object's frame.
  bool success = false;         ///< The episode had succeeded (else it timed out).
};

/// The anchor A of a part box (see the file comment) for part name `part`.
Eigen::Vector3d HandoffAnchor(const std::string& part, const scene::Aabb& part_O);

/// The state of world pose `pose_W` on object g's part `part` (g must have that part).
HandoffState MakeHandoffState(const std::string& skill, const std::string& part,
                              const ObjectGeometry& g, const humanoid::HumanoidPose& pose_W,
                              bool success);

/// Places state s on object g (world frame), or nullopt when g has no part s.part, its top
/// differs by more than `max_height_diff` m, or its depth (x extent) by more than
/// `max_depth_diff` m, or the placed pelvis leaves the part's footprint (0.05 m margin) when it
/// was over the source part.
std::optional<humanoid::HumanoidPose> PlaceHandoffState(const HandoffState& s,
                                                        const ObjectGeometry& g,
                                                        double max_height_diff = 0.05,
                                                        double max_depth_diff = 0.1);

/// Writes states as {"format": "sims-handoff-states", "version": 1, "states": [...]}
/// (atomically).
void SaveHandoffStates(const std::vector<HandoffState>& states, const std::filesystem::path& path);

/// Reads a file written by SaveHandoffStates; throws sims::Error naming the file and field.
std::vector<HandoffState> LoadHandoffStates(const std::filesystem::path& path);

/// The states of all `files` in order (a relative path missing from the working directory is
/// the project root's), read once per process per list and shared read-only by every skill
/// instance (each story of a batch builds its own).
std::shared_ptr<const std::vector<HandoffState>> SharedHandoffStates(
    const std::vector<std::string>& files);

}  // namespace sims::task
