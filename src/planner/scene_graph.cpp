#include "sims/planner/scene_graph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include "sims/planner/text.h"
#include "sims/scene/ray_caster.h"

namespace sims::planner {

void SceneGraphConfig::Validate() const {
  Require(max_edge_distance > 0, "max_edge_distance", "a positive distance in metres");
  Require(sight_height > 0, "sight_height", "a positive height in metres");
}

void MatchCostConfig::Validate() const {
  Require(missing_node >= 0 && extra_node >= 0 && missing_edge >= 0 && extra_edge >= 0 &&
              unimportant_weight >= 0 && room_mismatch >= 0 && node_room_mismatch >= 0 &&
              composition_penalty >= 0,
          "missing_node", "non-negative costs");
}

EditCosts RetrievalCosts(const MatchCostConfig& config, const Vocabulary& vocab) {
  EditCosts c;
  const Vocabulary* v = &vocab;
  auto weight = [config](const GraphNode& n) {
    return n.important ? 1.0 : config.unimportant_weight;
  };
  c.substitute = [v, config](const GraphNode& a, const GraphNode& b) {
    std::optional<double> s = v->SubstitutionCost(a.category, b.category);
    if (!s) return std::numeric_limits<double>::infinity();
    // An armchair may stand in for a sofa to sit on, not to lie on.
    for (Skill u : a.uses)
      if (!v->Affords(b.category, u)) return std::numeric_limits<double>::infinity();
    for (Skill u : b.uses)
      if (!v->Affords(a.category, u)) return std::numeric_limits<double>::infinity();
    bool shared = a.room_types.empty() || b.room_types.empty();
    for (const std::string& r : a.room_types)
      shared =
          shared || std::find(b.room_types.begin(), b.room_types.end(), r) != b.room_types.end();
    return *s + (shared ? 0.0 : config.node_room_mismatch);
  };
  c.remove = [config, weight](const GraphNode& a) { return config.missing_node * weight(a); };
  c.insert = [config, weight](const GraphNode& b) { return config.extra_node * weight(b); };
  c.edge_remove = config.missing_edge;
  c.edge_insert = config.extra_edge;
  return c;
}

std::string CanonicalCategory(const std::string& category, const Vocabulary& vocab) {
  if (auto f = vocab.FindFurniture(category)) return *f;
  std::string s = ToLower(Trim(category));
  std::replace(s.begin(), s.end(), ' ', '_');
  return s;
}

scene::Aabb ObjectBounds(const scene::Object& object) {
  scene::Aabb box;
  for (const scene::Part& p : object.parts) {
    for (const Eigen::Vector3d& v : p.mesh.vertices) box.Extend(v);
    for (const Eigen::Vector3d& v : p.points) box.Extend(v);
  }
  if (box.empty()) box.Extend(object.X_WO.translation());
  return box;
}

namespace {

// Segment p→q against a box: the parameter interval [t0, t1] inside, or false.
bool SegmentBox(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const scene::Aabb& b,
                double* t0, double* t1) {
  double lo = 0.0, hi = 1.0;
  Eigen::Vector3d d = q - p;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (p[k] < b.min[k] || p[k] > b.max[k]) return false;
      continue;
    }
    double a = (b.min[k] - p[k]) / d[k], c = (b.max[k] - p[k]) / d[k];
    if (a > c) std::swap(a, c);
    lo = std::max(lo, a);
    hi = std::min(hi, c);
    if (lo > hi) return false;
  }
  *t0 = lo;
  *t1 = hi;
  return true;
}

double FootprintGap(const scene::Aabb& a, const scene::Aabb& b) {
  double dx = std::max({0.0, a.min.x() - b.max.x(), b.min.x() - a.max.x()});
  double dy = std::max({0.0, a.min.y() - b.max.y(), b.min.y() - a.max.y()});
  return std::hypot(dx, dy);
}

}  // namespace

LineOfSight DefaultLineOfSight(const scene::Scene& scene) {
  auto caster = std::make_shared<scene::RayCaster>(scene);
  return [caster](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return !caster->Occluded(a, b);
  };
}

