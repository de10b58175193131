#include "sims/scene/scene.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace sims::scene {

std::string NormalizeName(const std::string& name) {
  std::string out;
  for (char c : name) {
    char l = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (l == '_' || l == '-') l = ' ';
    if (l == ' ' && (out.empty() || out.back() == ' ')) continue;
    out += l;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string UniHsiPartKey(const Part& part) {
  std::string key = part.name;
  std::replace(key.begin(), key.end(), ' ', '_');
  return key + std::to_string(part.id);
}

Aabb Object::Bounds() const {
  Aabb b;
  for (const auto& p : parts) b.Extend(p.mesh.Bounds());
  return b;
}

Aabb Object::LocalBounds() const {
  const Eigen::Isometry3d X_OW = X_WO.inverse();
  Aabb b;
  for (const auto& p : parts)
    for (const auto& v : p.mesh.vertices) b.Extend(X_OW * v);
  return b;
}

const Part* Object::FindPart(const std::string& name) const {
  for (const auto& p : parts)
    if (p.name == name) return &p;
  return nullptr;
}

const Part* Object::FindPartByKey(const std::string& key) const {
  if (const Part* p = FindPart(key)) return p;
  const std::string norm = NormalizeName(key);
  for (const auto& p : parts)
    if (NormalizeName(p.name) == norm) return &p;
  for (const auto& p : parts) {
    if (UniHsiPartKey(p) == key) return &p;
    if (NormalizeName(p.name) + " " + std::to_string(p.id) == norm) return &p;
  }
  return nullptr;
}

std::vector<const Part*> Object::PartsNamed(const std::string& name) const {
  std::vector<const Part*> out;
  for (const auto& p : parts)
    if (p.name == name) out.push_back(&p);
  return out;
}

TriangleMesh Object::MergedMesh() const {
  TriangleMesh m;
  for (const auto& p : parts) m.Append(p.mesh);
  return m;
}

void Object::ApplyTransform(const Eigen::Isometry3d& X) {
  const Eigen::Affine3d A(X.matrix());
  for (auto& p : parts) {
    p.mesh.Transform(A);
    for (auto& q : p.points) q = X * q;
  }
  X_WO = X * X_WO;
}

void Object::ResamplePoints(Rng& rng, int points_per_part) {
  for (auto& p : parts) p.points = p.mesh.SamplePoints(points_per_part, rng);
}

bool Room::Contains(const Eigen::Vector2d& p) const {
  bool inside = false;
  const std::size_t n = floor_polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& a = floor_polygon[i];
    const Eigen::Vector2d& b = floor_polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

Eigen::Vector2d Room::Centroid() const {
  double area = 0;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  const std::size_t n = floor_polygon.size();
  if (n == 0) return c;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = floor_polygon[i];
    const Eigen::Vector2d& b = floor_polygon[(i + 1) % n];
    const double cross = a.x() * b.y() - b.x() * a.y();
    area += cross;
    c += cross * (a + b);
  }
  if (std::abs(area) < 1e-12) {
    for (const auto& p : floor_polygon) c += p;
    return c / static_cast<double>(n);
  }
  return c / (3.0 * area);
}

Aabb Scene::Bounds() const {
  Aabb b = walls.Bounds();
  for (const auto& o : objects) b.Extend(o.Bounds());
  return b;
}

const Object* Scene::FindObject(const std::string& instance) const {
  const int i = ObjectIndex(instance);
  return i >= 0 ? &objects[i] : nullptr;
}

int Scene::ObjectIndex(const std::string& instance) const {
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (objects[i].instance == instance) return static_cast<int>(i);
  return -1;
}

std::vector<int> Scene::ObjectsOfCategory(const std::string& category) const {
  std::vector<int> out;
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (objects[i].category == category) out.push_back(static_cast<int>(i));
  return out;
}

const Room* Scene::FindRoom(const std::string& id) const {
  for (const auto& r : rooms)
    if (r.id == id) return &r;
  return nullptr;
}

const Room* Scene::RoomAt(double x, double y) const {
  for (const auto& r : rooms)
    if (r.Contains({x, y})) return &r;
  return nullptr;
}

std::string Scene::UniqueInstanceId(const std::string& category) const {
  std::string base = category.empty() ? "object" : category;
  std::replace(base.begin(), base.end(), ' ', '_');
  std::set<std::string> used;
  for (const auto& o : objects) used.insert(o.instance);
  for (int n = 0;; ++n) {
    std::string id = base + "_" + std::to_string(n);
    if (!used.count(id)) return id;
  }
}

Object& Scene::AddObject(Object object) {
  if (object.instance.empty() || FindObject(object.instance))
    object.instance = UniqueInstanceId(object.category);
  objects.push_back(std::move(object));
  return objects.back();
}

std::size_t Scene::TriangleCount() const {
  std::size_t n = walls.triangles.size();
  for (const auto& o : objects)
    for (const auto& p : o.parts) n += p.mesh.triangles.size();
  return n;
}

}  // namespace sims::scene
