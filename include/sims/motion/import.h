// Importing BVH files into the clip format: one file (import_motion in.bvh --map ...), or a
// whole dataset folder described by configs/datasets/<name>.json (file pattern, retarget
// map, caption templates and per-file rules for skill/emotion/captions). Every import writes
// `<out>/<name>.json/.bin` and adds the clip to `<out>/manifest.json`.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/motion/motion_library.h"
#include "sims/motion/retarget.h"

namespace sims::motion {

/// Labels and settings of a single-file import.
struct ImportOptions {
  std::filesystem::path map;           ///< Retarget map (configs/retarget/<name>.json).
  std::string name;                    ///< Clip name (default: the file stem, sanitised).
  std::vector<std::string> captions;   ///< Captions (up to 5).
  std::string skill = "other";         ///< Skill label.
  std::string emotion = "neutral";     ///< Emotion label.
  std::vector<std::string> furniture;  ///< Furniture categories.
  double weight = 1.0;                 ///< Manifest sampling weight.
};

/// One line of import output.
struct ImportSummary {
  std::string name;                   ///< Clip name.
  std::filesystem::path output;       ///< Written clip JSON.
  int frames = 0;                     ///< Output frames.
  double fps = 0;                     ///< Output frame rate.
  double duration = 0;                ///< Seconds.
  double source_fps = 0;              ///< Frame rate of the BVH.
  std::vector<std::string> warnings;  ///< Clamped joints and other notes.
  /// "name: 688 frames @ 30 fps, 22.9 s[, warnings: ...]".
  std::string Line() const;
};

/// Retargets one BVH file, writes the clip into `out_dir` and adds it to the manifest there.
/// Malformed BVH or maps throw sims::Error naming the file.
ImportSummary ImportBvhFile(const std::filesystem::path& bvh, const std::filesystem::path& out_dir,
                            const ImportOptions& options);

/// A per-file rule of a dataset config; every rule whose regex matches the file's path
/// (relative to the dataset root, '/' separators) applies, later ones overriding.
struct DatasetRule {
  std::string match;                        ///< ECMAScript regex searched in the relative path.
  bool skip = false;                        ///< Do not import matching files.
  std::string skill;                        ///< Skill label (empty = unchanged).
  std::string emotion;                      ///< Emotion label (empty = unchanged).
  std::vector<std::string> captions;        ///< Caption templates replacing the defaults.
  std::vector<std::string> furniture;       ///< Furniture categories.
  std::map<std::string, std::string> vars;  ///< Template variables.
  double weight = 0;                        ///< Sampling weight (0 = unchanged).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(match));
    a->Visit(SIMS_NVP(skip));
    a->Visit(SIMS_NVP(skill));
    a->Visit(SIMS_NVP(emotion));
    a->Visit(SIMS_NVP(captions));
    a->Visit(SIMS_NVP(furniture));
    a->Visit(SIMS_NVP(vars));
    a->Visit(SIMS_NVP(weight));
  }
  /// Checks the regex and labels.
  void Validate() const;
};

/// How to import a dataset (configs/datasets/<name>.json).
struct DatasetConfig {
  std::string name;               ///< Dataset name (clip name prefix).
  std::string description;        ///< Free text (where to get it, licence).
  std::string root;               ///< Dataset folder (relative to the project root, or absolute).
  std::string pattern = "*.bvh";  ///< File-name glob (* and ?).
  bool recursive = true;          ///< Search subfolders.
  double source_fps = 0;          ///< Expected BVH frame rate (0 = any); others warn.
  std::string retarget;           ///< Retarget map, relative to configs/ (or absolute).
  std::string output;             ///< Output folder (relative to the project root).
  std::string default_skill = "other";      ///< Skill when no rule sets one.
  std::string default_emotion = "neutral";  ///< Emotion when no rule sets one.
  std::vector<std::string>
      captions;  ///< Caption templates ({stem}, {dir}, {stem_words}, {dir_words}, vars).
  std::map<std::string, std::string> vars;  ///< Default template variables.
  std::vector<DatasetRule> rules;           ///< Per-file rules.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(description));
    a->Visit(SIMS_NVP(root));
    a->Visit(SIMS_NVP(pattern));
    a->Visit(SIMS_NVP(recursive));
    a->Visit(SIMS_NVP(source_fps));
    a->Visit(SIMS_NVP(retarget));
    a->Visit(SIMS_NVP(output));
    a->Visit(SIMS_NVP(default_skill));
    a->Visit(SIMS_NVP(default_emotion));
    a->Visit(SIMS_NVP(captions));
    a->Visit(SIMS_NVP(vars));
    a->Visit(SIMS_NVP(rules));
  }
  /// Checks names, labels and paths.
  void Validate() const;
};

/// The labels a dataset config gives one file (relative path with '/' separators); `skip`
/// is set when a rule excludes it.
ImportOptions DatasetFileOptions(const DatasetConfig& config, const std::string& relative_path,
                                 bool* skip);

/// Imports every matching file of a dataset. `root` / `out_dir` override the config's when
/// non-empty. Files that fail are reported (with the error as a warning) and skipped when
/// `keep_going`, else the first error is thrown.
std::vector<ImportSummary> ImportDataset(const std::filesystem::path& config_path,
                                         const std::filesystem::path& root,
                                         const std::filesystem::path& out_dir, bool keep_going,
                                         int* failures = nullptr);

/// Splits "ArmsBehindBack_FW" into "arms behind back fw".
std::string ToWords(const std::string& s);

/// Adds or replaces (same file) an entry of `<dir>/manifest.json`, creating it if needed.
void AddToManifest(const std::filesystem::path& manifest, const ManifestEntry& entry);

}  // namespace sims::motion
