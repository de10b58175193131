#include "sims/task/unified/unified.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sims/core/error.h"
#include "sims/scene/contact_targets.h"
#include "sims/sim/features.h"

namespace sims::task {

namespace {

ContactPairSpec PartPair(int joint, ContactType type, int object, int part,
                         const Eigen::Vector3d& dir = Eigen::Vector3d::Zero()) {
  ContactPairSpec p;
  p.joint = joint;
  p.type = type;
  p.object = object;
  p.part = part;
  p.direction = dir;
  return p;
}

ContactPairSpec JointPairSpec(int joint, int other) {
  ContactPairSpec p;
  p.joint = joint;
  p.type = ContactType::kContact;
  p.target_joint = other;
  return p;
}

Eigen::Vector3d StandAt(const ObjectGeometry& g, int k) {
  if (g.stand_points.empty()) {
    const Eigen::Vector3d p =
        g.ToWorld(Eigen::Vector3d(g.local.max.x() + 0.45, g.local.center().y(), 0));
    return {p.x(), p.y(), sim::kDefaultRootHeight};
  }
  const Eigen::Vector3d& p = g.stand_points[k % g.stand_points.size()];
  return {p.x(), p.y(), sim::kDefaultRootHeight};
}

}  // namespace

std::vector<std::string> UnifiedCategories() {
  return {"chair", "armchair", "sofa", "stool", "bed", "table", "shelf"};
}

UnifiedSkill::UnifiedSkill(const SkillConfig& config, const SkillContext& context)
    : ObjectSkill(config, context) {
  const int n = context.num_envs;
  steps_.assign(n, {});
  step_.assign(n, 0);
  still_.assign(n, 0);
  completed_.assign(n, 0);
  CollectObjects("object");
}

int UnifiedSkill::obs_dim() const { return Skill::obs_dim() + kContactPairObsDim; }

std::vector<sim::ObsSegment> UnifiedSkill::obs_segments() const {
  auto segs = Skill::obs_segments();
  sim::ObsSegment s;
  s.name = "contact_pairs";
  s.kind = sim::ObsSegment::Kind::kVector;
  s.offset = Skill::obs_dim();
  s.size = kContactPairObsDim;
  segs.push_back(s);
  return segs;
}

void UnifiedSkill::Observe(const sim::EnvView& view, float* out) const {
  Skill::Observe(view, out);
  float* o = out + Skill::obs_dim();
  std::fill(o, o + kContactPairObsDim, 0.0f);
  const int i = view.env_id;
  if (steps_[i].empty()) return;
  const Eigen::Quaterniond h_inv = sim::HeadingInverse(view.bodies->rot[sim::kPelvis]);
  for (const auto& p : steps_[i][step_[i]].pairs) {
    if (p.type == ContactType::kNone) continue;
    o[p.joint] = p.type == ContactType::kContact ? 1.0f : -1.0f;
    const Eigen::Vector3d d = h_inv * p.direction;
    for (int k = 0; k < 3; ++k)
      o[sim::kNumContactJoints + 3 * p.joint + k] = static_cast<float>(d[k]);
  }
}

std::vector<ContactStep> UnifiedSkill::Templates(int k) const {
  const ObjectGeometry& g = objects_[k];
  const scene::Object& o = context_.scene->objects[g.object];
  const Eigen::Vector3d up(0, 0, 1);
  const Eigen::Vector3d front = g.X_WO.linear() * Eigen::Vector3d::UnitX();
  const ContactType C = ContactType::kContact, N = ContactType::kNotContact;
  std::vector<ContactStep> t;
  auto add = [&](const std::string& label, std::vector<ContactPairSpec> pairs) {
    ContactStep s;
    s.pairs = std::move(pairs);
    s.object = g.object;
    s.stand_point = StandAt(g, 0);
    s.label = label;
    t.push_back(std::move(s));
  };
  using namespace sim;
  if (g.seat >= 0) {
    const ContactPairSpec sit = PartPair(kCjPelvis, C, g.object, g.seat, up);
    add("sit", {sit});
    if (g.back >= 0) {
      add("sit, lean back", {sit, PartPair(kCjTorso, C, g.object, g.back, front)});
      add("sit upright", {sit, PartPair(kCjTorso, N, g.object, g.back)});
    }
    if (g.left_arm >= 0 && g.right_arm >= 0)
      add("sit, hands on the arm rests", {sit, PartPair(kCjLeftHand, C, g.object, g.left_arm, up),
                                          PartPair(kCjRightHand, C, g.object, g.right_arm, up)});
    add("sit, hands on the knees",
        {sit, JointPairSpec(kCjLeftHand, kCjLeftKnee), JointPairSpec(kCjRightHand, kCjRightKnee)});
  }
  if (g.mattress >= 0) {
    const ContactPairSpec on_bed = PartPair(kCjPelvis, C, g.object, g.mattress, up);
    add("sit on the bed", {on_bed});
    if (!g.pillows.empty())
      add("lie on the bed", {on_bed, PartPair(kCjHead, C, g.object, g.pillows[0], up)});
  }
  for (size_t p = 0; p < o.parts.size(); ++p) {
    const std::string& n = o.parts[p].name;
    if (n != "top" && n != "board" && n != "door") continue;
    const double top = o.parts[p].mesh.Bounds().max.z();
    if (top < 0.3 || top > 2.0) continue;
    add("touch the " + n + " with the left hand",
        {PartPair(kCjLeftHand, C, g.object, static_cast<int>(p))});
    add("touch the " + n + " with the right hand",
        {PartPair(kCjRightHand, C, g.object, static_cast<int>(p))});
  }
  return t;
}

std::vector<ContactStep> UnifiedSkill::RandomChain(int k, Rng& rng) const {
  const ObjectGeometry& g = objects_[k];
  const std::vector<ContactStep> templates = Templates(k);
  std::vector<ContactStep> chain;
  if (templates.empty() || rng.Bernoulli(0.5)) {
    ContactStep walk;
    walk.object = g.object;
    const int n = std::max<int>(1, static_cast<int>(g.stand_points.size()));
    walk.stand_point = StandAt(g, static_cast<int>(rng.UniformInt(n)));
    walk.label = "walk";
    chain.push_back(walk);
  }
  if (templates.empty()) return chain;
  const int n = static_cast<int>(templates.size());
  const int first = static_cast<int>(rng.UniformInt(n));
  chain.push_back(templates[first]);
  if (n > 1 && rng.Bernoulli(0.5)) {
    const int second = (first + 1 + static_cast<int>(rng.UniformInt(n - 1))) % n;
    chain.push_back(templates[second]);
  }
  return chain;
}

void UnifiedSkill::SetPlan(const std::vector<ContactStep>& steps) {
  for (const auto& s : steps)
    SIMS_CHECK(s.object >= 0 && s.object < static_cast<int>(context_.scene->objects.size()));
  plan_ = steps;
}

void UnifiedSkill::SampleTask(int i, Rng& rng) {
  step_[i] = still_[i] = completed_[i] = 0;
  if (plan_.empty()) {
    steps_[i] = RandomChain(object_[i], rng);
    return;
  }
  steps_[i] = plan_;
  if (const int k = SlotOf(plan_.front().object); k >= 0) object_[i] = k;
}

void UnifiedSkill::UpdateGoals(int i, const std::array<JointPair, sim::kNumContactJoints>& pairs) {
  ClearGoals(i);
  const ContactStep& st = steps_[i][step_[i]];
  if (st.walking()) {
    SetGoal(i, sim::kCjPelvis, st.stand_point);
    return;
  }
  for (int j = 0; j < sim::kNumContactJoints; ++j)
    if (pairs[j].type != ContactType::kNone) SetGoal(i, j, pairs[j].target);
}

namespace {
double StepContactError(const ContactStep& st,
                        const std::array<JointPair, sim::kNumContactJoints>& pairs,
                        const sim::BodyStates& b) {
  if (st.walking()) return (st.stand_point - sim::ContactJointPosition(b, sim::kCjPelvis)).norm();
  double sum = 0;
  int n = 0;
  for (const auto& p : pairs) {
    if (p.type == ContactType::kNone) continue;
    sum += PairContactError(p.type, (p.target - p.joint).norm());
    ++n;
  }
  return n ? sum / n : 0.0;
}
}  // namespace

bool UnifiedSkill::BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) {
  if (!target.contact_step) return ObjectSkill::BeginInstruction(view, target);
  const ContactStep& step = *target.contact_step;
  const int i = view.env_id;
  const int k = SlotOf(step.object);
  if (k < 0) return false;
  object_[i] = k;
  hold_[i] = 0;
  steps_[i] = {step};
  step_[i] = still_[i] = completed_[i] = 0;
  Rng unused(0);
  OnReset(view, unused);
  return true;
}

