#include "sims/task/lie/lie.h"

#include <algorithm>

#include "sims/humanoid/features.h"

namespace sims::task {

namespace {
// Height of the lying pelvis above the mattress top in the lie clips (m).
constexpr double kLyingPelvisHeight = 0.11;
// A seat this wide (m) is a sofa to lie on: a default sofa's seat is 1.68 m between its arms,
// an armchair's 0.55 m.
constexpr double kSofaMinWidth = 1.2;
// Lying, the head contact point is this far from the pelvis's along the body (the lie clips'
// end pose: 0.61 m).
constexpr double kLyingHeadReach = 0.61;
// Where the head comes to rest short of a sofa arm's inner face (about the head's radius).
constexpr double kHeadToArm = 0.1;

// The surface lain on: a bed's mattress, else a sofa's seat.
const scene::Aabb& LyingSurface(const ObjectGeometry& g) {
  const ObjectPart* mattress = g.part(kMattressPart);
  return mattress ? mattress->local : g.part_local(kSeatPart);
}

SurfaceTask LieTask() {
  SurfaceTask t;
  t.clip_skill = "lie";
  t.what = "bed or sofa (a 'mattress' part, or a 'seat surface' at least 1.2 m wide)";
  t.pelvis_part = kMattressPart;
  // Stories say "lies down on the sofa" (31 of 88 lie keyframes over eval_story's 90 stories
  // named a sofa, and scenes without a bed could not run lie at all).
  t.fallback_pelvis_part = kSeatPart;
  t.fallback_min_width = kSofaMinWidth;
  // The side of the bed the character lies down from (the clips come in mirrored pairs).
  t.lateral = [](const ObjectGeometry&, Rng& rng) { return rng.Bernoulli(0.5) ? 1.0 : -1.0; };
  // The surface centre, the lying pelvis height (the lie clips: 0.11 m) above its top. On a
  // sofa the head must reach an arm: the pelvis moves toward the episode's side so that a
  // lying head (kLyingHeadReach ahead) comes within kHeadToArm of it; from the centre the head
  // stayed 0.33 m from the arms of the wider sofas, beyond the success distance.
  t.target_local = [](const ObjectGeometry& g, double side, const SkillConfig&) {
    const scene::Aabb& surface = LyingSurface(g);
    const Eigen::Vector3d mid = surface.center();
    double y = mid.y();
    if (!g.part(kMattressPart)) {
      const double half = 0.5 * (surface.max.y() - surface.min.y());
      y += (side < 0 ? -1.0 : 1.0) * std::max(0.0, half - kLyingHeadReach - kHeadToArm);
    }
    return Eigen::Vector3d(mid.x(), y, surface.max.z() + kLyingPelvisHeight);
  };
  // A stand point beside the bed's long side (a procedural bed's long axis is its x), or in
  // front of the sofa (its long axis is y, its front +x).
  t.anchor_local = [](const ObjectGeometry& g, double side) {
    if (!g.part(kMattressPart))
      return Eigen::Vector3d(g.local.max.x() + kStandDistance, LyingSurface(g).center().y(), 0.0);
    const double y = side > 0 ? g.local.max.y() + kStandDistance : g.local.min.y() - kStandDistance;
    return Eigen::Vector3d(g.part_local(kMattressPart).center().x(), y, 0.0);
  };
  t.extra_joint = humanoid::kCjHead;
  // The head on a pillow, on a sofa on either arm.
  t.extra_parts = [](const ObjectGeometry& g, const SkillConfig&) {
    if (g.part(kMattressPart)) return g.part_indices("pillow");
    std::vector<int> arms = g.part_indices("left arm");
    for (int k : g.part_indices("right arm")) arms.push_back(k);
    return arms;
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
  // Beds unless the config's object_categories say otherwise (e.g. ["bed", "sofa"]).
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    return BuildTrainingGround(c, rng, {"bed"});
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<LieSkill>(c, ctx);
  };
  return info;
}

}  // namespace sims::task
