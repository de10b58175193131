#include "sims/task/surface_skill.h"

#include <cmath>
#include <limits>

#include "sims/sim/features.h"

namespace sims::task {

SurfaceSkill::SurfaceSkill(const SkillConfig& config, const SkillContext& context, SurfaceTask task)
    : ObjectSkill(config, context), task_(std::move(task)) {
  reference_clips_.clear();
  if (context.motions) reference_clips_ = context.motions->Find(task_.clip_skill);
  CollectObjects(task_.what);
  // The extra joint's candidate parts depend only on the object and the config.
  for (const ObjectGeometry& g : objects_)
    extra_parts_.push_back(task_.extra_parts ? task_.extra_parts(g, config_) : std::vector<int>{});
}

Eigen::Vector3d SurfaceSkill::PelvisTarget(int env_id, const Eigen::Vector3d& pelvis) const {
  const ObjectGeometry& g = geometry(env_id);
  return NearestOnPart(*context_.scene, g.object, g.*task_.pelvis_part, pelvis);
}

double SurfaceSkill::UpdateGoals(int i, const sim::BodyStates& b, double* success_distance) {
  const ObjectGeometry& g = geometry(i);
  const scene::Scene& s = *context_.scene;
  ClearGoals(i);
  const Eigen::Vector3d x = sim::ContactJointPosition(b, sim::kCjPelvis);
  const Eigen::Vector3d m = PelvisTarget(i, x);
  SetGoal(i, sim::kCjPelvis, m);
  double sum = (m - x).squaredNorm();
  double worst = (m - x).norm();
  const std::vector<int>& parts = extra_parts_[object(i)];
  if (!parts.empty()) {
    const Eigen::Vector3d h = sim::ContactJointPosition(b, task_.extra_joint);
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int p : parts) {
      const Eigen::Vector3d q = NearestOnPart(s, g.object, p, h);
      if ((q - h).squaredNorm() < best_d2) best_d2 = (q - h).squaredNorm(), best = q;
    }
    SetGoal(i, task_.extra_joint, best);
    sum += best_d2;
    if (task_.extra_in_success) worst = std::max(worst, std::sqrt(best_d2));
  }
  *success_distance = worst;
  return sum;
}

void SurfaceSkill::OnReset(const sim::EnvView& view, Rng&) {
  double d = 0;
  UpdateGoals(view.env_id, *view.bodies, &d);
  error_[view.env_id] = d;
}

sim::TaskStepResult SurfaceSkill::Step(const sim::EnvView& view) {
  double d = 0;
  const double sum = UpdateGoals(view.env_id, *view.bodies, &d);
  const scene::Aabb& part = geometry(view.env_id).*task_.pelvis_bounds;
  return ContactRewardStep(view, part.center(), sum, d);
}

bool SurfaceSkill::ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) {
  return FurnitureClipInit(env_id, rng, init);
}

}  // namespace sims::task
