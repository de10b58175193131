// ScanNet scans: our own PLY reader keeps ScanNet's vertex order, which the segment
// annotations index into.
#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "scene/loader_util.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/scene/loaders.h"

namespace sims::scene {

namespace {

std::filesystem::path FirstExisting(const std::vector<std::filesystem::path>& candidates) {
  for (const auto& c : candidates)
    if (std::filesystem::exists(c)) return c;
  return {};
}

}  // namespace

Scene LoadScanNet(const std::filesystem::path& scene_dir_or_ply) {
  namespace fs = std::filesystem;
  fs::path ply;
  if (fs::is_directory(scene_dir_or_ply)) {
    for (const auto& entry : fs::directory_iterator(scene_dir_or_ply)) {
      const std::string n = entry.path().filename().string();
      const std::string suffix = "_vh_clean_2.ply";
      if (n.size() > suffix.size() &&
          n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0)
        ply = entry.path();
    }
    if (ply.empty())
      ThrowInputError(scene_dir_or_ply.string(), "", "a ScanNet folder with <id>_vh_clean_2.ply",
                      "no such file");
  } else {
    ply = scene_dir_or_ply;
  }
  const std::string ply_name = ply.filename().string();
  const std::string suffix = "_vh_clean_2.ply";
  if (ply_name.size() <= suffix.size() ||
      ply_name.substr(ply_name.size() - suffix.size()) != suffix)
    ThrowInputError(ply.string(), "", "a ScanNet mesh named <id>_vh_clean_2.ply", ply_name);
  const std::string id = ply_name.substr(0, ply_name.size() - suffix.size());
  const fs::path dir = ply.parent_path();
  const fs::path agg_path =
      FirstExisting({dir / (id + ".aggregation.json"), dir / (id + "_vh_clean.aggregation.json")});
  if (agg_path.empty())
    ThrowInputError((dir / (id + ".aggregation.json")).string(), "",
                    "the ScanNet aggregation file next to " + ply_name, "no such file");
  const fs::path segs_path = dir / (id + "_vh_clean_2.0.010000.segs.json");
  TriangleMesh mesh = internal::ReadPly(ply);
  const nlohmann::json segs = internal::ReadJson(segs_path);
  const std::string segs_src = segs_path.string();
  const auto& seg_indices = internal::JsonField(segs, "segIndices", segs_src, "", "an array");
  if (!seg_indices.is_array() || seg_indices.size() != mesh.vertices.size())
    ThrowInputError(segs_src, "segIndices",
                    "one segment id per vertex (" + std::to_string(mesh.vertices.size()) + ")",
                    seg_indices.is_array() ? std::to_string(seg_indices.size()) + " ids"
                                           : seg_indices.type_name());
  std::vector<int64_t> vertex_segment(mesh.vertices.size());
  for (std::size_t i = 0; i < seg_indices.size(); ++i) {
    if (!seg_indices[i].is_number_integer())
      ThrowInputError(segs_src, "segIndices[" + std::to_string(i) + "]", "an integer",
                      seg_indices[i].dump());
    vertex_segment[i] = seg_indices[i].get<int64_t>();
  }
  const nlohmann::json agg = internal::ReadJson(agg_path);
  const std::string agg_src = agg_path.string();
  const auto& groups = internal::JsonField(agg, "segGroups", agg_src, "", "an array of groups");
  if (!groups.is_array()) ThrowInputError(agg_src, "segGroups", "an array", groups.type_name());

  // Optional axis alignment from <id>.txt.
  Eigen::Affine3d align = Eigen::Affine3d::Identity();
  if (std::ifstream meta(dir / (id + ".txt")); meta) {
    std::string line;
    while (std::getline(meta, line)) {
      if (line.rfind("axisAlignment", 0) != 0) continue;
      std::istringstream ss(line.substr(line.find('=') + 1));
      Eigen::Matrix4d M;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) ss >> M(r, c);
      if (!ss) ThrowInputError((dir / (id + ".txt")).string(), "axisAlignment", "16 numbers", line);
      align = Eigen::Affine3d(M);
    }
  }
  for (auto& v : mesh.vertices) v = align * v;

