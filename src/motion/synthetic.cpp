#include "sims/motion/synthetic.h"

#include "motion/synthetic_internal.h"
#include "sims/core/error.h"
#include "sims/core/rng.h"

namespace sims::motion {

void SyntheticOptions::Validate() const {
  Require(fps > 0, "fps", "a positive frame rate");
  Require(variants >= 1 && variants <= 20, "variants", "between 1 and 20");
  for (const auto& s : skills)
    Require(IsSkillLabel(s), "skills", "known skill labels (walk, sit, lie, reach, getup, idle)");
}

std::filesystem::path WriteMotionDataset(const std::vector<MotionClip>& clips,
                                         const std::filesystem::path& dir,
                                         const std::string& description) {
  MotionManifest manifest;
  manifest.description = description;
  for (const MotionClip& c : clips) {
    SIMS_CHECK(!c.meta().name.empty());
    SaveClip(c, dir / (c.meta().name + ".json"));
    ManifestEntry e;
    e.file = c.meta().name + ".json";
    e.weight = c.meta().skill == "walk" ? 2.0 : 1.0;
    manifest.clips.push_back(e);
  }
  const auto path = dir / "manifest.json";
  SaveManifest(path, manifest);
  return path;
}

}  // namespace sims::motion
