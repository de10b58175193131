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
  const int i = view.env_id;
  const ObjectGeometry& g = geometry(i);
  double d = 0;
  const double sum = UpdateGoals(i, *view.bodies, &d);
  error_[i] = d;
  const Eigen::Vector2d anchor = g.ToWorld(g.seat_local.center()).head<2>();
  const double r =
      ContactReward(anchor, view.pose->root_pos.head<2>(), view.pose->root_lin_vel.head<2>(),
                    FacingOf(*view.pose), config_.target_speed, sum);
  return Finish(view, r, d < config_.contact_success_threshold);
}

bool SitSkill::ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) {
  ClipPlacement placement;
  const int clip = ChooseFurnitureClip(reference_clips_, geometry(env_id), rng, &placement);
  if (clip < 0) return false;
  const double t = context_.motions->SampleTime(clip, rng, config_.reference_init_max_fraction);
  PlaceReference(env_id, clip, t, placement, init);
  return true;
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