  const CategoryTable table = CategoryTable::Load(ConfigPath("scene/scannet_categories.json"));
  std::map<int64_t, int> segment_group;
  struct Group {
    std::string label;
    int object_id;
  };
  std::vector<Group> infos;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::string field = "segGroups[" + std::to_string(g) + "]";
    const auto& grp = groups[g];
    const auto& label = internal::JsonField(grp, "label", agg_src, field, "a label string");
    const auto& segments = internal::JsonField(grp, "segments", agg_src, field, "an array");
    if (!label.is_string()) ThrowInputError(agg_src, field + ".label", "a string", label.dump());
    if (!segments.is_array())
      ThrowInputError(agg_src, field + ".segments", "an array of segment ids", segments.dump());
    int object_id = static_cast<int>(g);
    if (grp.contains("objectId") && grp["objectId"].is_number_integer())
      object_id = grp["objectId"].get<int>();
    for (const auto& s : segments) {
      if (!s.is_number_integer())
        ThrowInputError(agg_src, field + ".segments", "integer segment ids", s.dump());
      segment_group.emplace(s.get<int64_t>(), static_cast<int>(g));
    }
    infos.push_back({label.get<std::string>(), object_id});
  }
  // Triangles follow the group of their first vertex's segment.
  std::vector<TriangleMesh> group_mesh(infos.size());
  for (const auto& t : mesh.triangles) {
    auto it = segment_group.find(vertex_segment[t[0]]);
    if (it == segment_group.end()) continue;
    TriangleMesh& m = group_mesh[it->second];
    const int base = static_cast<int>(m.vertices.size());
    for (int k = 0; k < 3; ++k) m.vertices.push_back(mesh.vertices[t[k]]);
    m.triangles.emplace_back(base, base + 1, base + 2);
  }
  // Floor to z = 0: the median height of floor-labelled geometry, else the lowest vertex.
  std::vector<double> floor_z;
  for (std::size_t g = 0; g < infos.size(); ++g)
    if (NormalizeName(infos[g].label) == "floor")
      for (const auto& v : group_mesh[g].vertices) floor_z.push_back(v.z());
  double z0 = 0;
  if (!floor_z.empty()) {
    std::nth_element(floor_z.begin(), floor_z.begin() + floor_z.size() / 2, floor_z.end());
    z0 = floor_z[floor_z.size() / 2];
  } else if (!mesh.vertices.empty()) {
    z0 = mesh.Bounds().min.z();
  }
  Eigen::Affine3d shift = Eigen::Affine3d::Identity();
  shift.translation().z() = -z0;

  Scene scene;
  scene.name = id;
  for (std::size_t g = 0; g < infos.size(); ++g) {
    if (group_mesh[g].empty()) continue;
    group_mesh[g] = group_mesh[g].Welded(1e-9);
    group_mesh[g].Transform(shift);
    const CategoryTable::Match m = table.Classify(infos[g].label);
    if (m.kind == CategoryTable::Kind::kIgnore) continue;
    if (m.kind == CategoryTable::Kind::kStructure) {
      scene.walls.Append(group_mesh[g]);
      continue;
    }
    Object o;
    o.category =
        m.kind == CategoryTable::Kind::kObject ? m.category : NormalizeName(infos[g].label);
    o.important = m.kind == CategoryTable::Kind::kObject ? m.important : false;
    o.source = "scannet:" + id + ":" + std::to_string(infos[g].object_id) + ":" + infos[g].label;
    Part p;
    p.name = "body";
    p.mesh = std::move(group_mesh[g]);
    o.parts.push_back(std::move(p));
    internal::SetPoseFromBounds(&o);
    scene.AddObject(std::move(o));
  }
  internal::SampleScenePoints(&scene, Object::kDefaultPointsPerPart);
  return scene;
}

}  // namespace sims::scene
