// Shared fixtures of the io tests: a short synthetic walk recorded with two keyframes and a
// one-chair scene.
#pragma once

#include <string>

#include "sims/io/motion_record.h"
#include "sims/motion/synthetic.h"
#include "sims/scene/builtin.h"

namespace sims::io::testing {

/// A synthetic walk of `seconds` (turning left) recorded at 30 fps, split into two keyframes:
/// "walk" (success) and "sit" (failed).
inline MotionRecord TestRecord(double seconds = 1.0) {
  motion::WalkSpec spec;
  spec.duration = seconds + 0.1;
  spec.keys = {{0.0, 1.0, 0.4}};
  motion::MotionMeta meta;
  meta.name = "test_walk";
  meta.skill = "walk";
  const motion::MotionClip clip = motion::GenerateWalk(spec, meta, 30.0);
  MotionRecordBuilder b;
  b.SetTitle("a test walk");
  b.SetScene({"chair", "chair"});
  const int n = static_cast<int>(seconds * 30) + 1;
  KeyframeAnnotation walk;
  walk.index = 0;
  walk.skill = "walk";
  walk.caption = "walks towards the chair";
  walk.emotion = "happy";
  walk.furniture = "floor";
  b.BeginKeyframe(walk);
  for (int i = 0; i < n / 2; ++i) b.AddFrame(clip.SamplePose(i / 30.0));
  b.EndKeyframe(true);
  KeyframeAnnotation sit = walk;
  sit.index = 1;
  sit.skill = "sit";
  sit.caption = "sits down slowly on the chair";
  sit.emotion = "tired";
  sit.furniture = "chair_0";
  b.BeginKeyframe(sit);
  for (int i = n / 2; i < n; ++i) b.AddFrame(clip.SamplePose(i / 30.0));
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
