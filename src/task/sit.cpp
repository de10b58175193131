#include "sims/task/sit.h"

#include "sims/core/error.h"
#include "sims/sim/features.h"

namespace sims::task {

std::vector<std::string> SeatCategories() { return {"chair", "armchair", "sofa", "stool"}; }

SitSkill::SitSkill(const SkillConfig& config, const SkillContext& context)
    : ObjectSkill(config, context) {
  reference_clips_.clear();
  if (context.motions) reference_clips_ = context.motions->Find("sit");
  CollectObjects("object with a 'seat surface' part");
}

Eigen::Vector3d SitSkill::SeatTarget(int env_id, const Eigen::Vector3d& pelvis) const {
  const ObjectGeometry& g = geometry(env_id);
  return NearestOnPart(*context_.scene, g.object, g.seat, pelvis);
}

double SitSkill::UpdateGoals(int i, const sim::BodyStates& b, double* pelvis_distance) {
  const ObjectGeometry& g = geometry(i);
  ClearGoals(i);
  const Eigen::Vector3d x = sim::ContactJointPosition(b, sim::kCjPelvis);
  const Eigen::Vector3d seat = SeatTarget(i, x);
  SetGoal(i, sim::kCjPelvis, seat);
  double sum = (seat - x).squaredNorm();
  *pelvis_distance = (seat - x).norm();
  if (config_.sit_back_contact && g.back >= 0) {
    const Eigen::Vector3d t = sim::ContactJointPosition(b, sim::kCjTorso);
    const Eigen::Vector3d back = NearestOnPart(*context_.scene, g.object, g.back, t);
    SetGoal(i, sim::kCjTorso, back);
    sum += (back - t).squaredNorm();
  }
  return sum;
}

void SitSkill::OnReset(const sim::EnvView& view, Rng&) {
  double d = 0;
  UpdateGoals(view.env_id, *view.bodies, &d);
  error_[view.env_id] = d;
}

sim::TaskStepResult SitSkill::Step(const sim::EnvView& view) {
  double d = 0;
  const double sum = UpdateGoals(view.env_id, *view.bodies, &d);
  return ContactRewardStep(view, geometry(view.env_id).seat_local.center(), sum, d);
}

bool SitSkill::ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) {
  return FurnitureClipInit(env_id, rng, init);
}

SkillInfo SitSkillInfo() {
  SkillInfo info;
  info.name = "sit";
  info.description = "sit down on a chair, armchair, sofa or stool";
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    return BuildTrainingGround(c, rng, SeatCategories());
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<SitSkill>(c, ctx);
  };
  return info;
}

}  // namespace sims::task
