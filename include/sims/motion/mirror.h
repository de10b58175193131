// Left–right mirroring about the humanoid's x–z plane (y → −y), used to double the motion
// data: left and right bodies swap, 3-DoF joints negate their x and z hinges and keep y,
// 1-DoF joints are unchanged, the root quaternion (w, x, y, z) becomes (w, −x, y, −z), and
// captions swap "left"/"right".
#pragma once

#include <string>

#include "sims/motion/motion_clip.h"

namespace sims::motion {

/// DoF index of the mirror partner of DoF i (itself for abdomen and neck).
int MirrorDof(int i);

/// Sign applied to DoF i when mirrored (−1 for x and z hinges of 3-DoF joints, else +1).
double MirrorDofSign(int i);

/// The mirrored frame.
MotionFrame MirrorFrame(const MotionFrame& f);

/// The mirrored pose (velocities included).
humanoid::HumanoidPose MirrorPose(const humanoid::HumanoidPose& p);

/// Swaps left/right words (left ↔ right, leftward ↔ rightward, clockwise ↔ counterclockwise),
/// keeping capitalisation.
std::string MirrorText(const std::string& text);

/// The mirrored clip: frames, captions, style and name ("_mirror" appended or removed),
/// params named *_y or *_yaw negated, `mirrored` toggled.
MotionClip MirrorClip(const MotionClip& clip);

}  // namespace sims::motion
