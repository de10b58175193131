// index_layouts: builds the layout database (scene graphs of built-in rooms and house, the MORSE
// apartment and 3D-FRONT houses) that plan_story retrieves layouts from.
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/environment.h"
#include "sims/core/error.h"
#include "sims/planner/planner.h"

int main(int argc, char** argv) {
  CLI::App app{"Index layouts (scene graphs) into a database JSON for plan_story --layouts"};
  std::string out = "layouts.json", config, future_dir;
  std::vector<std::string> front3d;
  bool no_builtin = false, no_morse = false;
  sims::AppFlags flags;
  app.add_option("--out", out, "database file to write");
  app.add_option("--front3d", front3d, "3D-FRONT folder(s) or house JSON file(s)");
  app.add_option("--future-dir", future_dir, "3D-FUTURE-model folder (default $SIMS_FUTURE_DIR)");
  app.add_flag("--no-builtin", no_builtin, "skip the built-in rooms and house");
  app.add_flag("--no-morse", no_morse, "skip the MORSE apartment");
  app.add_option("--config", config, "planner config (layout.graph settings)");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    if (future_dir.empty()) future_dir = sims::InstalledEnvironment().future_dir.string();
    sims::planner::PlannerConfig cfg = sims::planner::LoadPlannerConfig(config);
    std::vector<std::filesystem::path> dirs(front3d.begin(), front3d.end());
    std::vector<std::string> log;
    sims::planner::LayoutDatabase db = sims::planner::BuildLayoutDatabase(
        !no_builtin, !no_morse, dirs, future_dir, cfg.layout, &log);
    for (const std::string& line : log) std::cout << line << "\n";
    if (db.layouts.empty()) throw sims::Error("index_layouts: nothing was indexed");
    db.Save(out);
    std::cout << "wrote " << db.layouts.size() << " layouts to " << out << "\n";
    return 0;
  });
}
