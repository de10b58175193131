// make_synthetic_motions: writes the procedural (clearly labelled synthetic) motion clips
// and their manifest, the default training data when no motion-capture dataset is present.
#include <chrono>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"
#include "sims/motion/synthetic.h"
#include "sims/motion/synthetic_catalog.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Generate the synthetic motion clips (walk, idle, sit, lie, reach, getup) + manifest"};
  sims::motion::SyntheticOptions options;
  std::string out = sims::DataPath("motions/synthetic").string();
  std::string catalog = sims::motion::DefaultSyntheticCatalogPath().string();
  bool check = false;
  sims::AppFlags flags;
  app.add_option("--out", out, "output folder (clips + manifest.json)");
  app.add_option("--catalog", catalog, "recipe catalogue (JSON)");
  app.add_option("--seed", options.seed, "random seed");
  app.add_option("--variants", options.variants, "random variants per recipe")
      ->check(CLI::Range(1, 20));
  app.add_option("--fps", options.fps, "frame rate")->check(CLI::PositiveNumber);
  app.add_option("--skills", options.skills,
                 "only these skills (walk, idle, sit, lie, reach, getup)");
  app.add_flag("--check", check, "measure every clip (limits, floor, self-contact, foot sliding)");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    const auto start = std::chrono::steady_clock::now();
    const auto clips =
        sims::motion::GenerateSyntheticClips(sims::motion::LoadSyntheticCatalog(catalog), options);
    const auto manifest = sims::motion::WriteMotionDataset(
        clips, out,
        "SIMS synthetic clips (procedural, not motion capture), seed " +
            std::to_string(options.seed));
    double seconds = 0;
    for (const auto& c : clips) seconds += c.duration();
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    spdlog::info("wrote {} clips ({:.0f} s of motion) and {} in {:.1f} s", clips.size(), seconds,
                 manifest.string(), took);
    if (check) {
      for (const auto& c : clips) {
        const auto q = sims::motion::MeasureClipQuality(c);
        spdlog::info(
            "{:32s} sole {:+.4f} m, floor pen {:.4f} m, self pen {:.4f} m, limit {:.4f} rad, slide "
            "{:.3f} m/s",
            c.meta().name, q.min_sole_height, q.max_floor_penetration, q.max_self_penetration,
            q.max_limit_excess, q.max_stance_slide);
      }
    }
    return 0;
  });
}