SceneGraph BuildSceneGraph(const scene::Scene& scene, const SceneGraphConfig& config,
                           const Vocabulary& vocab, const LineOfSight& line_of_sight,
                           const std::vector<std::string>& rooms) {
  SceneGraph g;
  g.name = scene.name;
  std::map<std::string, std::string> room_types;
  for (const scene::Room& r : scene.rooms) {
    auto t = vocab.FindRoomType(r.type);
    room_types[r.id] = t ? *t : r.type;
  }
  std::set<std::string> ignore;
  for (const std::string& c : config.ignore_categories) ignore.insert(CanonicalCategory(c, vocab));
  std::vector<scene::Aabb> boxes;
  for (const scene::Object& o : scene.objects) {
    if (!rooms.empty() && std::find(rooms.begin(), rooms.end(), o.room) == rooms.end()) continue;
    std::string category = CanonicalCategory(o.category, vocab);
    if (ignore.count(category) || category.empty()) continue;
    GraphNode n;
    n.category = category;
    n.instance = o.instance;
    n.important = o.important && vocab.IsImportant(category);
    scene::Aabb box = ObjectBounds(o);
    n.position = box.center();
    n.room = o.room;
    if (auto it = room_types.find(o.room); it != room_types.end()) n.room_types = {it->second};
    g.nodes.push_back(n);
    boxes.push_back(box);
  }
  LineOfSight los = line_of_sight ? line_of_sight : DefaultLineOfSight(scene);
  for (int i = 0; i < g.size(); ++i) {
    for (int j = i + 1; j < g.size(); ++j) {
      if (FootprintGap(boxes[i], boxes[j]) > config.max_edge_distance) continue;
      Eigen::Vector3d a = boxes[i].center(), b = boxes[j].center();
      a.z() = b.z() = config.sight_height;
      // Leave each object's own box first, so the test only sees what lies between them.
      double ta0, ta1, tb0, tb1;
      scene::Aabb ai = boxes[i], bj = boxes[j];
      ai.min.z() = bj.min.z() = -1e9;
      ai.max.z() = bj.max.z() = 1e9;
      double start = SegmentBox(a, b, ai, &ta0, &ta1) ? ta1 : 0.0;
      double end = SegmentBox(a, b, bj, &tb0, &tb1) ? tb0 : 1.0;
      const double eps = 0.02 / std::max(1e-9, (b - a).norm());
      if (start + eps >= end - eps) {  // footprints touch or overlap: neighbours
        g.AddEdge(i, j);
        continue;
      }
      Eigen::Vector3d p = a + (start + eps) * (b - a), q = a + (end - eps) * (b - a);
      if (los(p, q)) g.AddEdge(i, j);
    }
  }
  return g;
}

RequiredGraph BuildRequiredGraph(const LongScript& script, const std::vector<int>& segments,
                                 const Vocabulary& vocab) {
  RequiredGraph out;
  out.keyframe_node.assign(script.keyframes.size(), -1);
  auto wanted = [&](int s) {
    return segments.empty() || std::find(segments.begin(), segments.end(), s) != segments.end();
  };
  // Per segment: distinct (category, instance) in order of first use, ranked within category.
  std::map<int, std::vector<std::pair<std::string, int>>> seg_objects;
  std::map<std::pair<int, std::pair<std::string, int>>, int> rank;  // (segment, object) → rank
  for (const Keyframe& k : script.keyframes) {
    if (k.furniture == "floor" || !wanted(k.segment)) continue;
    auto& objs = seg_objects[k.segment];
    std::pair<std::string, int> obj{k.furniture, k.instance};
    if (std::find(objs.begin(), objs.end(), obj) != objs.end()) continue;
    int r = static_cast<int>(std::count_if(objs.begin(), objs.end(),
                                           [&](const auto& o) { return o.first == k.furniture; }));
    objs.push_back(obj);
    rank[{k.segment, obj}] = r;
  }
  // Consolidation: node (category, r) exists for r below the largest per-segment count; nodes
  // appear in order of first use.
  std::map<std::pair<std::string, int>, int> node_of;
  auto room_of = [&](int segment) -> std::string {
    return segment >= 0 && segment < static_cast<int>(script.segment_rooms.size())
               ? script.segment_rooms[segment]
               : std::string();
  };
  for (std::size_t i = 0; i < script.keyframes.size(); ++i) {
    const Keyframe& k = script.keyframes[i];
    if (k.furniture == "floor" || !wanted(k.segment)) continue;
    int r = rank[{k.segment, {k.furniture, k.instance}}];
    auto key = std::make_pair(k.furniture, r);
    auto it = node_of.find(key);
    if (it == node_of.end()) {
      GraphNode n;
      n.category = k.furniture;
      n.instance = k.furniture + "#" + std::to_string(r);
      n.important = vocab.IsImportant(k.furniture);
      it = node_of.emplace(key, out.graph.size()).first;
      out.graph.nodes.push_back(n);
    }
    auto& uses = out.graph.nodes[it->second].uses;
    if (std::find(uses.begin(), uses.end(), k.skill) == uses.end()) uses.push_back(k.skill);
    std::string room = room_of(k.segment);
    auto& types = out.graph.nodes[it->second].room_types;
    if (!room.empty() && std::find(types.begin(), types.end(), room) == types.end())
      types.push_back(room);
    out.keyframe_node[i] = it->second;
  }
  // Edge integration: consecutive distinct objects of one short script.
  std::map<int, int> last_node;
  for (std::size_t i = 0; i < script.keyframes.size(); ++i) {
    int n = out.keyframe_node[i];
    if (n < 0) continue;
    int s = script.keyframes[i].segment;
    auto it = last_node.find(s);
    if (it != last_node.end() && it->second != n) out.graph.AddEdge(it->second, n);
    last_node[s] = n;
  }
  out.graph.name = "required graph";
  return out;
}

}  // namespace sims::planner
