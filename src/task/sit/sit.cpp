#include "sims/task/sit/sit.h"

#include <algorithm>

#include "sims/humanoid/features.h"

namespace sims::task {

std::vector<std::string> SeatCategories() { return {"chair", "armchair", "sofa", "stool"}; }

namespace {
// The surface sat on: the seat, or on a bed (stories sit on beds) its mattress, whose foot end
// faces +x like a seat's front with the headboard behind like a back rest.
const scene::Aabb& SeatOf(const ObjectGeometry& g) {
  return g.part_local(g.part(kSeatPart) ? kSeatPart : kMattressPart);
}

SurfaceTask SitTask() {
  SurfaceTask t;
  t.clip_skill = "sit";
  t.what = "object with a 'seat surface' part (or a bed's mattress)";
  t.pelvis_part = kSeatPart;
  t.fallback_pelvis_part = kMattressPart;
  t.lateral = SeatLateral;
  // Where the sit clips put the pelvis: behind the seat's front edge (at most its centre) and
  // the seated pelvis height above the seat top.
  t.target_local = [](const ObjectGeometry& g, double lateral, const SkillConfig& c) {
    const scene::Aabb& seat = SeatOf(g);
    const Eigen::Vector3d mid = seat.center();
    return Eigen::Vector3d(std::max(mid.x(), seat.max.x() - c.sit.target_behind_edge),
                           mid.y() + lateral, seat.max.z() + c.sit.pelvis_height);
  };
  // A stand point in front of the seat (objects face +x).
  t.anchor_local = [](const ObjectGeometry& g, double lateral) {
    return Eigen::Vector3d(g.local.max.x() + kStandDistance, SeatOf(g).center().y() + lateral, 0.0);
  };
  t.extra_joint = humanoid::kCjTorso;
  // The back rest, when the config asks for it and the seat has one.
  t.extra_parts = [](const ObjectGeometry& g, const SkillConfig& c) {
    const int back = g.part_index("back");
    return c.sit.back_contact && back >= 0 ? std::vector<int>{back} : std::vector<int>{};
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
