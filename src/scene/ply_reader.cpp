// Our own PLY reader (ASCII, binary little- and big-endian): it keeps the file's vertex order,
// which ScanNet's segment annotations index into, and Assimp 5.2's PLY importer loops without
// end or aborts on an assertion on some malformed files (fuzzer findings).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "scene/loader_util.h"
#include "sims/core/error.h"

namespace sims::scene::internal {

namespace {

struct PlyProperty {
  std::string name, type;
  bool is_list = false;
  std::string count_type;
};
struct PlyElement {
  std::string name;
  int64_t count = 0;
  std::vector<PlyProperty> props;
};

int TypeSize(const std::string& t, const std::string& file) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  ThrowInputError(file, "property type", "a PLY scalar type (char, uchar, short, ..., double)",
                  "'" + t + "'");
}

double ReadBinary(const char* p, const std::string& t) {
  auto get = [&](auto v) {
    std::memcpy(&v, p, sizeof(v));
    return static_cast<double>(v);
  };
  if (t == "char" || t == "int8") return get(int8_t{});
  if (t == "uchar" || t == "uint8") return get(uint8_t{});
  if (t == "short" || t == "int16") return get(int16_t{});
  if (t == "ushort" || t == "uint16") return get(uint16_t{});
  if (t == "int" || t == "int32") return get(int32_t{});
  if (t == "uint" || t == "uint32") return get(uint32_t{});
  if (t == "float" || t == "float32") return get(float{});
  return get(double{});
}

}  // namespace

TriangleMesh ReadPly(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowInputError(file, "", "a readable PLY file", "missing or unreadable");
  std::string line;
  std::getline(in, line);
  if (line.rfind("ply", 0) != 0)
    ThrowInputError(file, "header", "a file starting with 'ply'", line);
  std::string format;
  std::vector<PlyElement> elements;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ss(line);
    std::string word;
    ss >> word;
    if (word == "format") {
      ss >> format;
    } else if (word == "element") {
      PlyElement e;
      ss >> e.name >> e.count;
      if (!ss || e.count < 0) ThrowInputError(file, "element", "'element <name> <count>'", line);
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) ThrowInputError(file, "property", "a property after an element", line);
      PlyProperty p;
      std::string t;
      ss >> t;
      if (t == "list") {
        p.is_list = true;
        ss >> p.count_type >> p.type >> p.name;
        TypeSize(p.count_type, file);
      } else {
        p.type = t;
        ss >> p.name;
      }
      TypeSize(p.type, file);
      elements.back().props.push_back(p);
    } else if (word == "end_header") {
      break;
    }
  }
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
    ThrowInputError(file, "format", "ascii, binary_little_endian or binary_big_endian",
                    "'" + format + "'");
  TriangleMesh mesh;
  const bool ascii = format == "ascii";
  const bool swap = format == "binary_big_endian";
  // A face lists a few vertices; a count beyond this is a corrupt file, not a polygon.
  constexpr int64_t kMaxListSize = 1 << 16;
  const auto list_size = [&](double n, const std::string& element, int64_t row) {
    if (!(n >= 0 && n <= kMaxListSize))
      ThrowInputError(file, "element " + element + " row " + std::to_string(row),
                      "a list size in [0, " + std::to_string(kMaxListSize) + "]",
                      std::to_string(n));
    return static_cast<int>(n);
  };
  const auto index = [&](double v) {
    if (!(v >= 0 && v < 2147483647.0) || v != std::floor(v))
      ThrowInputError(file, "face.vertex_indices", "vertex indices (integers ≥ 0)",
                      std::to_string(v));
    return static_cast<int>(v);
  };
  for (const auto& e : elements) {
    int ix = -1, iy = -1, iz = -1, iface = -1;
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const auto& p = e.props[k];
      if (p.name == "x") ix = static_cast<int>(k);
      if (p.name == "y") iy = static_cast<int>(k);
      if (p.name == "z") iz = static_cast<int>(k);
      if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        iface = static_cast<int>(k);
    }
    if (e.name == "vertex" && (ix < 0 || iy < 0 || iz < 0))
      ThrowInputError(file, "element vertex", "x, y and z properties", "missing");
    std::vector<double> values;
    std::vector<int> list;
    for (int64_t r = 0; r < e.count; ++r) {
      values.assign(e.props.size(), 0.0);
      list.clear();
      if (ascii) {
        if (!std::getline(in, line))
          ThrowInputError(file, "element " + e.name, std::to_string(e.count) + " rows",
                          std::to_string(r) + " rows");
        std::istringstream ss(line);
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const auto& p = e.props[k];
          if (p.is_list) {
            double n = -1;
            ss >> n;
            const int count = list_size(n, e.name, r);
            for (int i = 0; i < count && ss; ++i) {
              double v = 0;
              ss >> v;
              if (ss && static_cast<int>(k) == iface) list.push_back(index(v));
            }
          } else {
            ss >> values[k];
          }
        }
        if (!ss)
          ThrowInputError(file, "element " + e.name + " row " + std::to_string(r),
                          "numbers for every property", line);
      } else {
        char buf[8];
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const auto& p = e.props[k];
          auto read = [&](const std::string& t) {
            const int sz = TypeSize(t, file);
            if (!in.read(buf, sz))
              ThrowInputError(file, "element " + e.name, std::to_string(e.count) + " rows",
                              "file ends at row " + std::to_string(r));
            if (swap) std::reverse(buf, buf + sz);
            return ReadBinary(buf, t);
          };
          if (p.is_list) {
            const int n = list_size(read(p.count_type), e.name, r);
            for (int i = 0; i < n; ++i) {
              const double v = read(p.type);
              if (static_cast<int>(k) == iface) list.push_back(index(v));
            }
          } else {
            values[k] = read(p.type);
          }
        }
      }
      if (e.name == "vertex") {
        mesh.vertices.emplace_back(values[ix], values[iy], values[iz]);
      } else if (e.name == "face" && iface >= 0) {
        for (std::size_t i = 2; i < list.size(); ++i)
          mesh.triangles.emplace_back(list[0], list[i - 1], list[i]);
      }
    }
  }
  const int nv = static_cast<int>(mesh.vertices.size());
  for (const auto& t : mesh.triangles)
    if (t.minCoeff() < 0 || t.maxCoeff() >= nv)
      ThrowInputError(file, "face.vertex_indices", "indices below " + std::to_string(nv),
                      std::to_string(t.maxCoeff()));
  return mesh;
}

}  // namespace sims::scene::internal
