#include "sims/task/unified/unified.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sims/core/error.h"
#include "sims/humanoid/features.h"
#include "sims/scene/contact_targets.h"

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
    return {p.x(), p.y(), humanoid::kDefaultRootHeight};
  }
  const Eigen::Vector3d& p = g.stand_points[k % g.stand_points.size()];
  return {p.x(), p.y(), humanoid::kDefaultRootHeight};
}

}  // namespace

std::vector<std::string> UnifiedCategories() {
  return {"chair", "armchair", "sofa", "stool", "bed", "table", "shelf"};
}

UnifiedSkill::UnifiedSkill(const SkillConfig& config, const SkillContext& context)
    : ObjectSkill(config, context) {
  const int n = context.num_envs;
  unified_.assign(n, UnifiedState{});
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
  if (unified_[i].steps.empty()) return;
  const Eigen::Quaterniond h_inv = humanoid::HeadingInverse(view.bodies->rot[humanoid::kPelvis]);
  for (const auto& p : unified_[i].steps[unified_[i].step].pairs) {
    if (p.type == ContactType::kNone) continue;
    o[p.joint] = p.type == ContactType::kContact ? 1.0f : -1.0f;
    const Eigen::Vector3d d = h_inv * p.direction;
    for (int k = 0; k < 3; ++k)
      o[humanoid::kNumContactJoints + 3 * p.joint + k] = static_cast<float>(d[k]);
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
  using namespace humanoid;
  const int seat = g.part_index(kSeatPart), back = g.part_index("back");
  const int left_arm = g.part_index("left arm"), right_arm = g.part_index("right arm");
  const int mattress = g.part_index(kMattressPart);
  const std::vector<int> pillows = g.part_indices("pillow");
  if (seat >= 0) {
    const ContactPairSpec sit = PartPair(kCjPelvis, C, g.object, seat, up);
    add("sit", {sit});
    if (back >= 0) {
      add("sit, lean back", {sit, PartPair(kCjTorso, C, g.object, back, front)});
      add("sit upright", {sit, PartPair(kCjTorso, N, g.object, back)});
    }
    if (left_arm >= 0 && right_arm >= 0)
      add("sit, hands on the arm rests", {sit, PartPair(kCjLeftHand, C, g.object, left_arm, up),
                                          PartPair(kCjRightHand, C, g.object, right_arm, up)});
    add("sit, hands on the knees",
        {sit, JointPairSpec(kCjLeftHand, kCjLeftKnee), JointPairSpec(kCjRightHand, kCjRightKnee)});
  }
  if (mattress >= 0) {
    const ContactPairSpec on_bed = PartPair(kCjPelvis, C, g.object, mattress, up);
    add("sit on the bed", {on_bed});
    if (!pillows.empty())
      add("lie on the bed", {on_bed, PartPair(kCjHead, C, g.object, pillows[0], up)});
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
  unified_[i].step = unified_[i].still = unified_[i].completed = 0;
  if (plan_.empty()) {
    unified_[i].steps = RandomChain(env_[i].object, rng);
    return;
  }
  unified_[i].steps = plan_;
  if (const int k = SlotOf(plan_.front().object); k >= 0) env_[i].object = k;
}

void UnifiedSkill::UpdateGoals(int i,
                               const std::array<JointPair, humanoid::kNumContactJoints>& pairs) {
  ClearGoals(i);
  const ContactStep& st = unified_[i].steps[unified_[i].step];
  if (st.walking()) {
    SetGoal(i, humanoid::kCjPelvis, st.stand_point);
    return;
  }
  for (int j = 0; j < humanoid::kNumContactJoints; ++j)
    if (pairs[j].type != ContactType::kNone) SetGoal(i, j, pairs[j].target);
}

namespace {
double StepContactError(const ContactStep& st,
                        const std::array<JointPair, humanoid::kNumContactJoints>& pairs,
                        const humanoid::BodyStates& b) {
  if (st.walking())
    return (st.stand_point - humanoid::ContactJointPosition(b, humanoid::kCjPelvis)).norm();
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
  env_[i].object = k;
  env_[i].hold = 0;
  unified_[i].steps = {step};
  unified_[i].step = unified_[i].still = unified_[i].completed = 0;
  Rng unused(0);
  OnReset(view, unused);
  return true;
}

void UnifiedSkill::OnReset(const sim::EnvView& view, Rng&) {
  const int i = view.env_id;
  const auto pairs =
      ResolveStep(unified_[i].steps[unified_[i].step], *context_.scene, *view.bodies);
  UpdateGoals(i, pairs);
  env_[i].error = StepContactError(unified_[i].steps[unified_[i].step], pairs, *view.bodies);
}

sim::TaskStepResult UnifiedSkill::Step(const sim::EnvView& view) {
  const int i = view.env_id;
  const humanoid::BodyStates& b = *view.bodies;
  const ContactStep& st = unified_[i].steps[unified_[i].step];
  auto pairs = ResolveStep(st, *context_.scene, b);
  const StepReward sr =
      UniHsiStepReward(pairs, view.pose->root_pos, view.pose->root_lin_vel, FacingOf(*view.pose),
                       st.stand_point, config_.target_speed);
  double max_l1 = 0;
  for (const auto& v : b.lin_vel) max_l1 = std::max(max_l1, v.cwiseAbs().sum());
  unified_[i].still = max_l1 < kStillVelocityL1 ? unified_[i].still + 1 : 0;
  const bool big_force =
      config_.object.max_contact_force > 0 && ContactForce(view) > config_.object.max_contact_force;
  const StepCheck check = CheckUniHsiStep(st.types(), sr, big_force, unified_[i].still);
  env_[i].error = StepContactError(st, pairs, b);

  sim::TaskStepResult r;
  r.reward = static_cast<float>(sr.reward);
  if (big_force) {
    r.terminate = true;
  } else if (check.advance) {
    r.success = true;
    ++unified_[i].completed;
    if (unified_[i].step + 1 < static_cast<int>(unified_[i].steps.size())) {
      ++unified_[i].step;
      unified_[i].still = 0;
      pairs = ResolveStep(unified_[i].steps[unified_[i].step], *context_.scene, b);
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

void UnifiedState::Serialize(StateArchive* a, const scene::Scene& scene) {
  constexpr long long kMaxInt = std::numeric_limits<int>::max();
  const long long objects = static_cast<long long>(scene.objects.size());
  a->Int("step", &step, 0, kMaxInt);
  a->Int("still", &still, 0, kMaxInt);
  a->Int("completed", &completed, 0, kMaxInt);
  // A step takes at least 5 values: no count beyond what is left.
  long long n = static_cast<long long>(steps.size());
  a->Int("steps", &n, 1, a->loading() ? static_cast<long long>(a->left() / 5) : kMaxInt);
  if (a->loading() && step >= n)
    ThrowInputError("unified skill state", "step", "a step of the chain", std::to_string(step));
  if (a->loading()) steps.assign(static_cast<size_t>(n), ContactStep{});
  for (ContactStep& s : steps) {
    a->Int("object", &s.object, -1, objects - 1);
    a->Reals("stand_point", &s.stand_point);
    // A pair takes 8 values.
    long long pairs = static_cast<long long>(s.pairs.size());
    a->Int("pairs", &pairs, 0, a->loading() ? static_cast<long long>(a->left() / 8) : kMaxInt);
    if (a->loading()) s.pairs.assign(static_cast<size_t>(pairs), ContactPairSpec{});
    for (ContactPairSpec& p : s.pairs) {
      a->Int("joint", &p.joint, 0, humanoid::kNumContactJoints - 1);
      int type = static_cast<int>(p.type);
      a->Int("type", &type, 0, 2);
      p.type = static_cast<ContactType>(type);
      a->Int("object", &p.object, -1, objects - 1);
      const long long parts =
          p.object >= 0 ? static_cast<long long>(scene.objects[p.object].parts.size()) : 0;
      a->Int("part", &p.part, -1, parts - 1);
      a->Int("target_joint", &p.target_joint, -1, humanoid::kNumContactJoints - 1);
      a->Reals("direction", &p.direction);
    }
    if (a->loading()) s.label = s.walking() ? "walk" : "contact";
  }
}

void UnifiedSkill::SerializeTaskState(int i, StateArchive* a) {
  // Read into a copy: a snapshot rejected part way leaves the chain as it was.
  UnifiedState st = unified_[i];
  st.Serialize(a, *context_.scene);
  if (a->loading()) unified_[i] = std::move(st);
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
