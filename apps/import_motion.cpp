// import_motion: converts BVH files into the project's clip format (retargeted onto the
// humanoid), one file or a whole dataset described by configs/datasets/<name>.json, and
// prints one summary line per clip. Malformed input exits non-zero with a clear message.
#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/motion/import.h"

int main(int argc, char** argv) {
  CLI::App app{"Import BVH motion (retarget onto the humanoid) into clips + manifest.json"};
  std::string bvh, dataset, root, out;
  sims::motion::ImportOptions o;
  std::string map = sims::ConfigPath("retarget/cmu.json").string();
  bool keep_going = false;
  sims::AppFlags flags;
  app.add_option("input", bvh, "BVH file to import");
  app.add_option("--dataset", dataset,
                 "dataset config (configs/datasets/<name>.json) instead of one file");
  app.add_option("--root", root, "dataset folder (overrides the config's root)");
  app.add_option("--map", map, "retarget map (configs/retarget/<name>.json)");
  app.add_option("--out", out, "output folder (clips + manifest.json)");
  app.add_option("--name", o.name, "clip name (default: file stem)");
  app.add_option("--caption", o.captions, "caption (repeat for up to 5 synonyms)");
  app.add_option("--skill", o.skill, "skill label (walk, sit, lie, reach, getup, idle, other)");
  app.add_option(
      "--emotion", o.emotion,
      "emotion label (neutral, happy, angry, hurried, tired, sad, stressed, drunk, relaxed)");
  app.add_option("--furniture", o.furniture, "suitable furniture categories");
  app.add_option("--weight", o.weight, "sampling weight in the manifest")
      ->check(CLI::PositiveNumber);
  app.add_flag("--keep-going", keep_going, "dataset mode: skip files that fail and report them");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    if (bvh.empty() == dataset.empty())
      throw sims::Error("import_motion: give either a BVH file or --dataset");
    if (!dataset.empty()) {
      int failures = 0;
      for (const auto& s : sims::motion::ImportDataset(dataset, root, out, keep_going, &failures))
        std::printf("%s\n", s.Line().c_str());
      return failures > 0 ? 2 : 0;  // 2: some files failed and were skipped (--keep-going)
    }
    o.map = map;
    const auto s = sims::motion::ImportBvhFile(bvh, out.empty() ? "clips" : out, o);
    std::printf("%s\n", s.Line().c_str());
    return 0;
  });
}
