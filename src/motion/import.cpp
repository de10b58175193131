#include "sims/motion/import.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <exception>
#include <optional>
#include <regex>

#include <spdlog/spdlog.h>

#include "sims/core/error.h"
#include "sims/core/paths.h"

namespace sims::motion {

namespace fs = std::filesystem;

namespace {

std::string Sanitize(const std::string& s) {
  std::string out;
  for (char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    out += std::isalnum(u) ? static_cast<char>(std::tolower(u)) : '_';
  }
  while (out.find("__") != std::string::npos) out.replace(out.find("__"), 2, "_");
  if (!out.empty() && out.front() == '_') out.erase(0, 1);
  if (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() ? "clip" : out;
}

bool GlobMatch(const char* p, const char* s) {
  if (*p == '\0') return *s == '\0';
  if (*p == '*') return GlobMatch(p + 1, s) || (*s && GlobMatch(p, s + 1));
  if (*s && (*p == '?' || *p == *s)) return GlobMatch(p + 1, s + 1);
  return false;
}

std::string Fill(std::string t, const std::map<std::string, std::string>& vars) {
  // Variables may refer to the built-ins, so substitute twice.
  for (int pass = 0; pass < 2; ++pass)
    for (const auto& [k, v] : vars) {
      const std::string key = "{" + k + "}";
      for (std::size_t p = t.find(key); p != std::string::npos; p = t.find(key, p + v.size()))
        t.replace(p, key.size(), v);
    }
  return t;
}

fs::path ResolveProjectPath(const std::string& p) {
  const fs::path path(p);
  return path.is_absolute() ? path : ProjectRoot() / path;
}

// Replaces the manifest entry of the same file, or appends it.
void UpsertEntry(MotionManifest* m, const ManifestEntry& entry) {
  auto it = std::find_if(m->clips.begin(), m->clips.end(),
                         [&](const ManifestEntry& e) { return e.file == entry.file; });
  if (it != m->clips.end())
    *it = entry;
  else
    m->clips.push_back(entry);
}

// ImportBvhFile without the manifest update, with the retarget map already loaded.
ImportSummary ImportWithMap(const fs::path& bvh_path, const fs::path& out_dir,
                            const ImportOptions& options, const RetargetConfig& map,
                            ManifestEntry* entry) {
  const BvhMotion bvh = ReadBvh(bvh_path);
  RetargetReport report;
  MotionClip clip = RetargetBvh(bvh, map, HumanoidSkeleton::Default(), &report, bvh_path.string());
  MotionMeta& meta = clip.mutable_meta();
  meta.name = options.name.empty() ? Sanitize(bvh_path.stem().string()) : Sanitize(options.name);
  meta.captions = options.captions;
  meta.skill = options.skill;
  meta.emotion = options.emotion;
  meta.furniture = options.furniture;
  meta.source = bvh_path.string() + " (retarget map " + map.name + ")";
  meta.params["retarget_scale"] = report.scale;
  meta.params["source_fps"] = report.source_fps;
  meta.params["ground_shift"] = report.ground_shift;
  ValidateConfig(meta, "import of " + bvh_path.string());

  const fs::path json = out_dir / (meta.name + ".json");
  SaveClip(clip, json);
  entry->file = json.filename().string();
  entry->weight = options.weight;

  ImportSummary s;
  s.name = meta.name;
  s.output = json;
  s.frames = clip.num_frames();
  s.fps = clip.fps();
  s.duration = clip.duration();
  s.source_fps = report.source_fps;
  s.warnings = report.warnings;
  return s;
}

}  // namespace

std::string ImportSummary::Line() const {
  char buf[256];
  std::snprintf(buf, sizeof(buf), "%s: %d frames @ %g fps, %.2f s", name.c_str(), frames, fps,
                duration);
  std::string out = buf;
  if (!warnings.empty()) {
    out += ", warnings: ";
    for (std::size_t i = 0; i < warnings.size(); ++i) out += (i ? "; " : "") + warnings[i];
  }
  return out;
}

std::string ToWords(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const bool boundary =
        i > 0 && std::isupper(c) &&
        (std::islower(static_cast<unsigned char>(s[i - 1])) ||
         (i + 1 < s.size() && std::islower(static_cast<unsigned char>(s[i + 1])) &&
          std::isupper(static_cast<unsigned char>(s[i - 1]))));
    if (c == '_' || c == '-' || c == ' ') {
      if (!out.empty() && out.back() != ' ') out += ' ';
      continue;
    }
    if (boundary && !out.empty() && out.back() != ' ') out += ' ';
    out += static_cast<char>(std::tolower(c));
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

void AddToManifest(const fs::path& manifest_path, const ManifestEntry& entry) {
  MotionManifest m;
  if (fs::exists(manifest_path)) m = LoadManifest(manifest_path);
  UpsertEntry(&m, entry);
  SaveManifest(manifest_path, m);
}

ImportSummary ImportBvhFile(const fs::path& bvh_path, const fs::path& out_dir,
                            const ImportOptions& options) {
  if (options.map.empty())
    ThrowInputError("import_motion", "--map", "a retarget map (configs/retarget/<dataset>.json)");
  const RetargetConfig map = LoadRetargetConfig(options.map);
  ManifestEntry e;
  ImportSummary s = ImportWithMap(bvh_path, out_dir, options, map, &e);
  AddToManifest(out_dir / "manifest.json", e);
  return s;
}

void DatasetRule::Validate() const {
  Require(!match.empty(), "match", "a regular expression");
  try {
    std::regex re(match, std::regex::ECMAScript);
  } catch (const std::regex_error&) {
    Require(false, "match", "a valid ECMAScript regular expression");
  }
  Require(skill.empty() || IsSkillLabel(skill), "skill", "a known skill label");
  Require(emotion.empty() || IsEmotionLabel(emotion), "emotion", "one of the 9 emotion labels");
  Require(weight >= 0, "weight", "a non-negative weight");
}

void DatasetConfig::Validate() const {
  Require(!name.empty(), "name", "a dataset name");
  Require(!retarget.empty(), "retarget", "a retarget map path (relative to configs/)");
  Require(!pattern.empty(), "pattern", "a file-name glob such as *.bvh");
  Require(source_fps >= 0, "source_fps", "a frame rate, or 0 for any");
  Require(IsSkillLabel(default_skill), "default_skill", "a known skill label");
  Require(IsEmotionLabel(default_emotion), "default_emotion", "one of the 9 emotion labels");
  Require(captions.size() <= 5, "captions", "at most 5 caption templates");
}

ImportOptions DatasetFileOptions(const DatasetConfig& config, const std::string& relative_path,
                                 bool* skip) {
  ImportOptions o;
  o.skill = config.default_skill;
  o.emotion = config.default_emotion;
  std::vector<std::string> templates = config.captions;
  const fs::path rel(relative_path);
  std::map<std::string, std::string> vars = config.vars;
  const std::string stem = rel.stem().string();
  const std::string dir = rel.has_parent_path() ? rel.parent_path().filename().string() : "";
  std::map<std::string, std::string> builtin = {
      {"stem", stem}, {"dir", dir}, {"stem_words", ToWords(stem)}, {"dir_words", ToWords(dir)}};
  *skip = false;
  for (const DatasetRule& r : config.rules) {
    if (!std::regex_search(relative_path, std::regex(r.match, std::regex::ECMAScript))) continue;
    if (r.skip) *skip = true;
    if (!r.skill.empty()) o.skill = r.skill;
    if (!r.emotion.empty()) o.emotion = r.emotion;
    if (!r.captions.empty()) templates = r.captions;
    if (!r.furniture.empty()) o.furniture = r.furniture;
    if (r.weight > 0) o.weight = r.weight;
    for (const auto& [k, v] : r.vars) vars[k] = v;
  }
  for (auto& [k, v] : vars) v = Fill(v, builtin);
  for (const auto& [k, v] : builtin) vars.emplace(k, v);
  for (const std::string& t : templates) {
    std::string c = Fill(t, vars);
    // Collapse doubled spaces left by empty variables.
    while (c.find("  ") != std::string::npos) c.replace(c.find("  "), 2, " ");
    o.captions.push_back(c);
  }
  o.name = Sanitize(config.name + "_" + (dir.empty() ? "" : dir + "_") + stem);
  return o;
}

std::vector<ImportSummary> ImportDataset(const fs::path& config_path, const fs::path& root_override,
                                         const fs::path& out_override, bool keep_going,
                                         int* failures) {
  const DatasetConfig config = LoadConfig<DatasetConfig>(config_path);
  const fs::path root = root_override.empty() ? ResolveProjectPath(config.root) : root_override;
  const fs::path out = out_override.empty() ? ResolveProjectPath(config.output) : out_override;
  const fs::path map = fs::path(config.retarget).is_absolute() ? fs::path(config.retarget)
                                                               : ConfigPath(config.retarget);
  if (!fs::is_directory(root))
    ThrowInputError(config_path.string(), "root",
                    "an existing dataset folder (download the dataset there or pass --root)",
                    root.string());
  std::vector<fs::path> files;
  auto consider = [&](const fs::directory_entry& e) {
    if (e.is_regular_file() &&
        GlobMatch(config.pattern.c_str(), e.path().filename().string().c_str()))
      files.push_back(e.path());
  };
  if (config.recursive)
    for (const auto& e : fs::recursive_directory_iterator(root)) consider(e);
  else
    for (const auto& e : fs::directory_iterator(root)) consider(e);
  std::sort(files.begin(), files.end());
  if (files.empty())
    ThrowInputError(config_path.string(), "pattern",
                    "files matching '" + config.pattern + "' under " + root.string(), "none");
  // The map is read and the manifest written once for all files; a map that fails to load
  // fails every imported file, as loading it per file would.
  std::optional<RetargetConfig> retarget;
  std::exception_ptr map_error;
  try {
    retarget = LoadRetargetConfig(map);
  } catch (...) {
    map_error = std::current_exception();
  }
  const fs::path manifest_path = out / "manifest.json";
  std::optional<MotionManifest> manifest;  // read at the first successful import
  bool manifest_changed = false;
  auto save_manifest = [&] {
    if (manifest_changed) SaveManifest(manifest_path, *manifest);
  };
  std::vector<ImportSummary> out_list;
  int failed = 0;
  for (const fs::path& f : files) {
    const std::string rel = fs::relative(f, root).generic_string();
    bool skip = false;
    ImportOptions o = DatasetFileOptions(config, rel, &skip);
    if (skip) continue;
    try {
      if (map_error) std::rethrow_exception(map_error);
      ManifestEntry entry;
      ImportSummary s = ImportWithMap(f, out, o, *retarget, &entry);
      if (!manifest)
        manifest = fs::exists(manifest_path) ? LoadManifest(manifest_path) : MotionManifest{};
      UpsertEntry(&*manifest, entry);
      manifest_changed = true;
      if (config.source_fps > 0 && std::abs(s.source_fps - config.source_fps) > 0.5)
        s.warnings.push_back("source frame rate differs from the dataset's " +
                             std::to_string(config.source_fps) + " fps");
      out_list.push_back(std::move(s));
    } catch (const Error& e) {
      if (!keep_going) {
        save_manifest();
        throw;
      }
      ++failed;
      ImportSummary s;
      s.name = o.name;
      s.warnings.push_back(std::string("FAILED: ") + e.what());
      out_list.push_back(std::move(s));
    } catch (...) {
      save_manifest();
      throw;
    }
  }
  save_manifest();
  if (failures) *failures = failed;
  return out_list;
}

}  // namespace sims::motion
