#include "sims/io/gltf_export.h"

#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "io/shapes.h"
#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/motion/skeleton.h"

namespace sims::io {

namespace {

using nlohmann::json;

constexpr int kFloat = 5126;
constexpr int kUint32 = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementBuffer = 34963;

// Accumulates the binary buffer, buffer views, accessors, meshes, materials and nodes.
class GltfBuilder {
 public:
  GltfBuilder() {
    doc_["asset"] = {{"version", "2.0"}, {"generator", "SIMS-C++ io::ExportGltf"}};
    for (const char* k : {"bufferViews", "accessors", "meshes", "materials", "nodes"})
      doc_[k] = json::array();
  }

  int AddView(const void* data, std::size_t bytes, int target) {
    while (bin_.size() % 4) bin_.push_back(0);
    json v = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
    if (target) v["target"] = target;
    const auto* p = static_cast<const uint8_t*>(data);
    bin_.insert(bin_.end(), p, p + bytes);
    doc_["bufferViews"].push_back(v);
    return static_cast<int>(doc_["bufferViews"].size()) - 1;
  }

  // Float accessor of `count` elements of `width` floats; min/max when requested.
  int AddFloats(const std::vector<float>& values, int width, const char* type, bool bounds,
                int target) {
    const std::size_t count = values.size() / width;
    const int view = AddView(values.data(), values.size() * sizeof(float), target);
    json a = {{"bufferView", view}, {"componentType", kFloat}, {"count", count}, {"type", type}};
    if (bounds && count > 0) {
      std::vector<float> lo(width, 1e30f), hi(width, -1e30f);
      for (std::size_t i = 0; i < count; ++i)
        for (int k = 0; k < width; ++k) {
          lo[k] = std::min(lo[k], values[i * width + k]);
          hi[k] = std::max(hi[k], values[i * width + k]);
        }
      a["min"] = lo;
      a["max"] = hi;
    }
    doc_["accessors"].push_back(a);
    return static_cast<int>(doc_["accessors"].size()) - 1;
  }

  int AddIndices(const std::vector<uint32_t>& idx) {
    const int view = AddView(idx.data(), idx.size() * sizeof(uint32_t), kElementBuffer);
    doc_["accessors"].push_back({{"bufferView", view},
                                 {"componentType", kUint32},
                                 {"count", idx.size()},
                                 {"type", "SCALAR"}});
    return static_cast<int>(doc_["accessors"].size()) - 1;
  }

  int Material(const std::string& name, const Eigen::Vector4f& rgba, double roughness = 0.8) {
    auto it = materials_.find(name);
    if (it != materials_.end()) return it->second;
    json m = {{"name", name},
              {"pbrMetallicRoughness",
               {{"baseColorFactor", {rgba[0], rgba[1], rgba[2], rgba[3]}},
                {"metallicFactor", 0.0},
                {"roughnessFactor", roughness}}}};
    if (rgba[3] < 1) m["alphaMode"] = "BLEND";
    doc_["materials"].push_back(m);
    const int id = static_cast<int>(doc_["materials"].size()) - 1;
    materials_[name] = id;
    return id;
  }

  // One mesh from (shape, material) primitives; −1 when all are empty.
  int AddMesh(const std::string& name, const std::vector<std::pair<ShapeMesh, int>>& prims) {
    json primitives = json::array();
    for (const auto& [shape, material] : prims) {
      if (shape.indices.empty()) continue;
      const int pos = AddFloats(shape.positions, 3, "VEC3", true, kArrayBuffer);
      const int nrm = AddFloats(shape.normals, 3, "VEC3", false, kArrayBuffer);
      const int idx = AddIndices(shape.indices);
      primitives.push_back({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}},
                            {"indices", idx},
                            {"material", material},
                            {"mode", 4}});
    }
    if (primitives.empty()) return -1;
    doc_["meshes"].push_back({{"name", name}, {"primitives", primitives}});
    return static_cast<int>(doc_["meshes"].size()) - 1;
  }

