// The web viewer: DIR/index.html + viewer.js (from assets/viewer) and the three.js files it
// imports (unpacked from the npm tarball that cmake/setup.sh fetches, three@0.170.0), so a
// story folder plays offline in any browser once served over HTTP (StaticHttpServer,
// apps/serve_viewer). The page reads DIR/motion.json and DIR/scene.glb.
#pragma once

#include <filesystem>

namespace sims::io {

/// npm version of three.js the viewer is written against.
inline constexpr const char* kThreeVersion = "0.170.0";

/// Where the viewer's files come from.
struct ViewerOptions {
  std::filesystem::path assets_dir;     ///< index.html + viewer.js ("" = AssetPath("viewer")).
  std::filesystem::path three_archive;  ///< three-*.tgz ("" = FindThreeArchive()).
};

/// The installed Environment's three_tgz ($SIMS_THREE_TGZ in the apps), else
/// DataPath("npm/three-<kThreeVersion>.tgz"), else another DataPath("npm/three-*.tgz"); throws
/// sims::Error telling to run cmake/setup.sh if none.
std::filesystem::path FindThreeArchive();

/// Writes DIR/three/ (unpacked once per three version), DIR/viewer.js and DIR/index.html, each
/// atomically (three/ is unpacked into a temporary folder and renamed).
void InstallViewer(const std::filesystem::path& dir, const ViewerOptions& options = {});

}  // namespace sims::io