void UnifiedSkill::OnReset(const sim::EnvView& view, Rng&) {
  const int i = view.env_id;
  const auto pairs = ResolveStep(steps_[i][step_[i]], *context_.scene, *view.bodies);
  UpdateGoals(i, pairs);
  error_[i] = StepContactError(steps_[i][step_[i]], pairs, *view.bodies);
}

sim::TaskStepResult UnifiedSkill::Step(const sim::EnvView& view) {
  const int i = view.env_id;
  const sim::BodyStates& b = *view.bodies;
  const ContactStep& st = steps_[i][step_[i]];
  auto pairs = ResolveStep(st, *context_.scene, b);
  const StepReward sr =
      UniHsiStepReward(pairs, view.pose->root_pos, view.pose->root_lin_vel, FacingOf(*view.pose),
                       st.stand_point, config_.target_speed);
  double max_l1 = 0;
  for (const auto& v : b.lin_vel) max_l1 = std::max(max_l1, v.cwiseAbs().sum());
  still_[i] = max_l1 < kStillVelocityL1 ? still_[i] + 1 : 0;
  const bool big_force =
      config_.object.max_contact_force > 0 && ContactForce(view) > config_.object.max_contact_force;
  const StepCheck check = CheckUniHsiStep(st.types(), sr, big_force, still_[i]);
  error_[i] = StepContactError(st, pairs, b);

  sim::TaskStepResult r;
  r.reward = static_cast<float>(sr.reward);
  if (big_force) {
    r.terminate = true;
  } else if (check.advance) {
    r.success = true;
    ++completed_[i];
    if (step_[i] + 1 < static_cast<int>(steps_[i].size())) {
      ++step_[i];
      still_[i] = 0;
      pairs = ResolveStep(steps_[i][step_[i]], *context_.scene, b);
    } else {
      r.truncate = true;
      r.completed = true;  // the whole chain passed
    }
  } else if (check.triggered) {
    r.truncate = true;  // done without passing: UniHSI restarts the chain
  }
  UpdateGoals(i, pairs);
  return r;
}

