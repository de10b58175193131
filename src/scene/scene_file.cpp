// LoadSceneFile: one entry point that picks the loader by extension and content.
#include "scene/loader_util.h"
#include "sims/core/environment.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/scene/builtin.h"
#include "sims/scene/loaders.h"

namespace sims::scene {

namespace {

std::filesystem::path Or(const std::filesystem::path& setting,
                         const std::filesystem::path& fallback) {
  return setting.empty() ? fallback : setting;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

ScenePlanRef ParseScenePlanRef(const std::string& ref) {
  if (const auto hash = ref.rfind('#'); hash != std::string::npos && !std::filesystem::exists(ref))
    return {ref.substr(0, hash), ref.substr(hash + 1)};
  return {ref, ""};
}

std::filesystem::path DefaultPartNetRoot() {
  return Or(InstalledEnvironment().partnet_dir, DataPath("partnet"));
}

Scene LoadSceneFile(const std::string& spec) {
  namespace fs = std::filesystem;
  if (spec.rfind("builtin:", 0) == 0) return BuiltinScene(spec.substr(8));
  const auto [path, fragment] = ParseScenePlanRef(spec);
  if (!fs::exists(path)) {
    // Not a file: a built-in name, or a clear error listing both options.
    if (path.extension().empty() && path.parent_path().empty()) return BuiltinScene(spec);
    ThrowInputError(spec, "", "an existing scene file or folder, or a built-in scene name",
                    "no such file");
  }
  if (fs::is_directory(path)) {
    if (fs::exists(path / "result.json")) {
      Scene s;
      s.name = path.filename().string();
      s.AddObject(LoadPartNet(path));
      return s;
    }
    return LoadScanNet(path);
  }
  const std::string ext = internal::LowerExtension(path);
  if (ext == ".json") {
    const nlohmann::json j = internal::ReadJson(path);
    if (j.is_object() && j.contains("furniture") && j.contains("scene")) {
      const fs::path future = Or(InstalledEnvironment().future_dir,
                                 path.parent_path().parent_path() / "3D-FUTURE-model");
      return LoadFront3D(path, future);
    }
    if (j.is_object() && !j.empty() && j.begin()->is_object() && j.begin()->contains("obj"))
      return LoadScenePlan(path, DefaultPartNetRoot(), fragment);
    ThrowInputError(path.string(), "",
                    "a 3D-FRONT house (furniture, mesh, scene) or a UniHSI ScenePlan "
                    "({plan_id: {obj: ...}})",
                    "a JSON file of neither kind");
  }
  if (ext == ".ply" && EndsWith(path.filename().string(), "_vh_clean_2.ply"))
    return LoadScanNet(path);
  if (ext == ".blend") return LoadMorseScene(path);
  return LoadMeshScene(path);
}

}  // namespace sims::scene
