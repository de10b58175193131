#include "sims/planner/layout.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <spdlog/spdlog.h>

#include "sims/core/error.h"
#include "sims/planner/text.h"
#include "sims/scene/builtin.h"
#include "sims/scene/loaders.h"

namespace sims::planner {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string Pretty(std::string s) {
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

std::string IdOf(const std::string& s) {
  std::string out;
  for (char c : ToLower(s)) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// Database.

void LayoutEntry::Validate() const {
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (int k : edges[i])
      Require(k >= 0 && k < static_cast<int>(nodes.size()), "edges[" + std::to_string(i) + "]",
              "node indices below " + std::to_string(nodes.size()));
}

SceneGraph LayoutEntry::Graph() const {
  SceneGraph g;
  g.name = name;
  for (const LayoutNode& n : nodes) {
    GraphNode gn;
    gn.category = n.category;
    gn.instance = n.instance;
    gn.important = n.important;
    gn.position = Eigen::Vector3d(n.position[0], n.position[1], n.position[2]);
    gn.room = n.room;
    if (!n.room_type.empty()) {
      gn.room_types = {n.room_type};
    } else if (room_types.size() == 1) {
      gn.room_types = room_types;
    }
    g.nodes.push_back(gn);
  }
  for (const auto& e : edges) g.AddEdge(e[0], e[1]);
  return g;
}

void LayoutDatabase::Validate() const { Require(version == 1, "version", "1"); }

LayoutDatabase LayoutDatabase::Load(const std::filesystem::path& path) {
  return LoadConfig<LayoutDatabase>(path);
}

void LayoutDatabase::Save(const std::filesystem::path& path) const { SaveConfig(path, *this); }

void CompositionConfig::Validate() const {
  Require(wall_thickness > 0 && wall_height > 0 && door_width > 0 && door_clearance >= 0,
          "wall_thickness", "positive wall and door sizes");
}

void LayoutConfig::Validate() const {
  Require(exact_max_nodes >= 0 && exact_max_target_nodes >= 0 && max_expansions > 0,
          "exact_max_nodes", "non-negative limits and a positive expansion budget");
}

GedOptions LayoutConfig::Ged() const {
  GedOptions o;
  o.exact_max_nodes = exact_max_nodes;
  o.exact_max_target_nodes = exact_max_target_nodes;
  o.max_expansions = max_expansions;
  return o;
}

std::vector<LayoutEntry> MakeLayoutEntries(const scene::Scene& scene, const LayoutSource& source,
                                           const SceneGraphConfig& config, const Vocabulary& vocab,
                                           const LineOfSight& line_of_sight) {
  SceneGraph whole = BuildSceneGraph(scene, config, vocab, line_of_sight);
  std::map<std::string, const scene::Object*> by_instance;
  for (const scene::Object& o : scene.objects) by_instance[o.instance] = &o;
  std::map<std::string, std::string> room_type;
  for (const scene::Room& r : scene.rooms) {
    auto t = vocab.FindRoomType(r.type);
    room_type[r.id] = t ? *t : r.type;
  }
  std::vector<LayoutNode> nodes;
  for (const GraphNode& n : whole.nodes) {
    LayoutNode ln;
    ln.category = n.category;
    ln.instance = n.instance;
    ln.important = n.important;
    ln.position = {n.position.x(), n.position.y(), n.position.z()};
    ln.room = n.room;
    if (!n.room_types.empty()) ln.room_type = n.room_types.front();
    scene::Aabb b = ObjectBounds(*by_instance.at(n.instance));
    ln.box = {b.min.x(), b.min.y(), b.max.x(), b.max.y()};
    nodes.push_back(ln);
  }
  auto bounds_of = [&](const std::vector<int>& idx, const std::vector<Eigen::Vector2d>& polygon) {
    scene::Aabb b;
    for (const Eigen::Vector2d& p : polygon) b.Extend(Eigen::Vector3d(p.x(), p.y(), 0.0));
    if (polygon.empty()) {
      for (int i : idx) {
        b.Extend(Eigen::Vector3d(nodes[i].box[0], nodes[i].box[1], 0));
        b.Extend(Eigen::Vector3d(nodes[i].box[2], nodes[i].box[3], 0));
      }
    }
    if (b.empty()) return std::array<double, 4>{0, 0, 0, 0};
    return std::array<double, 4>{b.min.x(), b.min.y(), b.max.x(), b.max.y()};
  };
  auto make = [&](const std::vector<int>& idx, const std::string& name, const std::string& room_id,
                  std::vector<std::string> types, std::array<double, 4> footprint) {
    LayoutEntry e;
    e.name = name;
    e.source = source;
    e.source.room_id = room_id;
    e.room_types = std::move(types);
    e.footprint = footprint;
    std::map<int, int> remap;
    for (int i : idx) {
      remap[i] = static_cast<int>(e.nodes.size());
      e.nodes.push_back(nodes[i]);
    }
    for (const auto& [a, b] : whole.edges)
      if (remap.count(a) && remap.count(b)) e.edges.push_back({remap[a], remap[b]});
    return e;
  };
  std::string base = source.name.empty() ? scene.name : source.name;
  std::vector<int> all(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) all[i] = static_cast<int>(i);
  std::vector<std::string> types;
  for (const scene::Room& r : scene.rooms)
    if (std::find(types.begin(), types.end(), room_type[r.id]) == types.end())
      types.push_back(room_type[r.id]);
  std::vector<LayoutEntry> out;
  // Whole scene footprint: objects and walls.
  scene::Aabb sb;
  for (const LayoutNode& n : nodes) {
    sb.Extend(Eigen::Vector3d(n.box[0], n.box[1], 0));
    sb.Extend(Eigen::Vector3d(n.box[2], n.box[3], 0));
  }
  for (const Eigen::Vector3d& v : scene.walls.vertices) sb.Extend(v);
  for (const scene::Room& r : scene.rooms)
    for (const Eigen::Vector2d& p : r.floor_polygon) sb.Extend(Eigen::Vector3d(p.x(), p.y(), 0));
  std::array<double, 4> whole_fp =
      sb.empty() ? std::array<double, 4>{0, 0, 0, 0}
                 : std::array<double, 4>{sb.min.x(), sb.min.y(), sb.max.x(), sb.max.y()};
  if (scene.rooms.size() == 1) {
    // One room: its entry is the whole scene (room_id stays empty so every object is kept).
    out.push_back(make(all, base, "", types, whole_fp));
    return out;
  }
  out.push_back(make(all, base, "", types, whole_fp));
  for (const scene::Room& r : scene.rooms) {
    std::vector<int> idx;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].room == r.id) idx.push_back(static_cast<int>(i));
    if (idx.empty()) continue;
    out.push_back(
        make(idx, base + " / " + r.id, r.id, {room_type[r.id]}, bounds_of(idx, r.floor_polygon)));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Composition.

namespace {
double OverlapArea(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  double w = std::min(a[2], b[2]) - std::max(a[0], b[0]);
  double h = std::min(a[3], b[3]) - std::max(a[1], b[1]);
  return w > 0 && h > 0 ? w * h : 0.0;
}
}  // namespace

Composition ComposeRooms(const std::vector<RoomPiece>& rooms, const CompositionConfig& cfg) {
  Composition c;
  const double t = cfg.wall_thickness, w = cfg.door_width;
  double cursor = 0.0;
  std::vector<std::vector<std::array<double, 4>>> obstacles(rooms.size());
  for (std::size_t k = 0; k < rooms.size(); ++k) {
    const auto& fp = rooms[k].footprint;
    double width = fp[2] - fp[0], height = fp[3] - fp[1];
    double dx = cursor - fp[0], dy = -fp[1];
    c.offsets.push_back({dx, dy, 0.0});
    c.footprints.push_back({cursor, 0.0, cursor + width, height});
    for (const auto& o : rooms[k].obstacles)
      obstacles[k].push_back({o[0] + dx, o[1] + dy, o[2] + dx, o[3] + dy});
    cursor += width + t;
  }
  auto wall = [&](double x0, double y0, double x1, double y1) {
    PlanWall pw;
    pw.from = {x0, y0};
    pw.to = {x1, y1};
    pw.thickness = t;
    pw.height = cfg.wall_height;
    c.walls.push_back(pw);
  };
  for (std::size_t k = 0; k < rooms.size(); ++k) {
    const auto& f = c.footprints[k];
    wall(f[0] - t, f[1] - 0.5 * t, f[2] + t, f[1] - 0.5 * t);  // bottom
    wall(f[0] - t, f[3] + 0.5 * t, f[2] + t, f[3] + 0.5 * t);  // top
    if (k == 0) wall(f[0] - 0.5 * t, f[1] - t, f[0] - 0.5 * t, f[3] + t);
    if (k + 1 == rooms.size()) {
      wall(f[2] + 0.5 * t, f[1] - t, f[2] + 0.5 * t, f[3] + t);
      continue;
    }
    // Shared wall with the next room, with a door where nothing stands in the way.
    const auto& g = c.footprints[k + 1];
    double xw = f[2] + 0.5 * t;
    double top = std::max(f[3], g[3]) + t;
    double common = std::min(f[3], g[3]);
    double width = std::min(w, std::max(0.3, common - 0.1));
    double lo = 0.5 * width + 0.05, hi = common - 0.5 * width - 0.05;
    // Scan outwards from the middle; take the first spot whose corridor is free, else the spot
    // that overlaps furniture least.
    double mid = 0.5 * common, yc = mid, least = kInf;
    bool found = false;
    for (double step = 0.0; !found && step <= 0.5 * common; step += 0.05) {
      for (double cand : {mid - step, mid + step}) {
        if (cand < lo || cand > hi) continue;
        std::array<double, 4> corridor{xw - 0.5 * t - cfg.door_clearance, cand - 0.5 * width,
                                       xw + 0.5 * t + cfg.door_clearance, cand + 0.5 * width};
        double overlap = 0.0;
        for (std::size_t r : {k, k + 1})
          for (const auto& o : obstacles[r]) overlap += OverlapArea(corridor, o);
        if (overlap < least - 1e-12) {
          least = overlap;
          yc = cand;
        }
        if (overlap <= 0.0) {
          found = true;
          break;
        }
      }
    }
    if (!found)
      spdlog::warn(
          "ComposeRooms: furniture stands in front of every door position between '{}' "
          "and '{}'; using the least obstructed one",
          rooms[k].id, rooms[k + 1].id);
    wall(xw, f[1] - t, xw, yc - 0.5 * width);
    wall(xw, yc + 0.5 * width, xw, top);
    PlanDoor d;
    d.center = {xw, yc};
    d.width = width;
    d.rooms = {rooms[k].id, rooms[k + 1].id};
    c.doors.push_back(d);
  }
  return c;
}

// ---------------------------------------------------------------------------------------------
// Matching and binding.

namespace {

struct Candidate {
  double cost = kInf;
  bool exact = true;
  std::vector<int> entries;                // one entry (single) or one per group (composed)
  std::vector<std::vector<int>> mappings;  // per entry: required node → layout node
  std::vector<RequiredGraph> required;     // per entry: the (sub)graph matched
  std::vector<std::vector<int>> segments;  // per entry: segments it serves
};

std::vector<std::pair<std::string, std::vector<int>>> RoomGroups(const LongScript& script) {
  std::vector<std::pair<std::string, std::vector<int>>> groups;
  std::set<int> segments;
  for (const Keyframe& k : script.keyframes) segments.insert(k.segment);
  for (int s : segments) {
    std::string room =
        s < static_cast<int>(script.segment_rooms.size()) ? script.segment_rooms[s] : "";
    auto it =
        std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == room; });
    if (it == groups.end()) {
      groups.push_back({room, {s}});
    } else {
      it->second.push_back(s);
    }
  }
  return groups;
}

double RoomPenalty(const LongScript& script, const std::vector<std::string>& types,
                   const std::vector<int>& segments, double per_segment) {
  double p = 0.0;
  for (int s : segments) {
    if (s >= static_cast<int>(script.segment_rooms.size())) continue;
    const std::string& r = script.segment_rooms[s];
    if (!r.empty() && std::find(types.begin(), types.end(), r) == types.end()) p += per_segment;
  }
  return p;
}

// Binds keyframes given, per keyframe, the layout node its required node maps to (-1: the
// matching deleted it; -2: floor keyframe) and the room each keyframe should prefer.
std::vector<Binding> Bind(const LongScript& script, const SceneGraph& layout,
                          const std::vector<int>& target,
                          const std::vector<std::string>& prefer_room,
                          const std::vector<std::string>& fallback_key, const Vocabulary& vocab,
                          std::vector<std::string>* warnings) {
  const std::size_t n = script.keyframes.size();
  std::vector<Binding> out(n);
  std::set<int> taken;
  for (int t : target)
    if (t >= 0) taken.insert(t);
  std::map<std::string, int> fallback;  // required node key → layout node
  auto bind_node = [&](Binding* b, int node, const Keyframe& k) {
    const GraphNode& g = layout.nodes[node];
    b->object = g.instance;
    b->object_category = g.category;
    b->room = g.room;
    b->placed = true;
    if (g.category != k.furniture)
      b->note = "a " + Pretty(g.category) + " stands in for the " + Pretty(k.furniture) +
                " (substitution)";
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Keyframe& k = script.keyframes[i];
    if (target[i] == -2) continue;  // floor walks are bound below
    if (target[i] >= 0) {
      bind_node(&out[i], target[i], k);
      continue;
    }
    // The matching left this object out: any free object of the category, then substitutes.
    int node = -1;
    auto it = fallback.find(fallback_key[i]);
    if (it != fallback.end()) {
      node = it->second;
    } else {
      std::vector<std::string> cats = {k.furniture};
      for (const std::string& s : vocab.Substitutes(k.furniture))
        if (vocab.Affords(s, k.skill == Skill::kGetUp ? Skill::kSit : k.skill) ||
            k.skill == Skill::kWalk)
          cats.push_back(s);
      for (int pass = 0; pass < 4 && node < 0; ++pass) {
        bool same_room = pass % 2 == 0, free_only = pass < 2;
        for (const std::string& c : cats) {
          for (int j = 0; j < layout.size() && node < 0; ++j) {
            const GraphNode& g = layout.nodes[j];
            if (g.category != c) continue;
            if (same_room && !prefer_room[i].empty() && g.room != prefer_room[i]) continue;
            if (free_only && taken.count(j)) continue;
            node = j;
          }
          if (node >= 0) break;
        }
      }
      if (node >= 0) {
        taken.insert(node);
        fallback[fallback_key[i]] = node;
      } else {
        fallback[fallback_key[i]] = -1;
      }
    }
    if (node >= 0) {
      bind_node(&out[i], node, k);
      if (out[i].note.empty()) out[i].note = "bound after matching (the graph match left it out)";
    } else {
      std::vector<std::string> subs = vocab.Substitutes(k.furniture);
      out[i].placed = false;
      out[i].room = prefer_room[i];
      out[i].note = "layout '" + layout.name + "' has no " + Pretty(k.furniture) +
                    (subs.empty() ? "" : " or substitute (" + Join(subs, ", ") + ")");
      warnings->push_back("keyframe " + std::to_string(i) + " (" + SkillName(k.skill) + " " +
                          Pretty(k.furniture) + ") could not be placed: " + out[i].note);
    }
  }
  // Walks to "the floor" head for the next bound object; a final free walk stays unbound. A
  // get-up from the floor happens where the character is.
  for (std::size_t i = 0; i < n; ++i) {
    if (target[i] != -2) continue;
    if (script.keyframes[i].skill == Skill::kGetUp) {
      out[i].placed = true;
      out[i].room = i > 0 ? out[i - 1].room : prefer_room[i];
      out[i].note = "gets up from the floor where the character is";
      continue;
    }
    std::size_t j = i + 1;
    while (j < n && (target[j] == -2 || !out[j].placed || out[j].object.empty())) ++j;
    if (j < n) {
      out[i] = out[j];
      out[i].note = "walks towards " + out[j].object;
    } else {
      out[i].placed = true;
      out[i].room = i > 0 ? out[i - 1].room : prefer_room[i];
      out[i].note = "free walk on the floor" + (out[i].room.empty() ? "" : " of " + out[i].room);
    }
  }
  return out;
}

LayoutMatch Finish(const LongScript& script, const SceneGraph& combined,
                   const std::vector<int>& target, const std::vector<std::string>& prefer_room,
                   const std::vector<std::string>& fallback_key, PlanLayout layout,
                   const Vocabulary& vocab) {
  LayoutMatch m;
  m.layout = std::move(layout);
  m.bindings = Bind(script, combined, target, prefer_room, fallback_key, vocab, &m.warnings);
  return m;
}

}  // namespace

LayoutMatch MatchLayouts(const LongScript& script, const LayoutDatabase& db,
                         const LayoutConfig& config, const Vocabulary& vocab) {
  if (db.layouts.empty())
    ThrowInputError("layout database", "layouts", "at least one layout (run index_layouts)",
                    "none");
  const EditCosts costs = RetrievalCosts(config.costs, vocab);
  const GedOptions ged = config.Ged();
  std::vector<SceneGraph> graphs;
  for (const LayoutEntry& e : db.layouts) graphs.push_back(e.Graph());
  auto groups = RoomGroups(script);
  std::vector<int> all_segments;
  for (const auto& g : groups)
    all_segments.insert(all_segments.end(), g.second.begin(), g.second.end());

  // One layout for everything.
  Candidate single;
  RequiredGraph req = BuildRequiredGraph(script, {}, vocab);
  for (std::size_t e = 0; e < db.layouts.size(); ++e) {
    GedResult r = GraphEditDistance(req.graph, graphs[e], costs, ged);
    double c = r.cost + RoomPenalty(script, db.layouts[e].room_types, all_segments,
                                    config.costs.room_mismatch);
    if (c < single.cost - 1e-12) {
      single = Candidate();
      single.cost = c;
      single.exact = r.exact;
      single.entries = {static_cast<int>(e)};
      single.mappings = {r.mapping};
      single.required = {req};
      single.segments = {all_segments};
    }
  }
  // One single room per room type, composed side by side.
  Candidate composed;
  if (groups.size() > 1) {
    composed.cost = config.costs.composition_penalty;
    std::set<int> used;
    for (const auto& [room, segs] : groups) {
      RequiredGraph sub = BuildRequiredGraph(script, segs, vocab);
      double best = kInf;
      int best_e = -1;
      GedResult best_r;
      for (std::size_t e = 0; e < db.layouts.size(); ++e) {
        if (!db.layouts[e].IsSingleRoom() || used.count(static_cast<int>(e))) continue;
        GedResult r = GraphEditDistance(sub.graph, graphs[e], costs, ged);
        double c = r.cost +
                   RoomPenalty(script, db.layouts[e].room_types, segs, config.costs.room_mismatch);
        if (c < best - 1e-12) {
          best = c;
          best_e = static_cast<int>(e);
          best_r = r;
        }
      }
      if (best_e < 0) {
        composed.cost = kInf;
        break;
      }
      used.insert(best_e);
      composed.cost += best;
      composed.exact = composed.exact && best_r.exact;
      composed.entries.push_back(best_e);
      composed.mappings.push_back(best_r.mapping);
      composed.required.push_back(sub);
      composed.segments.push_back(segs);
    }
  }

  const std::size_t n = script.keyframes.size();
  std::vector<int> target(n, -2);
  std::vector<std::string> prefer(n), fkey(n);
  PlanLayout layout;
  SceneGraph combined;
  if (single.cost <= composed.cost) {
    const LayoutEntry& e = db.layouts[single.entries[0]];
    combined = graphs[single.entries[0]];
    layout.name = e.name;
    layout.mode = "single";
    layout.cost = single.cost;
    layout.exact = single.exact;
    PlanRoom room;
    room.id = e.source.room_id.empty() ? IdOf(e.name) : e.source.room_id;
    room.type = e.room_types.size() == 1 ? e.room_types[0] : "house";
    room.source = e.source;
    room.footprint = e.footprint;
    layout.rooms.push_back(room);
    for (GraphNode& g : combined.nodes)
      if (g.room.empty()) g.room = room.id;
    for (std::size_t i = 0; i < n; ++i) {
      int r = single.required[0].keyframe_node[i];
      if (r < 0) continue;
      target[i] = single.mappings[0][r];
      fkey[i] = "0:" + std::to_string(r);
    }
  } else {
    layout.mode = "composed";
    layout.cost = composed.cost;
    layout.exact = composed.exact;
    std::vector<RoomPiece> pieces;
    std::vector<std::string> names;
    for (std::size_t k = 0; k < composed.entries.size(); ++k) {
      const LayoutEntry& e = db.layouts[composed.entries[k]];
      RoomPiece p;
      p.id = IdOf(groups[k].first.empty() ? e.room_types[0] : groups[k].first) + "_" +
             std::to_string(k);
      p.footprint = e.footprint;
      for (const LayoutNode& ln : e.nodes) p.obstacles.push_back(ln.box);
      pieces.push_back(p);
      names.push_back(e.name);
    }
    Composition comp = ComposeRooms(pieces, config.composition);
    layout.name = "composed: " + Join(names, " + ");
    layout.walls = comp.walls;
    layout.doors = comp.doors;
    for (std::size_t k = 0; k < composed.entries.size(); ++k) {
      const LayoutEntry& e = db.layouts[composed.entries[k]];
      PlanRoom room;
      room.id = pieces[k].id;
      room.type = e.room_types[0];
      room.source = e.source;
      room.offset = comp.offsets[k];
      room.footprint = comp.footprints[k];
      layout.rooms.push_back(room);
      int base = combined.size();
      SceneGraph g = graphs[composed.entries[k]];
      for (GraphNode gn : g.nodes) {
        gn.instance = room.id + "/" + gn.instance;
        gn.room = room.id;
        gn.position += Eigen::Vector3d(room.offset[0], room.offset[1], room.offset[2]);
        combined.nodes.push_back(gn);
      }
      for (const auto& [a, b] : g.edges) combined.AddEdge(base + a, base + b);
      const RequiredGraph& sub = composed.required[k];
      for (std::size_t i = 0; i < n; ++i) {
        const Keyframe& kf = script.keyframes[i];
        const auto& segs = composed.segments[k];
        if (std::find(segs.begin(), segs.end(), kf.segment) == segs.end()) continue;
        prefer[i] = room.id;
        int r = sub.keyframe_node[i];
        if (r < 0) continue;
        int m = composed.mappings[k][r];
        target[i] = m >= 0 ? base + m : -1;
        fkey[i] = std::to_string(k) + ":" + std::to_string(r);
      }
    }
    combined.name = layout.name;
  }
  return Finish(script, combined, target, prefer, fkey, layout, vocab);
}

LayoutMatch MatchScene(const LongScript& script, const scene::Scene& scene,
                       const LayoutConfig& config, const Vocabulary& vocab,
                       const LineOfSight& line_of_sight) {
  SceneGraph g = BuildSceneGraph(scene, config.graph, vocab, line_of_sight);
  RequiredGraph req = BuildRequiredGraph(script, {}, vocab);
  GedResult r = GraphEditDistance(req.graph, g, RetrievalCosts(config.costs, vocab), config.Ged());
  PlanLayout layout;
  layout.name = scene.name;
  layout.mode = "given";
  layout.cost = r.cost;
  layout.exact = r.exact;
  for (const scene::Room& room : scene.rooms) {
    PlanRoom pr;
    pr.id = room.id;
    auto t = vocab.FindRoomType(room.type);
    pr.type = t ? *t : room.type;
    pr.source.kind = "given";
    pr.source.name = scene.name;
    pr.source.room_id = room.id;
    layout.rooms.push_back(pr);
  }
  const std::size_t n = script.keyframes.size();
  std::vector<int> target(n, -2);
  std::vector<std::string> prefer(n), fkey(n);
  for (std::size_t i = 0; i < n; ++i) {
    int node = req.keyframe_node[i];
    if (node < 0) continue;
    target[i] = r.mapping[node];
    fkey[i] = std::to_string(node);
  }
  g.name = scene.name;
  return Finish(script, g, target, prefer, fkey, layout, vocab);
}

// ---------------------------------------------------------------------------------------------
// Materialisation.

namespace {

void AppendWallBox(scene::TriangleMesh* mesh, const PlanWall& w) {
  Eigen::Vector2d a(w.from[0], w.from[1]), b(w.to[0], w.to[1]);
  Eigen::Vector2d d = b - a;
  if (d.norm() < 1e-9) return;
  Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()).normalized() * (0.5 * w.thickness);
  Eigen::Vector2d c[4] = {a - n, b - n, b + n, a + n};
  int base = static_cast<int>(mesh->vertices.size());
  for (double z : {0.0, w.height})
    for (const Eigen::Vector2d& p : c) mesh->vertices.emplace_back(p.x(), p.y(), z);
  // Orientation-consistent quads: bottom, top and the four sides.
  const int q[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  bool flip = (c[1] - c[0]).x() * (c[3] - c[0]).y() - (c[1] - c[0]).y() * (c[3] - c[0]).x() < 0;
  for (const auto& f : q) {
    Eigen::Vector3i t1(base + f[0], base + f[1], base + f[2]),
        t2(base + f[0], base + f[2], base + f[3]);
    if (flip) {
      std::swap(t1[1], t1[2]);
      std::swap(t2[1], t2[2]);
    }
    mesh->triangles.push_back(t1);
    mesh->triangles.push_back(t2);
  }
}

void Translate(scene::Object* o, const Eigen::Vector3d& d) {
  for (scene::Part& p : o->parts) {
    for (Eigen::Vector3d& v : p.mesh.vertices) v += d;
    for (Eigen::Vector3d& v : p.points) v += d;
  }
  o->X_WO.translation() += d;
}

}  // namespace

SceneLoader DefaultSceneLoader() {
  return [](const LayoutSource& s) -> scene::Scene {
    if (s.kind == "builtin_room") return scene::BuiltinScene(s.name);
    if (s.kind == "builtin_house") return scene::BuiltinHouse();
    if (s.kind == "morse") return scene::LoadMorseApartment();
    if (s.kind == "front3d") return scene::LoadFront3D(s.path, s.model_dir);
    if (s.kind == "scene_file") return scene::LoadSceneFile(s.path);
    ThrowInputError("layout source '" + s.name + "'", "kind",
                    "builtin_room, builtin_house, morse, front3d or scene_file ('given' scenes are "
                    "passed in by the caller)",
                    s.kind);
  };
}

scene::Scene MaterializeLayout(const PlanLayout& layout, const SceneLoader& loader) {
  if (layout.mode == "given")
    ThrowInputError("plan layout '" + layout.name + "'", "mode",
                    "single or composed (a 'given' layout is the scene the caller passed in)",
                    "given");
  if (layout.rooms.empty())
    ThrowInputError("plan layout '" + layout.name + "'", "rooms", "at least one room");
  std::map<std::string, scene::Scene> cache;
  auto load = [&](const LayoutSource& s) -> const scene::Scene& {
    auto it = cache.find(s.SceneKey());
    if (it == cache.end()) it = cache.emplace(s.SceneKey(), loader(s)).first;
    return it->second;
  };
  scene::Scene out;
  out.name = layout.name;
  if (layout.mode == "single") {
    const PlanRoom& room = layout.rooms[0];
    const scene::Scene& src = load(room.source);
    out = src;
    out.name = layout.name;
    if (!room.source.room_id.empty()) {
      out.objects.clear();
      for (const scene::Object& o : src.objects)
        if (o.room == room.source.room_id) out.objects.push_back(o);
      out.rooms.clear();
      for (const scene::Room& r : src.rooms)
        if (r.id == room.source.room_id) out.rooms.push_back(r);
    }
    return out;
  }
  for (const PlanRoom& room : layout.rooms) {
    const scene::Scene& src = load(room.source);
    Eigen::Vector3d d(room.offset[0], room.offset[1], room.offset[2]);
    for (const scene::Object& o : src.objects) {
      if (!room.source.room_id.empty() && o.room != room.source.room_id) continue;
      scene::Object moved = o;
      Translate(&moved, d);
      moved.instance = room.id + "/" + o.instance;
      moved.room = room.id;
      out.objects.push_back(std::move(moved));
    }
    scene::Room r;
    r.id = room.id;
    r.type = room.type;
    const auto& f = room.footprint;
    r.floor_polygon = {{f[0], f[1]}, {f[2], f[1]}, {f[2], f[3]}, {f[0], f[3]}};
    out.rooms.push_back(r);
  }
  for (const PlanWall& w : layout.walls) AppendWallBox(&out.walls, w);
  return out;
}

// ---------------------------------------------------------------------------------------------

LayoutDatabase BuildLayoutDatabase(bool builtin, bool morse,
                                   const std::vector<std::filesystem::path>& front3d_dirs,
                                   const std::filesystem::path& future_dir,
                                   const LayoutConfig& config, std::vector<std::string>* log,
                                   const Vocabulary& vocab) {
  LayoutDatabase db;
  auto add = [&](const scene::Scene& s, const LayoutSource& src) {
    std::vector<LayoutEntry> entries = MakeLayoutEntries(s, src, config.graph, vocab);
    for (LayoutEntry& e : entries) {
      log->push_back("indexed '" + e.name + "': " + std::to_string(e.nodes.size()) + " objects, " +
                     std::to_string(e.edges.size()) + " edges, rooms [" + Join(e.room_types, ", ") +
                     "]");
      db.layouts.push_back(std::move(e));
    }
  };
  if (builtin) {
    for (const scene::Scene& s : scene::BuiltinRooms()) {
      LayoutSource src;
      src.kind = "builtin_room";
      src.name = s.name;
      add(s, src);
    }
    LayoutSource house;
    house.kind = "builtin_house";
    house.name = "house";
    add(scene::BuiltinHouse(), house);
  }
  if (morse) {
    try {
      LayoutSource src;
      src.kind = "morse";
      src.name = "morse apartment";
      add(scene::LoadMorseApartment(), src);
    } catch (const Error& e) {
      log->push_back(std::string("skipped the MORSE apartment: ") + e.what());
    }
  }
  for (const std::filesystem::path& dir : front3d_dirs) {
    std::vector<std::filesystem::path> houses;
    if (std::filesystem::is_regular_file(dir)) {
      houses.push_back(dir);
    } else if (std::filesystem::is_directory(dir)) {
      for (const auto& f : std::filesystem::directory_iterator(dir))
        if (f.is_regular_file() && f.path().extension() == ".json") houses.push_back(f.path());
    } else {
      ThrowInputError(dir.string(), "", "a 3D-FRONT folder or house JSON", "no such path");
    }
    std::sort(houses.begin(), houses.end());
    for (const auto& h : houses) {
      try {
        LayoutSource src;
        src.kind = "front3d";
        src.path = std::filesystem::absolute(h).string();
        src.model_dir = future_dir.empty() ? "" : std::filesystem::absolute(future_dir).string();
        src.name = "3d-front " + h.stem().string();
        add(scene::LoadFront3D(h, future_dir), src);
      } catch (const Error& e) {
        log->push_back("skipped " + h.string() + ": " + e.what());
      }
    }
  }
  return db;
}

}  // namespace sims::planner
