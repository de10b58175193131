#include "sims/task/sit/sit.h"

#include "sims/sim/features.h"

namespace sims::task {

std::vector<std::string> SeatCategories() { return {"chair", "armchair", "sofa", "stool"}; }

namespace {
SurfaceTask SitTask() {
  SurfaceTask t;
  t.clip_skill = "sit";
  t.what = "object with a 'seat surface' part";
  t.pelvis_part = &ObjectGeometry::seat;
  t.pelvis_bounds = &ObjectGeometry::seat_local;
  t.extra_joint = sim::kCjTorso;
  // The back rest, when the config asks for it and the seat has one.
  t.extra_parts = [](const ObjectGeometry& g, const SkillConfig& c) {
    return c.sit.back_contact && g.back >= 0 ? std::vector<int>{g.back} : std::vector<int>{};
  };
  t.extra_in_success = false;  // leaning back is rewarded, not required
  return t;
}
}  // namespace

SitSkill::SitSkill(const SkillConfig& config, const SkillContext& context)
    : SurfaceSkill(config, context, SitTask()) {}

// The registry entry: vocabulary traits (core/skill_vocabulary.cpp), params, scene, factory.
SkillInfo SitSkillInfo() {
  SkillInfo info = BuiltinSkillInfo("sit");
  info.params = ConfigToJson(ObjectParams{});
  info.params.update(ConfigToJson(SitParams{}));
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    return BuildTrainingGround(c, rng, SeatCategories());
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<SitSkill>(c, ctx);
  };
  return info;
}

}  // namespace sims::task
