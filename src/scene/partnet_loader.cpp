// PartNet objects and UniHSI ScenePlans.
#include <functional>

#include "scene/loader_util.h"
#include "sims/core/error.h"
#include "sims/scene/loaders.h"

namespace sims::scene {

namespace {

using nlohmann::json;

struct Leaf {
  std::string name;
  int id = 0;
  std::vector<std::string> objs;
};

void CollectLeaves(const json& node, const std::string& src, const std::string& path,
                   std::vector<Leaf>* out) {
  if (!node.is_object()) ThrowInputError(src, path, "a part node object", node.type_name());
  if (node.contains("children")) {
    const json& ch = node["children"];
    if (!ch.is_array()) ThrowInputError(src, path + ".children", "an array", ch.type_name());
    for (std::size_t i = 0; i < ch.size(); ++i)
      CollectLeaves(ch[i], src, path + ".children[" + std::to_string(i) + "]", out);
    return;
  }
  Leaf leaf;
  const json& name = internal::JsonField(node, "name", src, path, "a part name");
  if (!name.is_string()) ThrowInputError(src, path + ".name", "a string", name.dump());
  leaf.name = name.get<std::string>();
  const json& id = internal::JsonField(node, "id", src, path, "an integer part id");
  if (!id.is_number_integer()) ThrowInputError(src, path + ".id", "an integer", id.dump());
  leaf.id = id.get<int>();
  const json& objs = internal::JsonField(node, "objs", src, path, "a list of obj names");
  if (!objs.is_array()) ThrowInputError(src, path + ".objs", "an array", objs.type_name());
  for (const auto& o : objs) {
    if (!o.is_string()) ThrowInputError(src, path + ".objs", "obj names (strings)", o.dump());
    leaf.objs.push_back(o.get<std::string>());
  }
  out->push_back(std::move(leaf));
}

Eigen::Matrix3d RotationXYZ(const std::vector<double>& r) {
  return (Eigen::AngleAxisd(r[0], Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(r[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r[2], Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

}  // namespace

Object LoadPartNet(const std::filesystem::path& dir, const PartNetOptions& options) {
  const auto result_path = dir / "result.json";
  const std::string src = result_path.string();
  const json result = internal::ReadJson(result_path);
  std::vector<Leaf> leaves;
  std::string root_name;
  if (result.is_array()) {
    if (result.empty()) ThrowInputError(src, "", "a non-empty array of part trees", "[]");
    for (std::size_t i = 0; i < result.size(); ++i)
      CollectLeaves(result[i], src, "[" + std::to_string(i) + "]", &leaves);
    if (result[0].is_object() && result[0].contains("name") && result[0]["name"].is_string())
      root_name = result[0]["name"].get<std::string>();
  } else {
    CollectLeaves(result, src, "", &leaves);
    if (result.contains("name") && result["name"].is_string())
      root_name = result["name"].get<std::string>();
  }
  if (leaves.empty()) ThrowInputError(src, "", "at least one leaf part with objs", "none");
  Object o;
  o.category = options.category.empty() ? NormalizeName(root_name) : options.category;
  if (o.category.empty()) o.category = "object";
  o.source = "partnet:" + dir.filename().string();
  o.instance = o.category + "_" + dir.filename().string();
  MeshLoadOptions mo;
  mo.up_axis = options.y_up_to_z_up ? "y" : "z";
  for (const auto& leaf : leaves) {
    Part p;
    p.name = NormalizeName(leaf.name);
    p.id = leaf.id;
    for (const auto& obj : leaf.objs) {
      const auto path = dir / "objs" / (obj + ".obj");
      if (!std::filesystem::exists(path))
        ThrowInputError(src, "part '" + leaf.name + "' (id " + std::to_string(leaf.id) + ").objs",
                        "an existing objs/" + obj + ".obj", "no such file");
      p.mesh.Append(LoadTriangleMesh(path, mo));
    }
    o.parts.push_back(std::move(p));
  }
  Rng rng(0);
  o.ResamplePoints(rng, options.points_per_part);
  return o;
}

std::vector<std::string> ScenePlanIds(const std::filesystem::path& json_path) {
  const json plans = internal::ReadJson(json_path);
  if (!plans.is_object() || plans.empty())
    ThrowInputError(json_path.string(), "", "an object of plans {plan_id: {obj, ...}}",
                    plans.is_object() ? "{}" : plans.type_name());
  std::vector<std::string> ids;
  for (auto it = plans.begin(); it != plans.end(); ++it) ids.push_back(it.key());
  return ids;
}

Scene LoadScenePlan(const std::filesystem::path& json_path,
                    const std::filesystem::path& partnet_root, const std::string& plan_id) {
  const std::string src = json_path.string();
  const json plans = internal::ReadJson(json_path);
  if (!plans.is_object() || plans.empty())
    ThrowInputError(src, "", "an object of plans {plan_id: {obj, ...}}", plans.type_name());
  const std::string id = plan_id.empty() ? plans.begin().key() : plan_id;
  if (!plans.contains(id)) {
    std::string ids;
    for (auto it = plans.begin(); it != plans.end() && ids.size() < 200; ++it)
      ids += (ids.empty() ? "" : ", ") + it.key();
    ThrowInputError(src, id, "a plan id (" + ids + ")", "no such plan");
  }
  const json& plan = plans[id];
  const json& objs = internal::JsonField(plan, "obj", src, id, "the plan's objects");
  if (!objs.is_object()) ThrowInputError(src, id + ".obj", "an object", objs.type_name());
  Scene scene;
  scene.name = json_path.stem().string() + "#" + id;
  PartNetOptions po;
  po.y_up_to_z_up = false;  // the plan's rotations take PartNet's frame to the scene
  for (auto it = objs.begin(); it != objs.end(); ++it) {
    const std::string field = id + ".obj." + it.key();
    const json& oj = it.value();
    const json& pid_j = internal::JsonField(oj, "id", src, field, "a PartNet id");
    const std::string pid = pid_j.is_string() ? pid_j.get<std::string>() : pid_j.dump();
    const json& name_j = internal::JsonField(oj, "name", src, field, "an object name");
    if (!name_j.is_string()) ThrowInputError(src, field + ".name", "a string", name_j.dump());
    const std::string name = name_j.get<std::string>();
    const auto dir = partnet_root / pid;
    if (!std::filesystem::exists(dir / "result.json"))
      ThrowInputError(src, field + ".id",
                      "a PartNet object folder " + dir.string() + " with result.json",
                      "no such folder");
    po.category = NormalizeName(name);
    Object o = LoadPartNet(dir, po);
    // rotate: a list of XYZ Euler triples applied in order about the origin.
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (oj.contains("rotate")) {
      const json& rot = oj["rotate"];
      if (!rot.is_array())
        ThrowInputError(src, field + ".rotate", "a list of [x, y, z] angles", rot.type_name());
      for (std::size_t k = 0; k < rot.size(); ++k)
        R = RotationXYZ(internal::NumberArray(rot[k], 3, src,
                                              field + ".rotate[" + std::to_string(k) + "]")) *
            R;
    }
    double scale = 1.0;
    if (oj.contains("scale")) {
      if (!oj["scale"].is_number() || oj["scale"].get<double>() <= 0)
        ThrowInputError(src, field + ".scale", "a positive number", oj["scale"].dump());
      scale = oj["scale"].get<double>();
    }
    Eigen::Vector3d transfer = Eigen::Vector3d::Zero();
    if (oj.contains("transfer")) {
      const auto t = internal::NumberArray(oj["transfer"], 3, src, field + ".transfer");
      transfer = Eigen::Vector3d(t[0], t[1], t[2]);
    }
    // Rotate, then scale about the vertex centroid, as UniHSI does with Open3D.
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::size_t count = 0;
    for (const auto& p : o.parts)
      for (const auto& v : p.mesh.vertices) {
        centroid += R * v;
        ++count;
      }
    if (count > 0) centroid /= static_cast<double>(count);
    Eigen::Affine3d A = Eigen::Affine3d::Identity();
    A.linear() = scale * R;
    A.translation() = centroid - scale * centroid;
    double min_z = 1e300;
    for (const auto& p : o.parts)
      for (const auto& v : p.mesh.vertices) min_z = std::min(min_z, (A * v).z());
    A.translation() += transfer - Eigen::Vector3d(0, 0, min_z);
    for (auto& p : o.parts) {
      p.mesh.Transform(A);
      for (auto& q : p.points) q = A * q;
    }
    o.X_WO = Eigen::Isometry3d::Identity();
    o.X_WO.linear() = R;
    o.X_WO.translation() = A.translation();
    o.scale = Eigen::Vector3d::Constant(scale);
    o.instance = name + it.key();
    o.source = "partnet:" + pid;
    scene.AddObject(std::move(o));
  }
  return scene;
}

}  // namespace sims::scene
