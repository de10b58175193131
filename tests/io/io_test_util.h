// Shared fixtures of the io tests: a short procedural walk recorded with two keyframes and a
// one-chair scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "sims/io/motion_record.h"
#include "sims/scene/builtin.h"

namespace sims::io::testing {

/// A simple procedural walk pose at time t: the root moves at 1 m/s along a left-turning arc
/// (0.4 rad/s), legs and arms swing at 0.9 Hz (kept here so the io tests need no motion data).
inline humanoid::HumanoidPose WalkPose(double t) {
  humanoid::HumanoidPose p;
  const double yaw = 0.4 * t, r = 1.0 / 0.4;
  p.root_pos = Eigen::Vector3d(r * std::sin(yaw), r * (1 - std::cos(yaw)),
                               0.87 + 0.02 * std::cos(4 * M_PI * 0.9 * t));
  p.root_rot = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  const double ph = 2 * M_PI * 0.9 * t;
  auto dof = [](const char* joint, int axis) {
    for (const auto& j : humanoid::Joints())
      if (std::string(j.name) == joint) return j.dof_offset + axis;
    return -1;
  };
  p.dof_pos[dof("right_hip", 1)] = -0.45 * std::sin(ph);
  p.dof_pos[dof("left_hip", 1)] = 0.45 * std::sin(ph);
  p.dof_pos[dof("right_knee", 0)] = 0.1 + 0.6 * std::max(0.0, std::sin(ph + M_PI / 2));
  p.dof_pos[dof("left_knee", 0)] = 0.1 + 0.6 * std::max(0.0, std::sin(ph - M_PI / 2));
  p.dof_pos[dof("right_shoulder", 1)] = 0.4 * std::sin(ph);
  p.dof_pos[dof("left_shoulder", 1)] = -0.4 * std::sin(ph);
  p.dof_pos[dof("right_elbow", 0)] = -0.3;
  p.dof_pos[dof("left_elbow", 0)] = -0.3;
  return p;
}

/// The walk of `seconds` recorded at 30 fps, split into two keyframes: "walk" (success) and
/// "sit" (failed, "timed out").
inline MotionRecord TestRecord(double seconds = 1.0) {
  MotionRecordBuilder b;
  b.SetTitle("a test walk");
  b.SetScene({"chair", "chair"});
  const int n = static_cast<int>(std::lround(seconds * 30)) + 1;
  KeyframeAnnotation walk;
  walk.index = 0;
  walk.skill = "walk";
  walk.caption = "walks towards the chair";
  walk.emotion = "happy";
  walk.furniture = "floor";
  b.BeginKeyframe(walk);
  for (int i = 0; i < n / 2; ++i) b.AddFrame(WalkPose(i / 30.0));
  b.EndKeyframe(true);
  KeyframeAnnotation sit = walk;
  sit.index = 1;
  sit.skill = "sit";
  sit.caption = "sits down slowly on the chair";
  sit.emotion = "tired";
  sit.furniture = "chair_0";
  b.BeginKeyframe(sit);
  for (int i = n / 2; i < n; ++i) b.AddFrame(WalkPose(i / 30.0));
  b.EndKeyframe(false, "timed out");
  return b.Finish();
}

/// One default chair placed 2 m in front of the start.
inline scene::Scene TestScene() {
  scene::Scene s;
  s.name = "chair";
  scene::Object chair =
      scene::MakeFurniture("chair", scene::DefaultFurnitureParams("chair"), "chair_0");
  scene::PlaceObject(&chair, 2.0, 0.5, M_PI);
  s.AddObject(std::move(chair));
  return s;
}

}  // namespace sims::io::testing
