#include "sims/io/viewer.h"

#include <unistd.h>

#include <fstream>

#include "sims/core/config.h"
#include "sims/core/environment.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/humanoid/model_builder.h"
#include "sims/io/subprocess.h"

namespace sims::io {

namespace {

// Files of the three package the viewer imports (GLTFLoader needs BufferGeometryUtils).
const char* kThreeFiles[] = {
    "build/three.module.min.js",
    "examples/jsm/loaders/GLTFLoader.js",
    "examples/jsm/utils/BufferGeometryUtils.js",
    "examples/jsm/controls/OrbitControls.js",
    "LICENSE",
};

void InstallThree(const std::filesystem::path& dir, const std::filesystem::path& archive) {
  namespace fs = std::filesystem;
  const fs::path three = dir / "three";
  const std::string stamp = archive.filename().string();
  {
    std::ifstream in(three / "SOURCE");
    std::string have;
    std::getline(in, have);
    bool complete = have == stamp;
    for (const char* f : kThreeFiles) complete = complete && fs::exists(three / f);
    if (complete) return;
  }
  const fs::path tmp = dir / (".three.tmp." + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  std::vector<std::string> argv = {"tar", "-xzf",       archive.string(),
                                   "-C",  tmp.string(), "--strip-components=1"};
  for (const char* f : kThreeFiles) argv.push_back(std::string("package/") + f);
  std::string out;
  const int code = RunCommand(argv, &out);
  std::error_code ec;
  if (code != 0) {
    fs::remove_all(tmp, ec);
    ThrowInputError(archive.string(), "", "the npm tarball of three (package/build/...)",
                    "tar failed: " + out.substr(0, 400));
  }
  WriteFileAtomic(tmp / "SOURCE", stamp + "\n");
  fs::remove_all(three, ec);
  fs::rename(tmp, three, ec);
  if (ec) {
    fs::remove_all(tmp, ec);
    ThrowInputError(three.string(), "", "a writable folder", "rename failed");
  }
}

}  // namespace

std::filesystem::path FindThreeArchive() {
  namespace fs = std::filesystem;
  if (const fs::path& given = InstalledEnvironment().three_tgz; !given.empty()) {
    if (!fs::exists(given))
      ThrowInputError("$SIMS_THREE_TGZ", "", "the path of three-*.tgz",
                      given.string() + " (missing)");
    return given;
  }
  const fs::path want = DataPath(std::string("npm/three-") + kThreeVersion + ".tgz");
  if (fs::exists(want)) return want;
  const fs::path npm = want.parent_path();
  if (fs::is_directory(npm))
    for (const auto& e : fs::directory_iterator(npm)) {
      const std::string n = e.path().filename().string();
      if (n.rfind("three-", 0) == 0 && e.path().extension() == ".tgz") return e.path();
    }
  ThrowInputError(
      want.string(), "", "the three.js npm tarball for the web viewer",
      "missing; run cmake/setup.sh (npm pack three@" + std::string(kThreeVersion) + ")");
}

void InstallViewer(const std::filesystem::path& dir, const ViewerOptions& options) {
  std::filesystem::create_directories(dir);
  const std::filesystem::path assets =
      options.assets_dir.empty() ? AssetPath("viewer") : options.assets_dir;
  InstallThree(dir, options.three_archive.empty() ? FindThreeArchive() : options.three_archive);
  // index.html last: it is what a person opens, and it needs everything else.
  WriteFileAtomic(dir / "viewer.js", humanoid::ReadTextFile(assets / "viewer.js"));
  WriteFileAtomic(dir / "index.html", humanoid::ReadTextFile(assets / "index.html"));
}

}  // namespace sims::io
