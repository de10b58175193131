#include "sims/task/contact_plan.h"

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/scene/contact_targets.h"
#include "sims/scene/loaders.h"

namespace sims::task {

bool ContactStep::walking() const { return mask() == 0; }

uint32_t ContactStep::mask() const {
  uint32_t m = 0;
  for (const auto& p : pairs)
    if (p.type != ContactType::kNone) m |= 1u << p.joint;
  return m;
}

std::array<ContactType, humanoid::kNumContactJoints> ContactStep::types() const {
  std::array<ContactType, humanoid::kNumContactJoints> t;
  t.fill(ContactType::kNone);
  for (const auto& p : pairs) t[p.joint] = p.type;
  return t;
}

std::array<JointPair, humanoid::kNumContactJoints> ResolveStep(const ContactStep& step,
                                                               const scene::Scene& scene,
                                                               const humanoid::BodyStates& b) {
  std::array<JointPair, humanoid::kNumContactJoints> pairs;
  for (const auto& p : step.pairs) {
    if (p.type == ContactType::kNone) continue;
    JointPair& jp = pairs[p.joint];
    jp.type = p.type;
    jp.joint = humanoid::ContactJointPosition(b, p.joint);
    jp.target = p.target_joint >= 0
                    ? humanoid::ContactJointPosition(b, p.target_joint)
                    : scene::NearestSamplePoint(scene.objects[p.object].parts[p.part], jp.joint);
    jp.direction = p.direction;
  }
  return pairs;
}

namespace {

using nlohmann::json;

std::string Str(const json& j, const std::string& src, const std::string& field,
                const std::string& expected) {
  if (!j.is_string()) ThrowInputError(src, field, expected, j.dump());
  return j.get<std::string>();
}

int JointOrMinus(const std::string& name) {
  const auto& names = humanoid::ContactJointNames();
  for (int j = 0; j < humanoid::kNumContactJoints; ++j)
    if (name == names[j]) return j;
  return -1;
}

std::string JointList() {
  std::string s;
  for (const char* n : humanoid::ContactJointNames()) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

// The stand point of plan object `key` ("000"): its first "stand_point" entry, else a point
// in front (+x) of its bounds at standing height.
Eigen::Vector3d StandPoint(const json& plan, const std::string& key, const scene::Object& o,
                           const std::string& src, const std::string& field) {
  if (plan.contains("obj") && plan["obj"].is_object() && plan["obj"].contains(key)) {
    const json& oj = plan["obj"][key];
    if (oj.contains("stand_point")) {
      const json& sp = oj["stand_point"];
      const json& first = sp.is_array() && !sp.empty() && sp[0].is_array() ? sp[0] : sp;
      if (!first.is_array() || first.size() != 3)
        ThrowInputError(src, field + ".stand_point", "[x, y, z] or a list of them", sp.dump());
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        if (!first[k].is_number())
          ThrowInputError(src, field + ".stand_point", "numbers", first.dump());
        p[k] = first[k].get<double>();
      }
      return p;
    }
  }
  const scene::Aabb b = o.Bounds();
  return {b.max.x() + 0.45, 0.5 * (b.min.y() + b.max.y()), humanoid::kDefaultRootHeight};
}

}  // namespace

ContactPlan ContactPlanFromJson(const json& plan, const scene::Scene& scene, const std::string& src,
                                const std::string& id) {
  ContactPlan out;
  out.id = id;
  const char* key = plan.contains("chain of contacts") ? "chain of contacts" : "contact_pairs";
  if (!plan.is_object() || !plan.contains(key))
    ThrowInputError(src, id, "a plan with \"chain of contacts\" or \"contact_pairs\"",
                    plan.is_object() ? "neither key" : plan.type_name());
  const json& steps = plan[key];
  if (!steps.is_array()) ThrowInputError(src, id + "." + key, "a list of steps", steps.type_name());
  for (size_t s = 0; s < steps.size(); ++s) {
    const std::string sf = id + "." + key + "[" + std::to_string(s) + "]";
    const json& step = steps[s];
    if (!step.is_array()) ThrowInputError(src, sf, "a list of contact pairs", step.type_name());
    ContactStep cs;
    std::string obj_key;
    for (size_t p = 0; p < step.size(); ++p) {
      const std::string pf = sf + "[" + std::to_string(p) + "]";
      const json& pair = step[p];
      if (!pair.is_array() || pair.size() < 4)
        ThrowInputError(src, pf, "[object, part, joint, contact type, direction]", pair.dump());
      const std::string obj = Str(pair[0], src, pf + "[0]", "an object key such as chair000");
      const std::string part = Str(pair[1], src, pf + "[1]", "a part key, a joint or none");
      const std::string joint = Str(pair[2], src, pf + "[2]", "a joint name or none");
      const std::string type = Str(pair[3], src, pf + "[3]", "contact, not contact or none");
      const std::string dir =
          pair.size() > 4 ? Str(pair[4], src, pf + "[4]", "a direction") : std::string("none");
      const int oi = scene.ObjectIndex(obj);
      if (oi < 0) {
        std::string known;
        for (const auto& o : scene.objects) known += (known.empty() ? "" : ", ") + o.instance;
        ThrowInputError(src, pf + "[0]", "an object of the plan (" + known + ")", "'" + obj + "'");
      }
      cs.object = oi;
      obj_key = obj.size() >= 3 ? obj.substr(obj.size() - 3) : obj;
      ContactPairSpec ps;
      if (!ParseContactType(type, &ps.type))
        ThrowInputError(src, pf + "[3]", "contact, not contact or none", "'" + type + "'");
      if (!ParseDirection(dir, &ps.direction))
        ThrowInputError(src, pf + "[4]", "up, down, left, right, front, back or none",
                        "'" + dir + "'");
      if (part == "none" || joint == "none") continue;  // no contact: a walking pair
      ps.joint = JointOrMinus(joint);
      if (ps.joint < 0)
        ThrowInputError(src, pf + "[2]", "a contact joint (" + JointList() + ")",
                        "'" + joint + "'");
      ps.target_joint = JointOrMinus(part);
      if (ps.target_joint < 0) {
        const scene::Object& o = scene.objects[oi];
        const scene::Part* pp = o.FindPartByKey(part);
        if (!pp) {
          std::string known;
          for (const auto& q : o.parts)
            known += (known.empty() ? "" : ", ") + scene::UniHsiPartKey(q);
          ThrowInputError(src, pf + "[1]", "a part of " + obj + " (" + known + ")",
                          "'" + part + "'");
        }
        ps.object = oi;
        ps.part = static_cast<int>(pp - o.parts.data());
      }
      for (const auto& q : cs.pairs)
        if (q.joint == ps.joint)
          ThrowInputError(src, pf + "[2]", "one pair per joint in a step",
                          "a second pair for '" + joint + "'");
      cs.pairs.push_back(ps);
    }
    if (cs.object < 0)
      ThrowInputError(src, sf, "at least one pair naming an object", "an empty step");
    cs.stand_point =
        StandPoint(plan, obj_key, scene.objects[cs.object], src, id + ".obj." + obj_key);
    cs.label = cs.walking() ? "walk" : "contact";
    out.steps.push_back(std::move(cs));
  }
  return out;
}

ContactPlan LoadContactPlan(const std::filesystem::path& json_path, const scene::Scene& scene,
                            const std::string& plan_id) {
  const json plans = ReadJsonFile(json_path);
  const std::string src = json_path.string();
  if (!plans.is_object() || plans.empty())
    ThrowInputError(src, "", "an object of plans {plan_id: {obj, chain of contacts}}",
                    plans.type_name());
  const std::string id = plan_id.empty() ? plans.begin().key() : plan_id;
  if (!plans.contains(id)) {
    std::string ids;
    for (auto it = plans.begin(); it != plans.end() && ids.size() < 200; ++it)
      ids += (ids.empty() ? "" : ", ") + it.key();
    ThrowInputError(src, id, "a plan id (" + ids + ")", "no such plan");
  }
  return ContactPlanFromJson(plans[id], scene, src, id);
}

LoadedScenePlan LoadScenePlanRef(const std::string& ref,
                                 const std::filesystem::path& partnet_root) {
  const auto r = scene::ParseScenePlanRef(ref);
  LoadedScenePlan out;
  out.file = r.file;
  out.scene = std::make_shared<const scene::Scene>(scene::LoadScenePlan(
      r.file, partnet_root.empty() ? scene::DefaultPartNetRoot() : partnet_root, r.id));
  out.plan = LoadContactPlan(r.file, *out.scene, r.id);
  if (out.plan.steps.empty())
    ThrowInputError(r.file.string(), out.plan.id, "a plan with at least one chain-of-contacts step",
                    "no steps");
  return out;
}

}  // namespace sims::task