  int AddNode(json node) {
    doc_["nodes"].push_back(std::move(node));
    return static_cast<int>(doc_["nodes"].size()) - 1;
  }
  json& node(int i) { return doc_["nodes"][i]; }
  json& doc() { return doc_; }
  std::vector<uint8_t>& bin() { return bin_; }

 private:
  json doc_;
  std::vector<uint8_t> bin_;
  std::map<std::string, int> materials_;
};

Eigen::Vector4f CategoryRgba(const std::string& category) {
  static const std::map<std::string, Eigen::Vector4f> colors = {
      {"chair", {0.62f, 0.42f, 0.25f, 1}},    {"armchair", {0.55f, 0.2f, 0.2f, 1}},
      {"sofa", {0.35f, 0.4f, 0.6f, 1}},       {"bed", {0.85f, 0.85f, 0.8f, 1}},
      {"table", {0.5f, 0.35f, 0.2f, 1}},      {"desk", {0.45f, 0.33f, 0.22f, 1}},
      {"shelf", {0.6f, 0.5f, 0.35f, 1}},      {"lamp", {0.9f, 0.85f, 0.5f, 1}},
      {"stool", {0.58f, 0.44f, 0.3f, 1}},     {"cabinet", {0.52f, 0.4f, 0.3f, 1}},
      {"wardrobe", {0.48f, 0.36f, 0.26f, 1}},
  };
  auto it = colors.find(category);
  if (it != colors.end()) return it->second;
  // Unknown categories get a stable muted colour from their name.
  uint32_t h = 2166136261u;
  for (char c : category) h = (h ^ static_cast<uint8_t>(c)) * 16777619u;
  return {0.35f + 0.4f * ((h & 255) / 255.f), 0.35f + 0.4f * (((h >> 8) & 255) / 255.f),
          0.35f + 0.4f * (((h >> 16) & 255) / 255.f), 1};
}

json QuatXyzw(const Eigen::Quaterniond& q) { return {q.x(), q.y(), q.z(), q.w()}; }
json Vec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// Local rotation of body b relative to its parent in frame f.
Eigen::Quaterniond LocalRotation(const RecordFrame& f, int b, int parent) {
  return parent < 0 ? f.body_rot[b] : (f.body_rot[parent].conjugate() * f.body_rot[b]).normalized();
}

