// Generic Assimp scenes and the MORSE data.
#include <functional>

#include "scene/loader_util.h"
#include "sims/core/environment.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/scene/loaders.h"

namespace sims::scene {

using internal::ImportedMesh;
using internal::ImportedNode;

void MeshLoadOptions::Validate() const {
  Require(unit_scale > 0, "unit_scale", "a positive scale");
  Require(up_axis == "auto" || up_axis == "y" || up_axis == "z", "up_axis",
          "\"auto\", \"y\" or \"z\"");
  Require(split == "nodes" || split == "single", "split", "\"nodes\" or \"single\"");
  Require(points_per_part >= 0, "points_per_part", "a non-negative count");
}

namespace {

bool HasGeometry(const ImportedNode& n) {
  if (!n.meshes.empty()) return true;
  for (const auto& c : n.children)
    if (HasGeometry(c)) return true;
  return false;
}

void CollectMeshes(const ImportedNode& n, std::vector<const ImportedMesh*>* out) {
  for (const auto& m : n.meshes) out->push_back(&m);
  for (const auto& c : n.children) CollectMeshes(c, out);
}

// Z-up frame conversion for the file.
Eigen::Isometry3d UpAxisTransform(const std::filesystem::path& path, const MeshLoadOptions& o,
                                  char hint) {
  std::string up = o.up_axis;
  if (up == "auto") {
    if (hint == 'y' || hint == 'z') {
      up = std::string(1, hint);
    } else {
      const std::string ext = internal::LowerExtension(path);
      up = (ext == ".blend" || ext == ".ply" || ext == ".stl" || ext == ".off") ? "z" : "y";
    }
  }
  return up == "y" ? internal::YUpToZUp() : Eigen::Isometry3d::Identity();
}

// Rigid part of an affine node transform (Gram–Schmidt on the columns; scale dropped).
Eigen::Isometry3d RigidPart(const Eigen::Affine3d& X) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d R = X.linear();
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < c; ++k) R.col(c) -= R.col(k).dot(R.col(c)) * R.col(k);
    const double n = R.col(c).norm();
    if (n < 1e-12) return out;
    R.col(c) /= n;
  }
  if (R.determinant() < 0) R.col(2) *= -1;
  out.linear() = R;
  out.translation() = X.translation();
  return out;
}

std::string PartNameOf(const ImportedMesh& m, const std::string& node_name) {
  if (!m.material.empty() && m.material != "DefaultMaterial") return NormalizeName(m.material);
  if (!m.name.empty()) return NormalizeName(m.name);
  return node_name.empty() ? "body" : NormalizeName(node_name);
}

Object MakeObject(const std::string& name, const std::vector<const ImportedMesh*>& meshes,
                  const Eigen::Isometry3d& C, const Eigen::Affine3d& X_FN,
                  const std::string& source) {
  Object o;
  o.instance = name;
  o.source = source;
  const Eigen::Affine3d Ca(C.matrix());
  for (const ImportedMesh* m : meshes) {
    Part p;
    p.name = PartNameOf(*m, name);
    p.id = static_cast<int>(o.parts.size());
    p.mesh = m->mesh.Transformed(Ca);
    o.parts.push_back(std::move(p));
  }
  o.X_WO = C * RigidPart(X_FN);
  o.scale = X_FN.linear().colwise().norm().transpose();
  return o;
}

// Descends through wrapper nodes (a single child and no meshes) that many exporters add.
const ImportedNode& SceneRoot(const ImportedNode& root) {
  const ImportedNode* n = &root;
  while (n->meshes.empty() && n->children.size() == 1 && !n->children[0].children.empty())
    n = &n->children[0];
  return *n;
}

}  // namespace

