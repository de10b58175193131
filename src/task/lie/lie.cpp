#include "sims/task/lie/lie.h"

#include "sims/humanoid/features.h"

namespace sims::task {

namespace {
// Height of the lying pelvis above the mattress top in the lie clips (m).
constexpr double kLyingPelvisHeight = 0.11;

SurfaceTask LieTask() {
  SurfaceTask t;
  t.clip_skill = "lie";
  t.what = "bed (an object with a 'mattress' part)";
  t.pelvis_part = kMattressPart;
  // The side of the bed the character lies down from (the clips come in mirrored pairs).
  t.lateral = [](const ObjectGeometry&, Rng& rng) { return rng.Bernoulli(0.5) ? 1.0 : -1.0; };
  // The mattress centre, the lying pelvis height (the lie clips: 0.11 m) above its top.
  t.target_local = [](const ObjectGeometry& g, double, const SkillConfig&) {
    const scene::Aabb& mattress = g.part_local(kMattressPart);
    const Eigen::Vector3d mid = mattress.center();
    return Eigen::Vector3d(mid.x(), mid.y(), mattress.max.z() + kLyingPelvisHeight);
  };
  // A stand point beside the bed's long side (a procedural bed's long axis is its x).
  t.anchor_local = [](const ObjectGeometry& g, double side) {
    const double y = side > 0 ? g.local.max.y() + kStandDistance : g.local.min.y() - kStandDistance;
    return Eigen::Vector3d(g.part_local(kMattressPart).center().x(), y, 0.0);
  };
  t.extra_joint = humanoid::kCjHead;
  t.extra_parts = [](const ObjectGeometry& g, const SkillConfig&) {
    return g.part_indices("pillow");
  };
  t.extra_in_success = true;  // lying means the head is on the pillow too
  // Seated on the bed's edge (where the lie clips sit first, and where the sit-initialised
  // policy stayed: 0/100 after 1950 iterations) Σ is ~1.4 m² and exp(−10·Σ) ~1e-6.
  t.wide_near_share = 0.5;
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