void AddCharacter(const MotionRecord& record, const GltfOptions& options, GltfBuilder* g,
                  int world) {
  const auto& skel = motion::HumanoidSkeleton::Default();
  const auto humanoid = motion::HumanoidSkeleton::DefaultHumanoid();
  const std::array<ShapeMesh, humanoid::kNumBodies> shapes =
      HumanoidBodyShapes(*humanoid, options.sphere_segments);
  const int skin = g->Material("character", {0.80f, 0.60f, 0.45f, 1}, 0.6);
  std::array<int, humanoid::kNumBodies> node{};
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    json n = {{"name", humanoid::BodyNames()[b]}};
    const int mesh =
        g->AddMesh(std::string(humanoid::BodyNames()[b]) + "_shape", {{shapes[b], skin}});
    if (mesh >= 0) n["mesh"] = mesh;
    Eigen::Quaterniond rot = skel.rest[b];
    Eigen::Vector3d trans =
        b == 0 ? Eigen::Vector3d(0, 0, humanoid::kDefaultRootHeight) : skel.offset[b];
    if (!record.frames.empty()) {
      rot = LocalRotation(record.frames[0], b, skel.parent[b]);
      if (b == 0) trans = record.frames[0].body_pos[0];
    }
    n["translation"] = Vec3(trans);
    n["rotation"] = QuatXyzw(rot);
    node[b] = g->AddNode(n);
  }
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    const int p = skel.parent[b];
    json& parent = p < 0 ? g->node(world) : g->node(node[p]);
    if (!parent.contains("children")) parent["children"] = json::array();
    parent["children"].push_back(node[b]);
  }
  if (record.frames.empty()) return;

  std::vector<float> times;
  for (const RecordFrame& f : record.frames) times.push_back(static_cast<float>(f.time));
  const int input = g->AddFloats(times, 1, "SCALAR", true, 0);
  json samplers = json::array(), channels = json::array();
  auto add_channel = [&](int node_id, const char* path, const std::vector<float>& values,
                         const char* type, int width) {
    const int output = g->AddFloats(values, width, type, false, 0);
    samplers.push_back({{"input", input}, {"output", output}, {"interpolation", "LINEAR"}});
    channels.push_back({{"sampler", static_cast<int>(samplers.size()) - 1},
                        {"target", {{"node", node_id}, {"path", path}}}});
  };
  std::vector<float> root_t;
  for (const RecordFrame& f : record.frames)
    for (int k = 0; k < 3; ++k) root_t.push_back(static_cast<float>(f.body_pos[0][k]));
  add_channel(node[0], "translation", root_t, "VEC3", 3);
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    std::vector<float> q;
    Eigen::Quaterniond prev = Eigen::Quaterniond::Identity();
    for (std::size_t i = 0; i < record.frames.size(); ++i) {
      Eigen::Quaterniond r = LocalRotation(record.frames[i], b, skel.parent[b]);
      // Keep consecutive keys in one hemisphere so every importer interpolates the short way.
      if (i > 0 && r.coeffs().dot(prev.coeffs()) < 0) r.coeffs() *= -1;
      prev = r;
      for (double c : {r.x(), r.y(), r.z(), r.w()}) q.push_back(static_cast<float>(c));
    }
    add_channel(node[b], "rotation", q, "VEC4", 4);
  }
  g->doc()["animations"] =
      json::array({{{"name", "motion"}, {"samplers", samplers}, {"channels", channels}}});
}

void AddScene(const MotionRecord& record, const scene::Scene* scene, const GltfOptions& options,
              GltfBuilder* g, int world) {
  auto attach = [&](int parent, int child) {
    json& p = g->node(parent);
    if (!p.contains("children")) p["children"] = json::array();
    p["children"].push_back(child);
  };
  scene::Aabb bounds;
  if (scene) {
    const int scene_node = g->AddNode({{"name", "scene"}});
    attach(world, scene_node);
    json& extras = g->node(scene_node)["extras"];
    extras["scene_name"] = scene->name;
    if (options.furniture) {
      for (const scene::Object& o : scene->objects) {
        const int obj = g->AddNode({{"name", o.instance}, {"extras", {{"category", o.category}}}});
        attach(scene_node, obj);
        const int mat = g->Material(o.category, CategoryRgba(o.category));
        std::set<std::string> used;
        for (const scene::Part& part : o.parts) {
          std::string name = o.instance + "/" + part.name;
          if (!used.insert(name).second) name += "#" + std::to_string(part.id);
          const int mesh = g->AddMesh(name, {{FlatShadedMesh(part.mesh), mat}});
          if (mesh < 0) continue;
          attach(obj, g->AddNode({{"name", name}, {"mesh", mesh}}));
        }
        bounds.Extend(o.Bounds());
      }
    }
    if (options.walls && !scene->walls.empty()) {
      const int mat = g->Material("walls", {0.78f, 0.78f, 0.75f, 1});
      const int mesh = g->AddMesh("walls", {{FlatShadedMesh(scene->walls), mat}});
      if (mesh >= 0) attach(scene_node, g->AddNode({{"name", "walls"}, {"mesh", mesh}}));
      bounds.Extend(scene->walls.Bounds());
    }
  }
  if (options.floor) {
    for (const RecordFrame& f : record.frames) bounds.Extend(f.root_pos);
    if (bounds.empty()) bounds.Extend(Eigen::Vector3d::Zero());
    const Eigen::Vector3d lo = bounds.min.array() - options.floor_margin;
    const Eigen::Vector3d hi = bounds.max.array() + options.floor_margin;
    const int mat = g->Material("floor", {0.55f, 0.56f, 0.58f, 1}, 0.9);
    const int mesh = g->AddMesh("floor", {{FloorQuad(lo.head<2>(), hi.head<2>()), mat}});
    attach(world, g->AddNode({{"name", "floor"}, {"mesh", mesh}}));
  }
}

