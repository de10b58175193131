#include "sims/task/handoff.h"

#include <cmath>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "task/cached.h"

namespace sims::task {

namespace {
using config_internal::Abbreviate;
constexpr const char* kFormat = "sims-handoff-states";
constexpr int kVersion = 1;
// Margin around the target part's footprint the placed pelvis may reach (m).
constexpr double kFootprintMargin = 0.05;

// The placement taking object-frame coordinates of g to the world (furniture is yaw-only).
ClipPlacement ObjectToWorld(const ObjectGeometry& g, const Eigen::Vector3d& shift_O) {
  const Eigen::Vector3d t = g.X_WO.translation();
  return ClipPlacement::Align(t.head<2>(), g.yaw, -shift_O.head<2>(), 0.0, t.z() + shift_O.z());
}

bool OverFootprint(const Eigen::Vector3d& p, const scene::Aabb& box, double margin) {
  return p.x() >= box.min.x() - margin && p.x() <= box.max.x() + margin &&
         p.y() >= box.min.y() - margin && p.y() <= box.max.y() + margin;
}

nlohmann::json Vec(const Eigen::Ref<const Eigen::VectorXd>& v) {
  nlohmann::json a = nlohmann::json::array();
  // Five decimals keep a state within 10 µm (or µrad) and the file small.
  for (int k = 0; k < v.size(); ++k) a.push_back(std::round(v[k] * 1e5) / 1e5);
  return a;
}

Eigen::VectorXd ReadVec(const nlohmann::json& j, const char* key, int n, const std::string& file,
                        const std::string& where) {
  const std::string field = where + "." + key;
  if (!j.contains(key) || !j[key].is_array() || static_cast<int>(j[key].size()) != n)
    ThrowInputError(file, field, "an array of " + std::to_string(n) + " numbers",
                    j.contains(key) ? Abbreviate(j[key]) : "nothing");
  Eigen::VectorXd v(n);
  for (int k = 0; k < n; ++k) {
    if (!j[key][k].is_number() || !std::isfinite(j[key][k].get<double>()))
      ThrowInputError(file, field, "finite numbers", Abbreviate(j[key][k]));
    v[k] = j[key][k].get<double>();
  }
  return v;
}
}  // namespace

Eigen::Vector3d HandoffAnchor(const std::string& part, const scene::Aabb& part_O) {
  const double y = 0.5 * (part_O.min.y() + part_O.max.y());
  // A bed is lain on head first: its head end (−x) lines the pillow up; a seat is sat on from
  // its front edge (+x).
  const double x = part == kMattressPart ? part_O.min.x() : part_O.max.x();
  return {x, y, part_O.max.z()};
}

HandoffState MakeHandoffState(const std::string& skill, const std::string& part,
                              const ObjectGeometry& g, const humanoid::HumanoidPose& pose_W,
                              bool success) {
  HandoffState s;
  s.skill = skill;
  s.part = part;
  s.part_O = g.part_local(part);
  // The inverse placement: the object's frame onto the origin.
  const Eigen::Vector3d t = g.X_WO.translation();
  s.pose =
      ClipPlacement::Align(Eigen::Vector2d::Zero(), 0.0, t.head<2>(), g.yaw, -t.z()).Apply(pose_W);
  s.success = success;
  return s;
}

std::optional<humanoid::HumanoidPose> PlaceHandoffState(const HandoffState& s,
                                                        const ObjectGeometry& g,
                                                        double max_height_diff,
                                                        double max_depth_diff) {
  const ObjectPart* part = g.part(s.part);
  if (!part) return std::nullopt;
  const scene::Aabb& to = part->local;
  const double dz = to.max.z() - s.part_O.max.z();
  const double depth_diff = (to.max.x() - to.min.x()) - (s.part_O.max.x() - s.part_O.min.x());
  if (std::abs(dz) > max_height_diff || std::abs(depth_diff) > max_depth_diff) return std::nullopt;
  Eigen::Vector3d shift = HandoffAnchor(s.part, to) - HandoffAnchor(s.part, s.part_O);
  shift.z() = std::max(dz, 0.0);
  if (OverFootprint(s.pose.root_pos, s.part_O, 0.0) &&
      !OverFootprint(s.pose.root_pos + shift, to, kFootprintMargin))
    return std::nullopt;
  return ObjectToWorld(g, shift).Apply(s.pose);
}

void SaveHandoffStates(const std::vector<HandoffState>& states, const std::filesystem::path& path) {
  nlohmann::json list = nlohmann::json::array();
  for (const HandoffState& s : states) {
    const humanoid::HumanoidPose& p = s.pose;
    list.push_back({{"skill", s.skill},
                    {"part", s.part},
                    {"part_min", Vec(s.part_O.min)},
                    {"part_max", Vec(s.part_O.max)},
                    {"success", s.success},
                    {"root_pos", Vec(p.root_pos)},
                    {"root_rot_wxyz", Vec(Eigen::Vector4d(p.root_rot.w(), p.root_rot.x(),
                                                          p.root_rot.y(), p.root_rot.z()))},
                    {"root_lin_vel", Vec(p.root_lin_vel)},
                    {"root_ang_vel", Vec(p.root_ang_vel)},
                    {"dof_pos", Vec(p.dof_pos)},
                    {"dof_vel", Vec(p.dof_vel)}});
  }
  // One state per line: the file stays small enough to commit beside a policy and diffable.
  std::string text = nlohmann::json({{"format", kFormat}, {"version", kVersion}}).dump();
  text.pop_back();
  text += ", \"states\": [\n";
  for (size_t k = 0; k < list.size(); ++k)
    text += list[k].dump() + (k + 1 < list.size() ? ",\n" : "\n");
  text += "]}\n";
  WriteFileAtomic(path, text);
}

std::vector<HandoffState> LoadHandoffStates(const std::filesystem::path& path) {
  const std::string file = path.string();
  const nlohmann::json j = ReadJsonFile(path);
  if (!j.is_object() || j.value("format", "") != kFormat)
    ThrowInputError(file, "format", std::string("\"") + kFormat + "\"",
                    j.is_object() && j.contains("format") ? Abbreviate(j["format"]) : "nothing");
  if (j.value("version", 0) != kVersion)
    ThrowInputError(file, "version", std::to_string(kVersion),
                    j.contains("version") ? Abbreviate(j["version"]) : "nothing");
  if (!j.contains("states") || !j["states"].is_array() || j["states"].empty())
    ThrowInputError(file, "states", "a non-empty array of states",
                    j.contains("states") ? Abbreviate(j["states"]) : "nothing");
  std::vector<HandoffState> out;
  for (size_t k = 0; k < j["states"].size(); ++k) {
    const nlohmann::json& e = j["states"][k];
    const std::string where = "states[" + std::to_string(k) + "]";
    if (!e.is_object()) ThrowInputError(file, where, "an object", Abbreviate(e));
    HandoffState s;
    for (const char* key : {"skill", "part"})
      if (!e.contains(key) || !e[key].is_string() || e[key].get<std::string>().empty())
        ThrowInputError(file, where + "." + key, "a non-empty string",
                        e.contains(key) ? Abbreviate(e[key]) : "nothing");
    s.skill = e["skill"].get<std::string>();
    s.part = e["part"].get<std::string>();
    s.success = e.value("success", false);
    s.part_O.min = ReadVec(e, "part_min", 3, file, where);
    s.part_O.max = ReadVec(e, "part_max", 3, file, where);
    if ((s.part_O.min.array() > s.part_O.max.array()).any())
      ThrowInputError(file, where + ".part_max", "a corner ≥ part_min in x, y and z",
                      Abbreviate(e["part_max"]));
    humanoid::HumanoidPose& p = s.pose;
    p.root_pos = ReadVec(e, "root_pos", 3, file, where);
    const Eigen::VectorXd q = ReadVec(e, "root_rot_wxyz", 4, file, where);
    if (q.norm() < 0.5)
      ThrowInputError(file, where + ".root_rot_wxyz", "a unit quaternion (w, x, y, z)",
                      Abbreviate(e["root_rot_wxyz"]));
    p.root_rot = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
    p.root_lin_vel = ReadVec(e, "root_lin_vel", 3, file, where);
    p.root_ang_vel = ReadVec(e, "root_ang_vel", 3, file, where);
    p.dof_pos = ReadVec(e, "dof_pos", humanoid::kNumDofs, file, where);
    p.dof_vel = ReadVec(e, "dof_vel", humanoid::kNumDofs, file, where);
    out.push_back(std::move(s));
  }
  return out;
}

std::shared_ptr<const std::vector<HandoffState>> SharedHandoffStates(
    const std::vector<std::string>& files) {
  std::vector<std::filesystem::path> paths;
  std::string key;
  for (const std::string& file : files) {
    std::filesystem::path path = file;
    if (path.is_relative() && !std::filesystem::exists(path)) path = ProjectRoot() / path;
    paths.push_back(std::filesystem::absolute(path).lexically_normal());
    key += paths.back().string() + '\n';
  }
  return Cached<std::vector<HandoffState>>(key, [&] {
    std::vector<HandoffState> states;
    for (const auto& path : paths) {
      const std::vector<HandoffState> part = LoadHandoffStates(path);
      states.insert(states.end(), part.begin(), part.end());
    }
    return states;
  });
}

}  // namespace sims::task