void UnifiedSkill::SaveTaskState(int i, std::vector<double>* out) const {
  out->push_back(static_cast<double>(step_[i]));
  out->push_back(static_cast<double>(still_[i]));
  out->push_back(static_cast<double>(completed_[i]));
  out->push_back(static_cast<double>(steps_[i].size()));
  for (const auto& s : steps_[i]) {
    out->insert(out->end(), {static_cast<double>(s.object), s.stand_point.x(), s.stand_point.y(),
                             s.stand_point.z(), static_cast<double>(s.pairs.size())});
    for (const auto& p : s.pairs)
      out->insert(
          out->end(),
          {static_cast<double>(p.joint), static_cast<double>(static_cast<int>(p.type)),
           static_cast<double>(p.object), static_cast<double>(p.part),
           static_cast<double>(p.target_joint), p.direction.x(), p.direction.y(), p.direction.z()});
  }
}

void UnifiedSkill::LoadTaskState(int i, StateReader* r) {
  constexpr long long kMaxInt = std::numeric_limits<int>::max();
  const scene::Scene& scene = *context_.scene;
  const long long objects = static_cast<long long>(scene.objects.size());
  const auto part_of = [&](long long object) {
    const long long parts =
        object >= 0 ? static_cast<long long>(scene.objects[object].parts.size()) : 0;
    return static_cast<int>(r->Int("part", -1, parts - 1));
  };
  const long long step = r->Int("step", 0, kMaxInt);
  const long long still = r->Int("still", 0, kMaxInt);
  const long long completed = r->Int("completed", 0, kMaxInt);
  // A step takes at least 5 values: no count beyond what is left.
  const long long n = r->Int("steps", 1, static_cast<long long>(r->left() / 5));
  if (step >= n)
    ThrowInputError("unified skill state", "step", "a step of the chain", std::to_string(step));
  std::vector<ContactStep> steps(static_cast<size_t>(n));
  for (ContactStep& s : steps) {
    s.object = static_cast<int>(r->Int("object", -1, objects - 1));
    for (int c = 0; c < 3; ++c) s.stand_point[c] = r->Real("stand_point");
    // A pair takes 8 values.
    s.pairs.resize(static_cast<size_t>(r->Int("pairs", 0, static_cast<long long>(r->left() / 8))));
    for (ContactPairSpec& p : s.pairs) {
      p.joint = static_cast<int>(r->Int("joint", 0, sim::kNumContactJoints - 1));
      p.type = static_cast<ContactType>(r->Int("type", 0, 2));
      p.object = static_cast<int>(r->Int("object", -1, objects - 1));
      p.part = part_of(p.object);
      p.target_joint = static_cast<int>(r->Int("target_joint", -1, sim::kNumContactJoints - 1));
      for (int c = 0; c < 3; ++c) p.direction[c] = r->Real("direction");
    }
    s.label = s.walking() ? "walk" : "contact";
  }
  step_[i] = static_cast<int>(step);
  still_[i] = static_cast<int>(still);
  completed_[i] = static_cast<int>(completed);
  steps_[i] = std::move(steps);
}

SkillInfo UnifiedSkillInfo() {
  SkillInfo info = BuiltinSkillInfo("unified");
  info.params = ConfigToJson(ObjectParams{});
  info.build_scene = [](const SkillConfig& c, Rng& rng) {
    return BuildTrainingGround(c, rng, UnifiedCategories());
  };
  info.create = [](const SkillConfig& c, const SkillContext& ctx) -> std::shared_ptr<Skill> {
    return std::make_shared<UnifiedSkill>(c, ctx);
  };
  return info;
}

}  // namespace sims::task
