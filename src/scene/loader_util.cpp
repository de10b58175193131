#include "scene/loader_util.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/scene/loaders.h"

namespace sims::scene {

namespace internal {

namespace {

Eigen::Affine3d ToEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d M;
  M << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return Eigen::Affine3d(M);
}

ImportedNode Convert(const aiScene* scene, const aiNode* node, const Eigen::Affine3d& G_parent,
                     double unit_scale) {
  ImportedNode out;
  out.name = node->mName.C_Str();
  const Eigen::Affine3d G = G_parent * ToEigen(node->mTransformation);  // file units
  const Eigen::Affine3d X = Eigen::Scaling(unit_scale) * G;             // metres
  out.X_WN = X;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const aiMesh* m = scene->mMeshes[node->mMeshes[i]];
    ImportedMesh im;
    im.name = m->mName.C_Str();
    if (m->mMaterialIndex < scene->mNumMaterials) {
      aiString name;
      if (scene->mMaterials[m->mMaterialIndex]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS)
        im.material = name.C_Str();
    }
    im.mesh.vertices.reserve(m->mNumVertices);
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D& p = m->mVertices[v];
      im.mesh.vertices.push_back(X * Eigen::Vector3d(p.x, p.y, p.z));
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;
      im.mesh.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
    }
    // Mirroring node transforms flip the winding; keep triangles outward-facing.
    if (X.linear().determinant() < 0)
      for (auto& t : im.mesh.triangles) std::swap(t[1], t[2]);
    if (!im.mesh.empty()) out.meshes.push_back(std::move(im));
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    out.children.push_back(Convert(scene, node->mChildren[c], G, unit_scale));
  return out;
}

}  // namespace

ImportedNode ImportWithAssimp(const std::filesystem::path& path, double unit_scale,
                              char* up_axis_hint) {
  if (!std::filesystem::exists(path))
    ThrowInputError(path.string(), "", "an existing mesh file", "no such file");
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // Assimp 5.2's PLY importer loops without end or aborts on some malformed files (fuzzer
  // findings): PLY goes through our own reader.
  if (ext == ".ply") {
    ImportedNode root;
    root.name = path.stem().string();
    root.X_WN = Eigen::Affine3d(Eigen::Scaling(unit_scale));
    const TriangleMesh ply = ReadPly(path);
    ImportedMesh im;
    im.name = root.name;
    for (const auto& v : ply.vertices) im.mesh.vertices.push_back(unit_scale * v);
    // As Assimp's FindDegenerates: no triangles that repeat a vertex.
    for (const auto& t : ply.triangles)
      if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) im.mesh.triangles.push_back(t);
    if (!im.mesh.empty()) root.meshes.push_back(std::move(im));
    if (up_axis_hint) *up_axis_hint = 0;
    return root;
  }
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer.SetPropertyBool(AI_CONFIG_FBX_CONVERT_TO_M, true);
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                           aiProcess_SortByPType | aiProcess_FindDegenerates);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    ThrowInputError(path.string(), "", "a mesh file Assimp can read", importer.GetErrorString());
  if (up_axis_hint) {
    *up_axis_hint = 0;
    int axis = -1;
    if (scene->mMetaData && scene->mMetaData->Get("UpAxis", axis) && axis >= 0 && axis <= 2)
      *up_axis_hint = static_cast<char>('x' + axis);
  }
  ImportedNode root = Convert(scene, scene->mRootNode, Eigen::Affine3d::Identity(), unit_scale);
  return root;
}

Eigen::Isometry3d YUpToZUp() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  return X;
}

const nlohmann::json& JsonField(const nlohmann::json& j, const std::string& key,
                                const std::string& source, const std::string& path,
                                const std::string& expected) {
  const std::string field = path.empty() ? key : path + "." + key;
  if (!j.is_object()) ThrowInputError(source, path, "an object", j.type_name());
  auto it = j.find(key);
  if (it == j.end()) ThrowInputError(source, field, expected, "missing");
  return *it;
}

std::vector<double> NumberArray(const nlohmann::json& j, int n, const std::string& source,
                                const std::string& path) {
  const std::string expected =
      n >= 0 ? "an array of " + std::to_string(n) + " numbers"
             : "an array of numbers (a multiple of " + std::to_string(-n) + ")";
  if (!j.is_array()) ThrowInputError(source, path, expected, j.type_name());
  if ((n >= 0 && static_cast<int>(j.size()) != n) || (n < 0 && j.size() % (-n) != 0))
    ThrowInputError(source, path, expected, std::to_string(j.size()) + " values");
  std::vector<double> out;
  out.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number())
      ThrowInputError(source, path + "[" + std::to_string(i) + "]", "a number", j[i].dump());
    out.push_back(j[i].get<double>());
  }
  return out;
}

