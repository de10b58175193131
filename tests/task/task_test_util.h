// Helpers for the skill tests: synthetic clip manifests and env views.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/test_util.h"
#include "sims/motion/synthetic.h"
#include "sims/sim/env.h"
#include "sims/task/skill.h"

namespace sims::task::testing {

/// A manifest of the synthetic clips of `skills` (one variant each), written once per process.
inline std::string SyntheticManifest(const std::vector<std::string>& skills) {
  static std::map<std::vector<std::string>, std::string> cache;
  auto it = cache.find(skills);
  if (it != cache.end()) return it->second;
  motion::SyntheticOptions o;
  o.variants = 1;
  o.skills = skills;
  std::string tag = "clips";
  for (const auto& s : skills) tag += "_" + s;
  const auto path = motion::WriteMotionDataset(motion::GenerateSyntheticClips(o),
                                               sims::testing::TempDir(tag), "test clips");
  return cache[skills] = path.string();
}

/// The view a task hook gets for env i.
inline sim::EnvView ViewOf(sim::BatchedEnv& env, int i) { return env.View(i); }

/// A skill and its environment.
struct SkillEnv {
  SkillSetup setup;                      ///< Skill and context.
  std::unique_ptr<sim::BatchedEnv> env;  ///< Environment.
};

/// Creates skill + env with `n` envs (2 threads, fixed seeds).
inline SkillEnv MakeSkillEnv(const SkillConfig& c, int n, uint64_t seed = 1) {
  SkillEnv s;
  s.setup = CreateSkill(c, n, seed);
  sim::EnvConfig ec;
  ec.num_envs = n;
  ec.threads = 2;
  ec.seed = seed + 2;
  s.env = std::make_unique<sim::BatchedEnv>(s.setup.context.humanoid, ec, s.setup.skill);
  return s;
}

/// Default pose at xy with yaw, pelvis at height z, zero velocities.
inline humanoid::HumanoidPose PoseAt(const Eigen::Vector3d& p, double yaw = 0) {
  humanoid::HumanoidPose pose;
  pose.root_pos = p;
  pose.root_rot = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  return pose;
}

}  // namespace sims::task::testing
