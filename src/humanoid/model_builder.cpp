#include "sims/humanoid/model_builder.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include <Eigen/Geometry>

#include "sims/core/error.h"
#include "sims/core/markup.h"
#include "sims/core/paths.h"

namespace sims::humanoid {

namespace {

std::string Vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(9);
  s << v.x() << " " << v.y() << " " << v.z();
  return s.str();
}

std::string Rgba(const Eigen::Vector4f& c) {
  std::ostringstream s;
  s << c[0] << " " << c[1] << " " << c[2] << " " << c[3];
  return s.str();
}

void ReplaceMarker(std::string* xml, const std::string& marker, const std::string& text,
                   const std::string& source) {
  const std::string tag = "<!-- " + marker + " -->";
  const auto pos = xml->find(tag);
  if (pos == std::string::npos)
    ThrowInputError(source, marker, "the marker '" + tag + "' where scene geometry goes",
                    "no such marker");
  xml->replace(pos, tag.size(), text);
}

}  // namespace

std::filesystem::path DefaultHumanoidPath() { return AssetPath("humanoid/amp_humanoid.xml"); }

std::string ReadTextFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowInputError(path.string(), "", "a readable file", "missing or unreadable");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string ComposeModelXml(const std::string& humanoid_xml, const StaticGeometry& geometry,
                            const std::string& source) {
  // Geoms of one static body, in order of first appearance; "" holds the world's own geoms.
  std::vector<std::string> bodies;
  std::vector<std::vector<int>> members;
  for (int i = 0; i < static_cast<int>(geometry.geoms.size()); ++i) {
    const std::string& b = geometry.geoms[i].body;
    const auto it = std::find(bodies.begin(), bodies.end(), b);
    if (it == bodies.end()) {
      bodies.push_back(b);
      members.push_back({i});
    } else {
      members[it - bodies.begin()].push_back(i);
    }
  }
  std::ostringstream assets, geoms;
  assets.precision(9);
  for (size_t k = 0; k < bodies.size(); ++k) {
    // A body sits at the centre of its geoms' extent so its bounding volume is tight; geoms
    // and mesh points are written relative to it.
    Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();
    if (!bodies[k].empty()) {
      Eigen::AlignedBox3d box;
      for (int i : members[k]) {
        const StaticGeom& g = geometry.geoms[i];
        if (g.type == StaticGeom::Type::kBox)
          box.extend(g.X_WG.translation());
        else
          for (const auto& v : g.vertices) box.extend(v);
      }
      p_WB = box.center();
      geoms << "    <body name=\"" << EscapeMarkup(bodies[k]) << "\" pos=\"" << Vec(p_WB)
            << "\">\n";
    }
    const std::string indent = bodies[k].empty() ? "    " : "      ";
    for (int i : members[k]) {
      const StaticGeom& g = geometry.geoms[i];
      const std::string name =
          EscapeMarkup(g.name.empty() ? "scene_geom_" + std::to_string(i) : g.name);
      const std::string common = " class=\"scene\" friction=\"" + std::to_string(g.friction) +
                                 " 0.05 0.05\" rgba=\"" + Rgba(g.rgba) + "\"";
      if (g.type == StaticGeom::Type::kBox) {
        const Eigen::Quaterniond q(g.X_WG.rotation());
        geoms << indent << "<geom name=\"" << name << "\" type=\"box\" pos=\""
              << Vec(g.X_WG.translation() - p_WB) << "\" quat=\"" << q.w() << " " << q.x() << " "
              << q.y() << " " << q.z() << "\" size=\"" << Vec(g.half_size) << "\"" << common
              << "/>\n";
      } else {
        if (g.vertices.size() < 4)
          ThrowInputError(source, "geom '" + name + "'", "a convex mesh with at least 4 points",
                          std::to_string(g.vertices.size()) + " points");
        assets << "    <mesh name=\"" << name << "_mesh\" vertex=\"";
        for (const auto& v : g.vertices) assets << Vec(v - p_WB) << " ";
        assets << "\"/>\n";
        geoms << indent << "<geom name=\"" << name << "\" type=\"mesh\" mesh=\"" << name
              << "_mesh\"" << common << "/>\n";
      }
    }
    if (!bodies[k].empty()) geoms << "    </body>\n";
  }
  std::string xml = humanoid_xml;
  ReplaceMarker(&xml, "SIMS_SCENE_ASSETS", assets.str(), source);
  ReplaceMarker(&xml, "SIMS_SCENE_GEOMS", geoms.str(), source);
  return xml;
}

MjModelPtr LoadModelFromXml(const std::string& xml, const std::string& source) {
  // mjVFS is a large struct in MuJoCo 2.2.2; keep it off the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* kName = "sims_model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(xml.size())) != 0)
    ThrowInputError(source, "", "an MJCF model that fits MuJoCo's virtual file system",
                    "too large");
  const int slot = mj_findFileVFS(vfs.get(), kName);
  std::memcpy(vfs->filedata[slot], xml.data(), xml.size());
  char error[1024] = {0};
  mjModel* m = mj_loadXML(kName, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (!m) ThrowInputError(source, "", "a valid MJCF model", error);
  return MjModelPtr(m, MjModelDeleter());
}

MjModelPtr BuildModel(const StaticGeometry& geometry, const std::filesystem::path& humanoid_path) {
  const std::filesystem::path path = humanoid_path.empty() ? DefaultHumanoidPath() : humanoid_path;
  return LoadModelFromXml(ComposeModelXml(ReadTextFile(path), geometry, path.string()),
                          path.string());
}

MjDataPtr MakeData(const mjModel* model) { return MjDataPtr(mj_makeData(model)); }

}  // namespace sims::humanoid