json RecordExtras(const MotionRecord& record) {
  json kfs = json::array();
  for (const auto& a : record.keyframes)
    kfs.push_back({{"index", a.index},
                   {"skill", a.skill},
                   {"caption", a.caption},
                   {"emotion", a.emotion},
                   {"start_frame", a.start_frame},
                   {"end_frame", a.end_frame},
                   {"success", a.success}});
  return {{"title", record.title}, {"fps", record.fps}, {"keyframes", kfs}};
}

std::string Padded(std::string s, char pad) {
  while (s.size() % 4) s.push_back(pad);
  return s;
}

void PutU32(std::string* s, uint32_t v) {
  char b[4];
  std::memcpy(b, &v, 4);  // glTF is little-endian, as is every platform this project runs on
  s->append(b, 4);
}

}  // namespace

void ExportGltf(const MotionRecord& record, const scene::Scene* scene,
                const std::filesystem::path& path, const GltfOptions& options) {
  const std::string ext = path.extension().string();
  if (ext != ".glb" && ext != ".gltf")
    ThrowInputError(path.string(), "", "a .glb or .gltf output path",
                    ext.empty() ? "no extension" : ext);
  if (!record.frames.empty()) record.Validate("ExportGltf");
  GltfBuilder g;
  // glTF is Y-up; the project is Z-up: one root rotation of −90° about x keeps every node below
  // it in project coordinates.
  const double s = std::sqrt(0.5);
  const int world = g.AddNode(
      {{"name", "sims_world"}, {"rotation", {-s, 0.0, 0.0, s}}, {"extras", RecordExtras(record)}});
  if (options.character) AddCharacter(record, options, &g, world);
  AddScene(record, scene, options, &g, world);
  g.doc()["scenes"] = json::array({{{"name", scene ? scene->name : "motion"}, {"nodes", {world}}}});
  g.doc()["scene"] = 0;
  for (const char* k : {"meshes", "materials", "accessors", "bufferViews"})
    if (g.doc()[k].empty()) g.doc().erase(k);
  std::vector<uint8_t>& bin = g.bin();
  while (bin.size() % 4) bin.push_back(0);

  if (ext == ".glb") {
    if (!bin.empty()) g.doc()["buffers"] = json::array({{{"byteLength", bin.size()}}});
    const std::string js = Padded(g.doc().dump(), ' ');
    std::string out;
    const uint32_t total = 12 + 8 + static_cast<uint32_t>(js.size()) +
                           (bin.empty() ? 0 : 8 + static_cast<uint32_t>(bin.size()));
    PutU32(&out, 0x46546C67);  // "glTF"
    PutU32(&out, 2);
    PutU32(&out, total);
    PutU32(&out, static_cast<uint32_t>(js.size()));
    PutU32(&out, 0x4E4F534A);  // "JSON"
    out += js;
    if (!bin.empty()) {
      PutU32(&out, static_cast<uint32_t>(bin.size()));
      PutU32(&out, 0x004E4942);  // "BIN\0"
      out.append(reinterpret_cast<const char*>(bin.data()), bin.size());
    }
    WriteFileAtomic(path, out);
  } else {
    std::filesystem::path bin_path = path;
    bin_path.replace_extension(".bin");
    if (!bin.empty()) {
      g.doc()["buffers"] =
          json::array({{{"byteLength", bin.size()}, {"uri", bin_path.filename().string()}}});
      WriteFileAtomic(bin_path, std::string(reinterpret_cast<const char*>(bin.data()), bin.size()));
    }
    WriteFileAtomic(path, g.doc().dump(1) + "\n");
  }
}

}  // namespace sims::io
