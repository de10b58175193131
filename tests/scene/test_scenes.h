// Small analytic scenes shared by the scene tests.
#pragma once

#include "sims/scene/scene.h"

namespace sims::scene::testing {

/// A scene with one box object spanning [lo, hi].
inline Scene BoxScene(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                      const std::string& category = "box") {
  Scene s;
  s.name = "box";
  Object o;
  o.category = category;
  o.instance = category + "_0";
  Part p;
  p.name = "body";
  p.mesh = TriangleMesh::Box(lo, hi);
  o.parts.push_back(p);
  s.AddObject(o);
  return s;
}

}  // namespace sims::scene::testing