Scene LoadMeshScene(const std::filesystem::path& path, const MeshLoadOptions& options) {
  ValidateConfig(options, "mesh load options for " + path.string());
  char hint = 0;
  const ImportedNode root = internal::ImportWithAssimp(path, options.unit_scale, &hint);
  const Eigen::Isometry3d C = UpAxisTransform(path, options, hint);
  const CategoryTable table = options.category_table.empty()
                                  ? CategoryTable()
                                  : CategoryTable::Load(options.category_table);
  Scene scene;
  scene.name = path.stem().string();
  const std::string source = path.string();
  auto classify_and_add = [&](const std::string& name, std::vector<const ImportedMesh*> meshes,
                              const Eigen::Affine3d& X_FN) {
    if (meshes.empty()) return;
    const CategoryTable::Match m = table.Classify(name);
    if (m.kind == CategoryTable::Kind::kIgnore) return;
    Object o = MakeObject(name, meshes, C, X_FN, source + ":" + name);
    if (m.kind == CategoryTable::Kind::kStructure) {
      for (const auto& p : o.parts) scene.walls.Append(p.mesh);
      return;
    }
    o.category = m.kind == CategoryTable::Kind::kObject ? m.category : options.category;
    o.important = m.kind == CategoryTable::Kind::kObject ? m.important : true;
    scene.AddObject(std::move(o));
  };
  if (options.split == "single") {
    std::vector<const ImportedMesh*> meshes;
    CollectMeshes(root, &meshes);
    classify_and_add(path.stem().string(), meshes, Eigen::Affine3d::Identity());
  } else {
    const ImportedNode& top = SceneRoot(root);
    std::vector<const ImportedMesh*> own;
    for (const auto& m : top.meshes) own.push_back(&m);
    classify_and_add(top.name.empty() ? path.stem().string() : top.name, own, top.X_WN);
    for (const auto& child : top.children) {
      if (!HasGeometry(child)) continue;
      std::vector<const ImportedMesh*> meshes;
      // Children that are helpers (e.g. bounding boxes) can be ignored by name.
      std::function<void(const ImportedNode&)> collect = [&](const ImportedNode& n) {
        if (&n != &child && table.Classify(n.name).kind == CategoryTable::Kind::kIgnore) return;
        for (const auto& m : n.meshes) meshes.push_back(&m);
        for (const auto& c : n.children) collect(c);
      };
      collect(child);
      classify_and_add(child.name, meshes, child.X_WN);
    }
  }
  if (scene.objects.empty() && scene.walls.empty())
    ThrowInputError(source, "", "a file with triangle meshes", "no triangles");
  if (options.drop_to_floor) {
    const Aabb b = scene.Bounds();
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation().z() = -b.min.z();
    for (auto& o : scene.objects) o.ApplyTransform(X);
    scene.walls.Transform(Eigen::Affine3d(X.matrix()));
  }
  internal::SampleScenePoints(&scene, options.points_per_part);
  return scene;
}

TriangleMesh LoadTriangleMesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
  ValidateConfig(options, "mesh load options for " + path.string());
  char hint = 0;
  const ImportedNode root = internal::ImportWithAssimp(path, options.unit_scale, &hint);
  const Eigen::Affine3d C(UpAxisTransform(path, options, hint).matrix());
  std::vector<const ImportedMesh*> meshes;
  CollectMeshes(root, &meshes);
  TriangleMesh out;
  for (const auto* m : meshes) out.Append(m->mesh.Transformed(C));
  if (out.empty())
    ThrowInputError(path.string(), "", "a file with triangle meshes", "no triangles");
  return out;
}

std::filesystem::path MorseDataDir() {
  const std::filesystem::path& dir = InstalledEnvironment().morse_dir;
  return dir.empty() ? std::filesystem::path("/usr/share/morse/data") : dir;
}

Scene LoadMorseScene(const std::filesystem::path& blend_path) {
  if (!std::filesystem::exists(blend_path))
    ThrowInputError(blend_path.string(), "",
                    "the MORSE data file (Debian package morse-simulator-data; set "
                    "SIMS_MORSE_DIR if it lives elsewhere)",
                    "no such file");
  MeshLoadOptions o;
  o.up_axis = "z";
  o.category_table = ConfigPath("scene/morse_categories.json").string();
  return LoadMeshScene(blend_path, o);
}

Scene LoadMorseFurniture() {
  Scene s = LoadMorseScene(MorseDataDir() / "props" / "furnitures.blend");
  s.name = "morse_furniture";
  return s;
}

Scene LoadMorseApartment() {
  Scene s = LoadMorseScene(MorseDataDir() / "environments" / "apartment.blend");
  s.name = "morse_apartment";
  return s;
}

}  // namespace sims::scene
