#include "sims/task/surface_skill.h"

#include <cmath>
#include <limits>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/humanoid/features.h"

namespace sims::task {

SurfaceSkill::SurfaceSkill(const SkillConfig& config, const SkillContext& context, SurfaceTask task)
    : ObjectSkill(config, context), task_(std::move(task)) {
  SIMS_CHECK(task_.target_local && task_.anchor_local);
  const double near_shares =
      task_.wide_near_share + config_.object.wide_near_share + config_.object.precise_near_share;
  Require(near_shares <= 1, "precise_near_share",
          fmt::format("a share ≤ {} − wide_near_share (the {} skill's own wide near share is {})",
                      1 - task_.wide_near_share, config_.skill, task_.wide_near_share));
  lateral_.assign(context.num_envs, 0.0);
  reference_clips_.clear();
  if (context.motions) reference_clips_ = context.motions->Find(task_.clip_skill);
  PrepareReferenceClips();
  CollectObjects(task_.what);
  // The extra joint's candidate parts depend only on the object and the config.
  for (const ObjectGeometry& g : objects_)
    extra_parts_.push_back(task_.extra_parts ? task_.extra_parts(g, config_) : std::vector<int>{});
}

std::string SurfaceSkill::support_part(const ObjectGeometry& g) const {
  if (g.part(task_.pelvis_part)) return task_.pelvis_part;
  const ObjectPart* f =
      task_.fallback_pelvis_part.empty() ? nullptr : g.part(task_.fallback_pelvis_part);
  if (!f || f->local.max.y() - f->local.min.y() < task_.fallback_min_width) return "";
  return task_.fallback_pelvis_part;
}

double SurfaceSkill::ClipContactTime(int clip) const {
  // The clips end on the furniture: contact begins once the pelvis is within the success
  // distance (with margin) of where it ends.
  const motion::MotionClip& c = context_.motions->clip(clip);
  const Eigen::Vector3d end = c.FramePose(c.num_frames() - 1).root_pos;
  const double reach = kPreContactMargin * config_.object.contact_success_threshold;
  for (int f = 0; f < c.num_frames(); ++f)
    if ((c.FramePose(f).root_pos - end).norm() < reach) return f / c.fps();
  return c.duration();
}

void SurfaceSkill::SampleTask(int i, Rng& rng) {
  const ObjectGeometry& g = geometry(i);
  lateral_[i] = task_.lateral ? task_.lateral(g, rng) : 0.0;
  SetEpisodeTarget(i, g.ToWorld(task_.target_local(g, lateral_[i], config_)),
                   g.ToWorld(task_.anchor_local(g, lateral_[i])).head<2>());
}

double SurfaceSkill::UpdateGoals(int i, const humanoid::BodyStates& b, double* success_distance,
                                 double* contact_error) {
  const ObjectGeometry& g = geometry(i);
  const scene::Scene& s = *context_.scene;
  ClearGoals(i);
  const Eigen::Vector3d x = humanoid::ContactJointPosition(b, humanoid::kCjPelvis);
  const Eigen::Vector3d& m = target(i);
  SetGoal(i, humanoid::kCjPelvis, m);
  double sum = (m - x).squaredNorm();
  double worst = (m - x).norm();
  *contact_error = worst;
  const std::vector<int>& parts = extra_parts_[object(i)];
  if (!parts.empty()) {
    const Eigen::Vector3d h = humanoid::ContactJointPosition(b, task_.extra_joint);
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int p : parts) {
      const Eigen::Vector3d q = NearestOnPart(s, g.object, p, h);
      if ((q - h).squaredNorm() < best_d2) best_d2 = (q - h).squaredNorm(), best = q;
    }
    SetGoal(i, task_.extra_joint, best);
    sum += best_d2;
    if (task_.extra_in_success) {
      worst = std::max(worst, std::sqrt(best_d2));
      *contact_error = 0.5 * (*contact_error + std::sqrt(best_d2));
    }
  }
  *success_distance = worst;
  return sum;
}

void SurfaceSkill::OnReset(const sim::EnvView& view, Rng&) {
  double d = 0;
  UpdateGoals(view.env_id, *view.bodies, &d, &env_[view.env_id].error);
}

sim::TaskStepResult SurfaceSkill::Step(const sim::EnvView& view) {
  double d = 0;
  const double sum = UpdateGoals(view.env_id, *view.bodies, &d, &env_[view.env_id].error);
  return ContactRewardStep(view, sum, d, task_.wide_near_share);
}

bool SurfaceSkill::ReferenceInit(int env_id, Rng& rng, sim::InitialState* init) {
  return FurnitureClipInit(env_id, lateral_[env_id], rng, init);
}

void SurfaceSkill::SerializeTaskState(int env_id, StateArchive* a) {
  a->Real("lateral", &lateral_[env_id]);
}

}  // namespace sims::task