nlohmann::json ReadJson(const std::filesystem::path& path) { return ReadJsonFile(path); }

void SampleScenePoints(Scene* scene, int points_per_part, uint64_t seed) {
  for (std::size_t i = 0; i < scene->objects.size(); ++i) {
    Rng rng(seed + i);
    scene->objects[i].ResamplePoints(rng, points_per_part);
  }
}

void SetPoseFromBounds(Object* object) {
  const Aabb b = object->Bounds();
  if (b.empty()) return;
  object->X_WO = Eigen::Isometry3d::Identity();
  object->X_WO.translation() = Eigen::Vector3d(b.center().x(), b.center().y(), b.min.z());
}

std::string LowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace internal

// ---------------------------------------------------------------------------------------------
// CategoryTable

struct CategoryTable::Impl {
  struct Rule {
    std::regex re;
    std::string category;
    bool important = true;
  };
  std::vector<Rule> rules;
  std::vector<std::regex> structure, ignore;
};

CategoryTable::CategoryTable() : impl_(std::make_shared<Impl>()) {}

CategoryTable CategoryTable::Load(const std::filesystem::path& path) {
  return FromJson(ReadJsonFile(path), path.string());
}

CategoryTable CategoryTable::FromJson(const nlohmann::json& j, const std::string& source) {
  auto impl = std::make_shared<Impl>();
  if (!j.is_object()) ThrowInputError(source, "", "a JSON object", j.type_name());
  auto compile = [&](const nlohmann::json& p, const std::string& field) {
    if (!p.is_string()) ThrowInputError(source, field, "a regular expression string", p.dump());
    try {
      return std::regex(p.get<std::string>(), std::regex::ECMAScript | std::regex::icase);
    } catch (const std::regex_error& e) {
      ThrowInputError(source, field, "a valid regular expression", p.get<std::string>());
    }
  };
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() != "categories" && it.key() != "structure" && it.key() != "ignore" &&
        it.key() != "description")
      ThrowInputError(source, it.key(), "one of categories, structure, ignore, description",
                      "unknown key");
  }
  if (j.contains("categories")) {
    const auto& rules = j["categories"];
    if (!rules.is_array()) ThrowInputError(source, "categories", "an array", rules.type_name());
    for (std::size_t i = 0; i < rules.size(); ++i) {
      const std::string field = "categories[" + std::to_string(i) + "]";
      const auto& r = rules[i];
      Impl::Rule rule;
      rule.re = compile(internal::JsonField(r, "pattern", source, field, "a pattern"),
                        field + ".pattern");
      const auto& cat = internal::JsonField(r, "category", source, field, "a category name");
      if (!cat.is_string() || cat.get<std::string>().empty())
        ThrowInputError(source, field + ".category", "a non-empty string", cat.dump());
      rule.category = cat.get<std::string>();
      if (r.contains("important")) {
        if (!r["important"].is_boolean())
          ThrowInputError(source, field + ".important", "true or false", r["important"].dump());
        rule.important = r["important"].get<bool>();
      }
      impl->rules.push_back(std::move(rule));
    }
  }
  for (const char* key : {"structure", "ignore"}) {
    if (!j.contains(key)) continue;
    const auto& list = j[key];
    if (!list.is_array()) ThrowInputError(source, key, "an array of patterns", list.type_name());
    for (std::size_t i = 0; i < list.size(); ++i) {
      auto re = compile(list[i], std::string(key) + "[" + std::to_string(i) + "]");
      (std::string(key) == "structure" ? impl->structure : impl->ignore).push_back(std::move(re));
    }
  }
  CategoryTable t;
  t.impl_ = std::move(impl);
  return t;
}

CategoryTable::Match CategoryTable::Classify(const std::string& name) const {
  Match m;
  for (const auto& re : impl_->ignore)
    if (std::regex_search(name, re)) {
      m.kind = Kind::kIgnore;
      return m;
    }
  for (const auto& re : impl_->structure)
    if (std::regex_search(name, re)) {
      m.kind = Kind::kStructure;
      return m;
    }
  for (const auto& r : impl_->rules)
    if (std::regex_search(name, r.re)) {
      m.kind = Kind::kObject;
      m.category = r.category;
      m.important = r.important;
      return m;
    }
  return m;
}

bool CategoryTable::empty() const {
  return impl_->rules.empty() && impl_->structure.empty() && impl_->ignore.empty();
}

}  // namespace sims::scene
