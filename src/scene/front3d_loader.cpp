// 3D-FRONT houses with 3D-FUTURE furniture models.
#include <algorithm>
#include <map>

#include <spdlog/spdlog.h>

#include "scene/loader_util.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/scene/loaders.h"

namespace sims::scene {

namespace {

using nlohmann::json;

struct ModelInfo {
  std::string category, super_category;
};

std::string StringField(const json& j, const std::string& key, const std::string& source,
                        const std::string& path) {
  const json& v = internal::JsonField(j, key, source, path, "a string");
  if (!v.is_string())
    ThrowInputError(source, path.empty() ? key : path + "." + key, "a string", v.dump());
  return v.get<std::string>();
}

std::string OptionalString(const json& j, const std::string& key) {
  auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

// World pose of a room child: world = R(rot) (v ⊙ scale) + pos, in the Y-up frame.
Eigen::Affine3d ChildTransform(const json& child, const std::string& source,
                               const std::string& path) {
  Eigen::Affine3d X = Eigen::Affine3d::Identity();
  if (child.contains("pos")) {
    const auto p = internal::NumberArray(child["pos"], 3, source, path + ".pos");
    X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (child.contains("rot")) {
    const auto r = internal::NumberArray(child["rot"], 4, source, path + ".rot");
    // 3D-FRONT stores quaternions as (x, y, z, w); Eigen's constructor takes (w, x, y, z).
    Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);
    if (q.norm() < 1e-9)
      ThrowInputError(source, path + ".rot", "a non-zero quaternion (x, y, z, w)", "zero");
    X.linear() = q.normalized().toRotationMatrix();
  }
  if (child.contains("scale")) {
    const auto s = internal::NumberArray(child["scale"], 3, source, path + ".scale");
    X.linear() = X.linear() * Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal();
  }
  return X;
}

std::string RoomType(const std::string& raw) {
  std::string t;
  for (char c : raw) {
    if (std::isupper(static_cast<unsigned char>(c)) && !t.empty() && t.back() != ' ') t += ' ';
    t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  t = NormalizeName(t);
  if (t.find("bedroom") != std::string::npos) return "bedroom";
  if (t.find("living") != std::string::npos) return "living room";
  if (t.find("dining") != std::string::npos) return "dining room";
  if (t.find("library") != std::string::npos || t.find("study") != std::string::npos)
    return "library";
  return t;
}

bool IsStructureMesh(const std::string& type) {
  static const char* kKinds[] = {"Wall",   "Front",  "Back",    "Baseboard",
                                 "Column", "Pillar", "Cabinet", "Pocket"};
  if (type.find("Ceiling") != std::string::npos || type.find("Floor") != std::string::npos)
    return false;
  for (const char* k : kKinds)
    if (type.find(k) != std::string::npos) return true;
  return false;
}

// Counter-clockwise convex hull of 2D points (monotone chain).
std::vector<Eigen::Vector2d> ConvexHull2D(std::vector<Eigen::Vector2d> pts) {
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  pts.erase(std::unique(pts.begin(), pts.end(),
                        [](const auto& a, const auto& b) { return (a - b).norm() < 1e-9; }),
            pts.end());
  if (pts.size() < 3) return pts;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
    h[k++] = pts[i - 1];
  }
  h.resize(k - 1);
  return h;
}

std::map<std::string, ModelInfo> ReadModelInfoList(const std::filesystem::path& path) {
  std::map<std::string, ModelInfo> out;
  if (!std::filesystem::exists(path)) return out;
  const json j = internal::ReadJson(path);
  if (!j.is_array()) ThrowInputError(path.string(), "", "an array of model records", j.type_name());
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string field = "[" + std::to_string(i) + "]";
    const std::string id = StringField(j[i], "model_id", path.string(), field);
    out[id] = {OptionalString(j[i], "category"), OptionalString(j[i], "super-category")};
  }
  return out;
}

}  // namespace

Scene LoadFront3D(const std::filesystem::path& house_json,
                  const std::filesystem::path& future_model_dir, const Front3DOptions& options) {
  const std::string src = house_json.string();
  const json house = internal::ReadJson(house_json);
  if (!std::filesystem::is_directory(future_model_dir))
    ThrowInputError(future_model_dir.string(), "", "the 3D-FUTURE-model folder", "no such folder");
  const CategoryTable table = CategoryTable::Load(
      options.category_table.empty() ? ConfigPath("scene/front3d_categories.json")
                                     : std::filesystem::path(options.category_table));
  const auto info_list = ReadModelInfoList(future_model_dir / "model_info.json");

  // furniture uid -> jid
  std::map<std::string, std::pair<std::string, std::string>> furniture;  // uid -> (jid, title)
  const json& furn = internal::JsonField(house, "furniture", src, "", "an array of furniture");
  if (!furn.is_array()) ThrowInputError(src, "furniture", "an array", furn.type_name());
  for (std::size_t i = 0; i < furn.size(); ++i) {
    const std::string field = "furniture[" + std::to_string(i) + "]";
    const std::string uid = StringField(furn[i], "uid", src, field);
    const std::string jid = StringField(furn[i], "jid", src, field);
    if (furn[i].contains("valid") && furn[i]["valid"].is_boolean() && !furn[i]["valid"].get<bool>())
      continue;
    furniture[uid] = {jid, OptionalString(furn[i], "title")};
  }
  // mesh uid -> index
  std::map<std::string, std::size_t> meshes;
  const json& mesh_list = internal::JsonField(house, "mesh", src, "", "an array of meshes");
  if (!mesh_list.is_array()) ThrowInputError(src, "mesh", "an array", mesh_list.type_name());
  for (std::size_t i = 0; i < mesh_list.size(); ++i)
    meshes[StringField(mesh_list[i], "uid", src, "mesh[" + std::to_string(i) + "]")] = i;

  const json& scene_j = internal::JsonField(house, "scene", src, "", "the scene object");
  const json& rooms = internal::JsonField(scene_j, "room", src, "scene", "an array of rooms");
  if (!rooms.is_array()) ThrowInputError(src, "scene.room", "an array", rooms.type_name());

  const Eigen::Affine3d C(internal::YUpToZUp().matrix());
  Scene scene;
  scene.name = house_json.stem().string();
  std::map<std::string, TriangleMesh> model_cache;
  int missing = 0;
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    const std::string rfield = "scene.room[" + std::to_string(r) + "]";
    const json& room = rooms[r];
    Room out_room;
    out_room.type = RoomType(StringField(room, "type", src, rfield));
    out_room.id = StringField(room, "instanceid", src, rfield);
    const json& children = internal::JsonField(room, "children", src, rfield, "an array");
    if (!children.is_array())
      ThrowInputError(src, rfield + ".children", "an array", children.type_name());
    std::vector<Eigen::Vector2d> floor_pts;
    for (std::size_t c = 0; c < children.size(); ++c) {
      const std::string cfield = rfield + ".children[" + std::to_string(c) + "]";
      const json& child = children[c];
      const std::string ref = StringField(child, "ref", src, cfield);
      const Eigen::Affine3d X = C * ChildTransform(child, src, cfield);
      if (auto f = furniture.find(ref); f != furniture.end()) {
        const std::string& jid = f->second.first;
        const auto model_dir = future_model_dir / jid;
        const auto obj = model_dir / "raw_model.obj";
        if (!std::filesystem::exists(obj)) {
          if (!options.skip_missing_models)
            ThrowInputError(obj.string(), "", "the 3D-FUTURE model of furniture '" + jid + "'",
                            "no such file");
          ++missing;
          continue;
        }
        auto cached = model_cache.find(jid);
        if (cached == model_cache.end()) {
          MeshLoadOptions mo;
          mo.up_axis = "z";  // keep the file frame; the child transform and C handle Y-up
          cached = model_cache.emplace(jid, LoadTriangleMesh(obj, mo)).first;
        }
        ModelInfo info;
        if (auto it = info_list.find(jid); it != info_list.end()) info = it->second;
        if (const auto per_model = model_dir / "model_info.json";
            std::filesystem::exists(per_model)) {
          const json mi = internal::ReadJson(per_model);
          info = {OptionalString(mi, "category"), OptionalString(mi, "super-category")};
        }
        CategoryTable::Match m = table.Classify(info.category);
        if (m.kind != CategoryTable::Kind::kObject) m = table.Classify(info.super_category);
        if (m.kind != CategoryTable::Kind::kObject) m = table.Classify(f->second.second);
        if (m.kind == CategoryTable::Kind::kIgnore) continue;
        Object o;
        o.category = m.kind == CategoryTable::Kind::kObject
                         ? m.category
                         : (info.category.empty() ? "object" : NormalizeName(info.category));
        o.important = m.kind == CategoryTable::Kind::kObject ? m.important : true;
        o.source = "3d-future:" + jid;
        o.room = out_room.id;
        Part p;
        p.name = "body";
        p.mesh = cached->second.Transformed(X);
        o.parts.push_back(std::move(p));
        // The object frame: rotation and position of the child, scale kept apart.
        Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
        const Eigen::Vector3d s = X.linear().colwise().norm().transpose();
        X_WO.linear() = X.linear() * s.cwiseInverse().asDiagonal();
        X_WO.translation() = X.translation();
        o.X_WO = X_WO;
        o.scale = s;
        scene.AddObject(std::move(o));
      } else if (auto mi = meshes.find(ref); mi != meshes.end()) {
        const json& mj = mesh_list[mi->second];
        const std::string mfield = "mesh[" + std::to_string(mi->second) + "]";
        const std::string type = OptionalString(mj, "type");
        const auto xyz =
            internal::NumberArray(internal::JsonField(mj, "xyz", src, mfield, "vertex coordinates"),
                                  -3, src, mfield + ".xyz");
        const auto faces =
            internal::NumberArray(internal::JsonField(mj, "faces", src, mfield, "triangle indices"),
                                  -3, src, mfield + ".faces");
        TriangleMesh tm;
        for (std::size_t k = 0; k < xyz.size(); k += 3)
          tm.vertices.push_back(X * Eigen::Vector3d(xyz[k], xyz[k + 1], xyz[k + 2]));
        const int nv = static_cast<int>(tm.vertices.size());
        for (std::size_t k = 0; k < faces.size(); k += 3) {
          Eigen::Vector3i t(static_cast<int>(faces[k]), static_cast<int>(faces[k + 1]),
                            static_cast<int>(faces[k + 2]));
          if (t.minCoeff() < 0 || t.maxCoeff() >= nv)
            ThrowInputError(src, mfield + ".faces", "indices below " + std::to_string(nv),
                            std::to_string(t.maxCoeff()));
          tm.triangles.push_back(t);
        }
        if (type.find("Floor") != std::string::npos)
          for (const auto& v : tm.vertices) floor_pts.emplace_back(v.x(), v.y());
        if (IsStructureMesh(type)) scene.walls.Append(tm);
      }
      // Other refs (lights, unknown) carry no geometry we use.
    }
    out_room.floor_polygon = ConvexHull2D(floor_pts);
    scene.rooms.push_back(std::move(out_room));
  }
  if (missing > 0)
    spdlog::warn("{}: skipped {} furniture item(s) whose 3D-FUTURE model is missing under {}", src,
                 missing, future_model_dir.string());
  internal::SampleScenePoints(&scene, options.points_per_part);
  return scene;
}

}  // namespace sims::scene
