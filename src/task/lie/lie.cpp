#include "sims/task/lie/lie.h"

#include "sims/sim/features.h"

namespace sims::task {

namespace {
SurfaceTask LieTask() {
  SurfaceTask t;
  t.clip_skill = "lie";
  t.what = "bed (an object with a 'mattress' part)";
  t.pelvis_part = &ObjectGeometry::mattress;
  t.pelvis_bounds = &ObjectGeometry::mattress_local;
  t.extra_joint = sim::kCjHead;
  t.extra_parts = [](const ObjectGeometry& g, const SkillConfig&) { return g.pillows; };
  t.extra_in_success = true;  // lying means the head is on the pillow too
  return t;
}
}  // namespace

LieSkill::LieSkill(const SkillConfig& config, const SkillContext& context)
    : SurfaceSkill(config, context, LieTask()) {}

// The registry entry: vocabulary traits (core/skill_vocabulary.cpp), params, scene, factory.
SkillInfo LieSkillInfo() {
  SkillInfo info = BuiltinSkillInfo("lie");
  info.params = ConfigToJson(ObjectParams{});
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    return BuildTrainingGround(c, rng, {"bed"});
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<LieSkill>(c, ctx);
  };
  return info;
}

}  // namespace sims::task
