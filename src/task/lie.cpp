#include "sims/task/lie.h"

#include <limits>

#include "sims/sim/features.h"

namespace sims::task {

LieSkill::LieSkill(const SkillConfig& config, const SkillContext& context)
    : ObjectSkill(config, context) {
  reference_clips_.clear();
  if (context.motions) reference_clips_ = context.motions->Find("lie");
  CollectObjects("bed (an object with a 'mattress' part)");
}

double LieSkill::UpdateGoals(int i, const sim::BodyStates& b, double* max_distance) {
  const ObjectGeometry& g = geometry(i);
  const scene::Scene& s = *context_.scene;
  ClearGoals(i);
  const Eigen::Vector3d x = sim::ContactJointPosition(b, sim::kCjPelvis);
  const Eigen::Vector3d m = NearestOnPart(s, g.object, g.mattress, x);
  SetGoal(i, sim::kCjPelvis, m);
  double sum = (m - x).squaredNorm();
  double worst = (m - x).norm();
  if (!g.pillows.empty()) {
    const Eigen::Vector3d h = sim::ContactJointPosition(b, sim::kCjHead);
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int p : g.pillows) {
      const Eigen::Vector3d q = NearestOnPart(s, g.object, p, h);
      if ((q - h).squaredNorm() < best_d2) best_d2 = (q - h).squaredNorm(), best = q;
    }
    SetGoal(i, sim::kCjHead, best);
    sum += best_d2;
    worst = std::max(worst, std::sqrt(best_d2));
  }
  *max_distance = worst;
  return sum;
}

void LieSkill::OnReset(const sim::EnvView& view, Rng&) {
  double d = 0;
  UpdateGoals(view.env_id, *view.bodies, &d);
  error_[view.env_id] = d;
}

sim::TaskStepResult LieSkill::Step(const sim::EnvView& view) {
  double d = 0;
  const double sum = UpdateGoals(view.env_id, *view.bodies, &d);
  return ContactRewardStep(view, geometry(view.env_id).mattress_local.center(), sum, d);
}

bool LieSkill::ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) {
  return FurnitureClipInit(env_id, rng, init);
}

SkillInfo LieSkillInfo() {
  SkillInfo info;
  info.name = "lie";
  info.description = "lie down on a bed with the head on a pillow";
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    return BuildTrainingGround(c, rng, {"bed"});
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<LieSkill>(c, ctx);
  };
  return info;
}

}  // namespace sims::task
