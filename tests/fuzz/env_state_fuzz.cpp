// Environment snapshots (the "env_state" of a training checkpoint) → BatchedEnv::LoadState, for
// the plain humanoid and the built-in skills. The first input byte picks the environment, the
// second how the input becomes a snapshot: as is, or as a patch (4-byte offset, then bytes
// written over a valid snapshot there) or a cut of a valid snapshot, so the fuzzer reaches the
// fields past the header checks. A load that fails must leave the environment as it was; one
// that succeeds must give an environment that steps.
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_util.h"
#include "sims/core/error.h"
#include "sims/humanoid/model_builder.h"
#include "sims/motion/synthetic.h"
#include "sims/sim/env.h"
#include "sims/task/skill.h"

namespace {

struct Target {
  sims::task::SkillSetup setup;  // empty for the plain humanoid
  std::unique_ptr<sims::sim::BatchedEnv> env;
  std::string valid;  // a snapshot taken after a few steps
};

std::vector<Target>& Targets() {
  static std::vector<Target> targets = [] {
    using sims::task::SkillConfig;
    sims::motion::SyntheticOptions o;
    o.variants = 1;
    o.skills = {"walk", "sit", "lie", "reach", "getup"};
    const std::string manifest =
        sims::motion::WriteMotionDataset(sims::motion::GenerateSyntheticClips(o),
                                         sims::fuzz::ScratchDir() / "clips", "fuzz clips")
            .string();
    const auto skill = [&](const std::string& name, std::vector<std::string> categories) {
      SkillConfig c;
      c.skill = name;
      c.object.num_objects = static_cast<int>(categories.size());
      c.object.object_categories = std::move(categories);
      c.motion.manifest = manifest;
      c.motion.skills = {name};
      c.reference_init_prob = 0.5;
      return c;
    };
    SkillConfig walk;
    walk.motion.manifest = manifest;
    walk.motion.skills = {"walk"};
    const std::vector<SkillConfig> configs = {
        walk, skill("sit", {"chair", "sofa"}), skill("lie", {"bed"}),
        skill("reach", {"shelf", "table"}), skill("getup", {"chair", "bed"})};
    std::vector<Target> out;
    sims::sim::EnvConfig ec;
    ec.num_envs = 2;
    ec.threads = 1;
    ec.seed = 5;
    {
      Target t;
      t.env = std::make_unique<sims::sim::BatchedEnv>(
          std::make_shared<const sims::humanoid::Humanoid>(sims::humanoid::BuildModel()), ec);
      out.push_back(std::move(t));
    }
    for (const SkillConfig& c : configs) {
      Target t;
      t.setup = sims::task::CreateSkill(c, ec.num_envs, 3);
      t.env = std::make_unique<sims::sim::BatchedEnv>(t.setup.context.humanoid, ec, t.setup.skill);
      out.push_back(std::move(t));
    }
    for (Target& t : out) {
      t.env->Reset();
      const std::vector<float> zero(static_cast<size_t>(ec.num_envs) * t.env->action_dim(), 0.f);
      for (int k = 0; k < 3; ++k) t.env->Step(zero.data());
      t.valid = t.env->SaveState();
    }
    return out;
  }();
  return targets;
}

uint32_t ReadU32(const uint8_t* p) {
  uint32_t v = 0;
  std::memcpy(&v, p, sizeof(v));
  return v;
}

}  // namespace

// Building the skills (clips, scenes, reference windows) takes seconds under ASan: once, before
// libFuzzer's per-input timeout starts.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  Targets();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  std::vector<Target>& targets = Targets();
  Target& t = targets[data[0] % targets.size()];
  const int mode = data[1] % 3;
  data += 2, size -= 2;
  std::string snapshot;
  if (mode == 0) {
    snapshot.assign(reinterpret_cast<const char*>(data), size);
  } else {
    if (size < 4) return 0;
    const size_t at = ReadU32(data) % (t.valid.size() + 1);
    data += 4, size -= 4;
    snapshot = t.valid;
    if (mode == 1) {
      snapshot.replace(at, std::min(size, snapshot.size() - at),
                       reinterpret_cast<const char*>(data), size);
    } else {
      snapshot.resize(at);
    }
  }
  t.env->LoadState(t.valid);
  try {
    t.env->LoadState(snapshot);
  } catch (const sims::Error&) {
    // Nothing half-written: a rejected snapshot leaves the environment as it was.
    if (t.env->SaveState() != t.valid) __builtin_trap();
    return 0;
  }
  const std::vector<float> zero(static_cast<size_t>(t.env->num_envs()) * t.env->action_dim(), 0.f);
  t.env->Step(zero.data());
  t.env->Step(zero.data());
  return 0;
}
