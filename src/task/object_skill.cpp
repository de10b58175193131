// The training ground, object choice, clip placement and step bookkeeping shared by the object
// skills. Per-env state lives in vectors indexed by env id (the env calls the hooks of
// different envs concurrently).
#include "sims/task/object_skill.h"

#include <limits>

#include <algorithm>
#include <cmath>
#include <optional>

#include "sims/core/error.h"
#include "sims/humanoid/features.h"
#include "sims/scene/builtin.h"
#include "sims/scene/contact_targets.h"
#include "sims/task/handoff.h"

namespace sims::task {

namespace {
// Hand-off states drawn before a start falls back to a reference clip.
constexpr int kHandoffDraws = 16;
// Free floor: the precomputed height may be this high (rugs) and must be so around a point.
constexpr double kFloorTolerance = 0.05;

double YawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

scene::Aabb PartLocalBounds(const scene::Object& o, int part) {
  const Eigen::Isometry3d X_OW = o.X_WO.inverse();
  scene::Aabb b;
  for (const auto& v : o.parts[part].mesh.vertices) b.Extend(X_OW * v);
  return b;
}

// True when `hit` holds at p or at one of eight points `radius` around it (centre first).
template <class Hit>
bool AnyOnDisk(const Eigen::Vector2d& p, double radius, const Hit& hit) {
  if (hit(p)) return true;
  for (int k = 0; k < 8; ++k) {
    const double a = k * M_PI / 4;
    if (hit(Eigen::Vector2d(p.x() + radius * std::cos(a), p.y() + radius * std::sin(a))))
      return true;
  }
  return false;
}

bool FreeAt(const scene::SceneHeightGrid& grid, const Eigen::Vector2d& p, double radius) {
  return !AnyOnDisk(p, radius, [&](const Eigen::Vector2d& q) {
    return grid.Height(q.x(), q.y()) >= kFloorTolerance;
  });
}
}  // namespace

void ObjectParams::Validate() const {
  Require(num_objects >= 0, "num_objects", "a non-negative count");
  Require(training_scale_min > 0 && training_scale_min <= 0.9, "training_scale_min",
          "a factor in (0, 0.9]");
  Require(training_scale_max >= 1.1 && training_scale_max <= 2, "training_scale_max",
          "a factor in [1.1, 2]");
  Require(spawn_max_distance >= spawn_min_distance && spawn_min_distance >= 0, "spawn_max_distance",
          "a distance ≥ spawn_min_distance ≥ 0");
  Require(spawn_arc_deg > 0 && spawn_arc_deg <= 360, "spawn_arc_deg", "an angle in (0, 360]");
  Require(spawn_curriculum_step > 0 && spawn_curriculum_step <= 1, "spawn_curriculum_step",
          "a level step in (0, 1]");
  Require(spawn_full_range_share >= 0 && spawn_full_range_share <= 1, "spawn_full_range_share",
          "a share in [0, 1]");
  Require(contact_success_threshold > 0, "contact_success_threshold", "a positive distance (m)");
  Require(reference_window >= 0, "reference_window", "a non-negative duration (s), 0 = off");
  Require(max_contact_force >= 0, "max_contact_force", "a non-negative force (N), 0 = off");
  Require(precise_near_share >= 0 && precise_near_share <= 1, "precise_near_share",
          "a share in [0, 1]");
  Require(wide_near_share >= 0 && wide_near_share + precise_near_share <= 1, "wide_near_share",
          "a share in [0, 1 − precise_near_share]");
  Require(near_facing_share >= 0 && near_facing_share <= 1, "near_facing_share",
          "a share in [0, 1]");
  Require(handoff_share >= 0 && handoff_share <= 1, "handoff_share", "a share in [0, 1]");
  Require(handoff_share == 0 || !handoff_states.empty(), "handoff_states",
          "hand-off state files (eval_policy --end-states) when handoff_share > 0");
  Require(clutter_share >= 0 && clutter_share <= 1, "clutter_share", "a share in [0, 1]");
  Require(clutter_gap_min >= 0 && clutter_gap_max >= clutter_gap_min && clutter_gap_max <= 3,
          "clutter_gap_max", "gaps with 0 ≤ clutter_gap_min ≤ clutter_gap_max ≤ 3 (m)");
  if (clutter_share > 0) {
    const auto names = [&](const char* c) {
      return std::find(object_categories.begin(), object_categories.end(), c) !=
             object_categories.end();
    };
    Require(!object_categories.empty() && !names("table") && !names("desk"), "object_categories",
            "the target categories, without table or desk, when clutter_share > 0 (the clutter "
            "tables must not become targets)");
  }
}

namespace {

// A table, desk or coffee table in front of `piece` (its +x is the front), `gap` from the
// front face, its long side across the piece's front, shifted `lateral` along it.
scene::Object ClutterTable(const scene::Object& piece, int kind, double gap, double lateral,
                           const std::string& instance) {
  const char* category = kind == 1 ? "desk" : "table";
  const scene::FurnitureParams p =
      kind == 2 ? scene::CoffeeTableParams() : scene::DefaultFurnitureParams(category);
  scene::Object t = scene::MakeFurniture(category, p, instance);
  const scene::Aabb tb = t.LocalBounds();
  const Eigen::Vector3d t_size = tb.max - tb.min;
  // Turned so that its longer side runs along the piece's front.
  const bool long_x = t_size.x() >= t_size.y();
  const double half_depth = 0.5 * (long_x ? t_size.y() : t_size.x());
  const scene::Aabb pb = piece.LocalBounds();
  const Eigen::Vector3d p_PT(pb.max.x() + gap + half_depth,
                             0.5 * (pb.min.y() + pb.max.y()) + lateral, 0);
  const Eigen::Vector3d p_WT = piece.X_WO * p_PT;
  const double piece_yaw = YawOf(piece.X_WO.linear());
  const double yaw = piece_yaw + (long_x ? M_PI / 2 : 0.0);
  // PlaceObject puts the object's origin: shift by its footprint's centre, turned.
  const Eigen::Vector2d c_T = Eigen::Rotation2Dd(yaw) * (0.5 * (tb.min + tb.max)).head<2>();
  scene::PlaceObject(&t, p_WT.x() - c_T.x(), p_WT.y() - c_T.y(), yaw);
  return t;
}

}  // namespace

scene::Scene BuildTrainingGround(const SkillConfig& config, Rng& rng,
                                 const std::vector<std::string>& default_categories) {
  const auto& cats = config.object.object_categories.empty() ? default_categories
                                                             : config.object.object_categories;
  if (cats.empty())
    ThrowInputError("skill config", "object_categories", "at least one furniture category", "none");
  scene::Scene s;
  s.name = "training_ground_" + config.skill;
  const int n = std::max(1, config.object.num_objects);
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (int i = 0; i < n; ++i) {
    const std::string& cat = cats[i % cats.size()];
    scene::Object o = scene::RandomFurniture(
        cat, rng, config.object.held_out_objects, cat + "_" + std::to_string(i),
        {config.object.training_scale_min, config.object.training_scale_max});
    const double yaw = rng.Uniform(-M_PI, M_PI);
    scene::PlaceObject(&o, (i % side) * kTrainingGroundSpacing, (i / side) * kTrainingGroundSpacing,
                       yaw);
    // Drawn only when clutter is on, so grounds without it keep their random streams.
    const auto& c = config.object;
    std::optional<scene::Object> table;
    if (c.clutter_share > 0 && rng.Bernoulli(c.clutter_share)) {
      const int kind = static_cast<int>(rng.UniformInt(3));
      const double gap = rng.Uniform(c.clutter_gap_min, c.clutter_gap_max);
      const double lateral = rng.Uniform(-0.3, 0.3);
      table = ClutterTable(o, kind, gap, lateral, "clutter_" + std::to_string(i));
    }
    s.AddObject(std::move(o));
    if (table) s.AddObject(std::move(*table));
  }
  return s;
}

const ObjectPart* ObjectGeometry::part(std::string_view name) const {
  for (const ObjectPart& p : parts)
    if (p.name == name) return &p;
  return nullptr;
}

int ObjectGeometry::part_index(std::string_view name) const {
  const ObjectPart* p = part(name);
  return p ? p->index : -1;
}

std::vector<int> ObjectGeometry::part_indices(std::string_view name) const {
  std::vector<int> out;
  for (const ObjectPart& p : parts)
    if (p.name == name) out.push_back(p.index);
  return out;
}

const scene::Aabb& ObjectGeometry::part_local(std::string_view name) const {
  const ObjectPart* p = part(name);
  SIMS_CHECK_MSG(p != nullptr,
                 "object " + std::to_string(object) + " has no part '" + std::string(name) + "'");
  return p->local;
}

ObjectGeometry DescribeObject(const scene::Scene& scene, int index,
                              const scene::SceneHeightGrid& grid) {
  const scene::Object& o = scene.objects[index];
  ObjectGeometry g;
  g.object = index;
  g.category = o.category;
  g.X_WO = o.X_WO;
  g.yaw = YawOf(o.X_WO.linear());
  g.local = o.LocalBounds();
  const Eigen::Vector3d c = g.local.center();
  g.center = (o.X_WO * Eigen::Vector3d(c.x(), c.y(), 0)).head<2>();
  g.radius = 0.5 * (g.local.max - g.local.min).head<2>().norm();
  for (size_t k = 0; k < o.parts.size(); ++k)
    g.parts.push_back(
        {static_cast<int>(k), o.parts[k].name, PartLocalBounds(o, static_cast<int>(k))});
  const double d = kStandDistance;
  const Eigen::Vector2d candidates[] = {{g.local.max.x() + d, c.y()},
                                        {c.x(), g.local.max.y() + d},
                                        {c.x(), g.local.min.y() - d},
                                        {g.local.min.x() - d, c.y()}};
  for (const auto& q : candidates) {
    const Eigen::Vector3d p = o.X_WO * Eigen::Vector3d(q.x(), q.y(), 0);
    if (FreeAt(grid, p.head<2>(), 0.25)) g.stand_points.emplace_back(p.x(), p.y(), 0.0);
  }
  return g;
}

ClipPlacement ClipPlacement::Align(const Eigen::Vector2d& p_world, double yaw_world,
                                   const Eigen::Vector2d& p_clip, double yaw_clip, double dz) {
  ClipPlacement c;
  c.yaw = yaw_world - yaw_clip;
  c.offset = p_world - Eigen::Rotation2Dd(c.yaw) * p_clip;
  c.dz = dz;
  return c;
}

humanoid::HumanoidPose ClipPlacement::Apply(const humanoid::HumanoidPose& p) const {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  humanoid::HumanoidPose out = p;
  out.root_pos = Apply(p.root_pos);
  out.root_rot = q * p.root_rot;
  out.root_lin_vel = q * p.root_lin_vel;
  out.root_ang_vel = q * p.root_ang_vel;
  return out;
}

Eigen::Vector3d ClipPlacement::Apply(const Eigen::Vector3d& p) const {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  return q * p + Eigen::Vector3d(offset.x(), offset.y(), dz);
}

bool ClipFurnitureFrame(const motion::MotionClip& clip, const ObjectGeometry& g,
                        double lateral_offset, Eigen::Vector2d* p_clip, double* yaw_clip,
                        double* dz) {
  const auto& m = clip.meta();
  const auto& prm = m.params;
  for (const char* key :
       {"furniture_height", "furniture_width", "furniture_front_x", "furniture_center_y"})
    if (!prm.count(key)) return false;
  const double h = prm.at("furniture_height"), w = prm.at("furniture_width");
  const double fx = prm.at("furniture_front_x"), cy = prm.at("furniture_center_y");
  auto fits = [&](const char* what) {
    return std::find(m.furniture.begin(), m.furniture.end(), what) != m.furniture.end();
  };
  // A sofa lie-down lies along the seat like a seat clip sits on it; lateral_offset is then the
  // lie skill's side (the arm the head goes to), which only the clips with their head that way
  // (+y, or −y when mirrored) fit.
  const bool sofa_lie = m.skill == "lie" && fits("sofa") && !fits("bed");
  if (sofa_lie && lateral_offset != 0 && (lateral_offset < 0) != m.mirrored) return false;
  const bool bed = !sofa_lie && (m.skill == "lie" || fits("bed"));
  if (!bed) {
    // Seat clips: the character faces +x with the seat behind it, seat front edge at x = fx;
    // the object faces the same way (+x is a seat's front).
    const ObjectPart* seat = g.part(kSeatPart);
    if (!seat) return false;
    const double sy =
        0.5 * (seat->local.min.y() + seat->local.max.y()) + (sofa_lie ? 0.0 : lateral_offset);
    *p_clip = Eigen::Vector2d(fx - seat->local.max.x(), cy - sy);
    *yaw_clip = 0;
    *dz = seat->local.max.z() - h;
    return true;
  }
  // Bed clips: the bed's long axis is the clip's y with the head toward +y (−y when mirrored);
  // the character approaches its long side from +x. A procedural bed's long axis is its x
  // with the headboard at −x, so object −x ↦ clip ±y and the mattress edge ↦ x = fx.
  const ObjectPart* mattress = g.part(kMattressPart);
  if (!mattress) return false;
  const double s = m.mirrored ? -1.0 : 1.0;
  const double ly_edge = s > 0 ? mattress->local.max.y() : mattress->local.min.y();
  const double lx_head = mattress->local.min.x();
  const double y_head = cy + s * w / 2;
  *p_clip = Eigen::Vector2d(fx - s * ly_edge, y_head + s * lx_head);
  *yaw_clip = -s * M_PI / 2;
  *dz = mattress->local.max.z() - h;
  return true;
}

double SeatLateral(const ObjectGeometry& g, Rng& rng) {
  const ObjectPart* seat = g.part(kSeatPart);
  if (!seat) return 0;
  const double half = 0.5 * (seat->local.max.y() - seat->local.min.y()) - 0.35;
  return half > 0 ? rng.Uniform(-half, half) : 0.0;
}

Eigen::Vector2d FacingOf(const humanoid::HumanoidPose& pose) {
  const double h = humanoid::HeadingAngle(pose.root_rot);
  return {std::cos(h), std::sin(h)};
}

Eigen::Vector3d NearestOnPart(const scene::Scene& scene, int object, int part,
                              const Eigen::Vector3d& p) {
  return scene::NearestPointOnPart(scene.objects[object].parts[part], p);
}

ObjectSkill::ObjectSkill(const SkillConfig& config, const SkillContext& context)
    : Skill(config, context) {
  SIMS_CHECK(context.scene != nullptr);
  const int n = context.num_envs;
  ObjectState initial;
  initial.level = config.object.spawn_curriculum ? 0.0 : 1.0;
  env_.assign(n, initial);
  override_.assign(n, -1);
  // Only resets draw them (a story's skill begins where the story is).
  handoff_ = config.object.handoff_share > 0 ? SharedHandoffStates(config.object.handoff_states)
                                             : std::make_shared<const std::vector<HandoffState>>();
}

const std::vector<HandoffState>& ObjectSkill::handoff_states() const { return *handoff_; }

std::string ObjectSkill::start_label(int env_id) const {
  return env_[env_id].handoff ? "handoff" : "";
}

void ObjectSkill::SetSpawnLevel(int env_id, double level) {
  SIMS_CHECK(level >= 0 && level <= 1);
  env_[env_id].level = level;
}

double ObjectSkill::curriculum_level(int env_id) const {
  return config_.object.spawn_curriculum ? env_[env_id].level
                                         : std::numeric_limits<double>::quiet_NaN();
}

double ObjectSkill::ClipContactTime(int clip) const {
  return context_.motions->clip(clip).duration();
}

void ObjectSkill::PrepareReferenceClips() {
  if (!context_.motions) return;
  pre_contact_.assign(context_.motions->num_clips(), -1.0);
  std::vector<int> kept;
  for (int c : reference_clips_) {
    const double t = ClipContactTime(c);
    if (t < kMinPreContactTime) continue;  // already in contact: idle clips
    pre_contact_[c] = t;
    kept.push_back(c);
  }
  reference_clips_ = std::move(kept);
}

double ObjectSkill::pre_contact_time(int clip) const {
  return clip >= 0 && clip < static_cast<int>(pre_contact_.size()) ? pre_contact_[clip] : -1.0;
}

double ObjectSkill::PreContactTime(int clip, Rng& rng) const {
  const double duration = context_.motions->clip(clip).duration();
  double end = config_.reference_init_max_fraction * duration;
  const double contact = pre_contact_time(clip);
  if (contact >= 0) end = std::min(end, contact);
  const double window = config_.object.reference_window;
  return rng.Uniform(window > 0 ? std::max(0.0, end - window) : 0.0, end);
}

void ObjectSkill::SetEpisodeTarget(int env_id, const Eigen::Vector3d& target_W,
                                   const Eigen::Vector2d& anchor_W) {
  env_[env_id].target_W = target_W;
  env_[env_id].anchor_W = anchor_W;
}

void ObjectSkill::ObserveTask(const sim::EnvView& view, float* out) const {
  if (!observes_object()) return;
  const int i = view.env_id;
  const humanoid::BodyStates& b = *view.bodies;
  const Eigen::Vector3d root = b.pos[humanoid::kPelvis];
  const Eigen::Quaterniond h_inv = humanoid::HeadingInverse(b.rot[humanoid::kPelvis]);
  auto put = [&out](const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) *out++ = static_cast<float>(v[k]);
  };
  put(h_inv * (env_[i].target_W - root));
  const ObjectGeometry& g = geometry(i);
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p_O((c & 1) ? g.local.max.x() : g.local.min.x(),
                              (c & 2) ? g.local.max.y() : g.local.min.y(),
                              (c & 4) ? g.local.max.z() : g.local.min.z());
    put(h_inv * (g.ToWorld(p_O) - root));
  }
  const Eigen::Vector3d facing = h_inv * (g.X_WO.linear() * Eigen::Vector3d::UnitX());
  *out++ = static_cast<float>(facing.x());
  *out++ = static_cast<float>(facing.y());
}

void ObjectSkill::CollectObjects(const std::string& what) {
  const scene::Scene& s = *context_.scene;
  const auto& cats = config_.object.object_categories;
  for (int i = 0; i < static_cast<int>(s.objects.size()); ++i) {
    if (!cats.empty() && std::find(cats.begin(), cats.end(), s.objects[i].category) == cats.end())
      continue;
    ObjectGeometry g = DescribeObject(s, i, *context_.height_grid);
    if (Accepts(g)) objects_.push_back(std::move(g));
  }
  if (objects_.empty())
    ThrowInputError("scene '" + s.name + "'", "objects", "at least one " + what,
                    std::to_string(s.objects.size()) + " objects, none suitable");
}

int ObjectSkill::SlotOf(int scene_object) const {
  for (size_t k = 0; k < objects_.size(); ++k)
    if (objects_[k].object == scene_object) return static_cast<int>(k);
  return -1;
}

bool ObjectSkill::BeginInstruction(const sim::EnvView& view, const InstructionTarget& target) {
  const int i = view.env_id;
  int k = target.object >= 0 ? SlotOf(target.object) : -1;
  if (target.object < 0) {  // no object named: the nearest one
    double best = std::numeric_limits<double>::infinity();
    const Eigen::Vector2d pelvis = view.pose->root_pos.head<2>();
    for (size_t j = 0; j < objects_.size(); ++j) {
      const double d = (objects_[j].center - pelvis).squaredNorm();
      if (d < best) best = d, k = static_cast<int>(j);
    }
  }
  if (k < 0) return false;
  env_[i].object = k;
  env_[i].hold = 0;
  Rng rng(0x5EEDull + static_cast<uint64_t>(objects_[k].object));  // same task every time
  SampleTask(i, rng);
  OnReset(view, rng);
  return true;
}

void ObjectSkill::SetObjectOverride(int env_id, int k) {
  SIMS_CHECK(k >= -1 && k < static_cast<int>(objects_.size()));
  override_[env_id] = k;
}

uint32_t ObjectSkill::contact_body_mask() const {
  using namespace humanoid;
  return (1u << kLeftFoot) | (1u << kRightFoot) | (1u << kLeftHand) | (1u << kRightHand) |
         (1u << kPelvis) | (1u << kLeftThigh) | (1u << kRightThigh) | (1u << kTorso) |
         (1u << kHead);
}

double ObjectSkill::ContactForce(const sim::EnvView& view) {
  // The free joint's translational constraint force is the sum of all contact forces on the
  // humanoid (self-contacts cancel); qfrc_constraint is left from the last physics step.
  const double* f = view.data->qfrc_constraint + view.humanoid->root_qvel_adr();
  return Eigen::Vector3d(f[0], f[1], f[2]).norm();
}

void ObjectSkill::SampleTask(int, Rng&) {}

bool ObjectSkill::ReferenceInit(int, Rng&, sim::InitialState*) { return false; }

bool ObjectSkill::HandoffInit(int env_id, Rng& rng, sim::InitialState* init) {
  // A few draws: states from another seat height or depth do not fit this object.
  for (int attempt = 0; attempt < kHandoffDraws; ++attempt) {
    const HandoffState& s = (*handoff_)[rng.UniformInt(static_cast<int64_t>(handoff_->size()))];
    const std::optional<humanoid::HumanoidPose> pose = PlaceHandoffState(s, geometry(env_id));
    if (!pose) continue;
    init->pose = *pose;
    init->history.clear();
    init->reference = false;
    SetStyle(env_id, DrawReferenceStyle(rng));
    return true;
  }
  return false;
}

bool ObjectSkill::FreeFloor(const Eigen::Vector2d& p, double radius) const {
  return FreeAt(*context_.height_grid, p, radius);
}

bool ObjectSkill::BlockedByClutter(const ObjectGeometry& g, const Eigen::Vector2d& p_W) const {
  constexpr double kRadius = 0.15, kMargin = 0.05;
  const Eigen::Isometry3d X_OW = g.X_WO.inverse();
  return AnyOnDisk(p_W, kRadius, [&](const Eigen::Vector2d& q) {
    if (context_.height_grid->Height(q.x(), q.y()) < kFloorTolerance) return false;
    const Eigen::Vector3d q_O = X_OW * Eigen::Vector3d(q.x(), q.y(), 0);
    const bool own = q_O.x() > g.local.min.x() - kMargin && q_O.x() < g.local.max.x() + kMargin &&
                     q_O.y() > g.local.min.y() - kMargin && q_O.y() < g.local.max.y() + kMargin;
    return !own;  // something else stands there
  });
}

Eigen::Vector2d ObjectSkill::SpawnPoint(int env_id, const ObjectGeometry& g, Rng& rng) const {
  const auto& o = config_.object;
  // Drawn only when the share is set, so configs without it keep their random streams.
  const bool full = o.spawn_full_range_share > 0 && rng.Bernoulli(o.spawn_full_range_share);
  const double level = full ? 1.0 : env_[env_id].level;
  const double far = o.spawn_min_distance + level * (o.spawn_max_distance - o.spawn_min_distance);
  const double half_arc = 0.5 * o.spawn_arc_deg * M_PI / 180.0;
  Eigen::Vector2d p = g.center;
  for (int attempt = 0; attempt < 32; ++attempt) {
    const double r = g.radius + rng.Uniform(o.spawn_min_distance, far);
    const double a = g.yaw + rng.Uniform(-half_arc, half_arc);
    p = g.center + r * Eigen::Vector2d(std::cos(a), std::sin(a));
    if (FreeFloor(p, 0.35)) return p;
  }
  return p;
}

void ObjectSkill::DefaultInit(int env_id, Rng& rng, sim::InitialState* init) {
  const Eigen::Vector2d p = SpawnPoint(env_id, geometry(env_id), rng);
  const double yaw = rng.Uniform(-M_PI, M_PI);
  init->pose.root_pos.x() = p.x();
  init->pose.root_pos.y() = p.y();
  init->pose.root_rot = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  SetStyle(env_id, DrawReferenceStyle(rng));
}

void ObjectSkill::SampleInitialState(int env_id, Rng& rng, sim::InitialState* init) {
  // The curriculum learns from the episode that just ended (default starts only: reference
  // and hand-off starts begin on or next to the object whatever the level).
  if (config_.object.spawn_curriculum && env_[env_id].started && !env_[env_id].reference &&
      !env_[env_id].handoff) {
    const double step = config_.object.spawn_curriculum_step;
    const bool done = env_[env_id].hold >= config_.success_hold_steps;
    env_[env_id].level = NextCurriculumLevel(env_[env_id].level, done, step);
  }
  const int n = static_cast<int>(objects_.size());
  env_[env_id].object =
      override_[env_id] >= 0 ? override_[env_id] : static_cast<int>(rng.UniformInt(n));
  env_[env_id].hold = 0;
  env_[env_id].error = 0;
  SampleTask(env_id, rng);
  const bool try_reference =
      context_.motions && !ReferenceClips().empty() && rng.Bernoulli(config_.reference_init_prob);
  // The share is drawn only when there are states, so configs without them keep their streams.
  const bool handoff = try_reference && !handoff_->empty() &&
                       rng.Bernoulli(config_.object.handoff_share) &&
                       HandoffInit(env_id, rng, init);
  if (!handoff && !(try_reference && ReferenceInit(env_id, rng, init)))
    DefaultInit(env_id, rng, init);
  env_[env_id].started = true;
  env_[env_id].reference = init->reference;
  env_[env_id].handoff = handoff;
}

double NextCurriculumLevel(double level, bool done, double step) {
  return std::clamp(level + (done ? step : -0.5 * step), 0.0, 1.0);
}

double FurnitureShare(const motion::MotionClip& clip, double pelvis_z) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int f = 0; f < clip.num_frames(); ++f) {
    const double z = clip.FramePose(f).root_pos.z();
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  // Seated or lying, the pelvis origin rests up to kPelvisOnFurniture above the top.
  const auto& prm = clip.meta().params;
  const auto top = prm.find("furniture_height");
  const double down = top != prm.end() ? std::max(lo, top->second + kPelvisOnFurniture) : lo;
  if (!(hi - down > 1e-3)) return 1.0;
  return std::clamp((hi - pelvis_z) / (hi - down), 0.0, 1.0);
}

void ObjectSkill::PlaceReference(int env_id, int clip, double t, const ClipPlacement& placement,
                                 sim::InitialState* init) {
  const motion::ReferenceState ref = context_.motions->StateAt(clip, t);
  // The height shift fits the clip's furniture to the object's, but the floor does not move:
  // the shift applies in full while the character is down on the furniture and fades out as
  // the pelvis rises to the clip's standing height, so standing and walking states (before a
  // sit, after a get-up) keep their feet on the floor instead of up to kMaxClipHeightMismatch
  // (beds: getup_bed_raise) inside or above it.
  ClipPlacement p = placement;
  if (p.dz != 0) p.dz *= FurnitureShare(context_.motions->clip(clip), ref.pose.root_pos.z());
  init->pose = p.Apply(ref.pose);
  init->history.clear();
  for (const auto& h : ref.history) init->history.push_back(p.Apply(h));
  init->reference = true;
  SetStyle(env_id, clip);
}

int ObjectSkill::ChooseFurnitureClip(const std::vector<int>& clips, const ObjectGeometry& g,
                                     double lateral, Rng& rng, ClipPlacement* placement,
                                     double max_raise) const {
  if (!context_.motions) return -1;
  // Clips made for the object's own kind come first: a sofa's seated pose sits deep, and on a
  // small stool of the same height it put the pelvis over the back edge (it tipped over).
  std::vector<std::pair<int, ClipPlacement>> fitting, own_kind;
  for (int c : clips) {
    Eigen::Vector2d p_clip;
    double yaw_clip = 0, dz = 0;
    const motion::MotionClip& clip = context_.motions->clip(c);
    if (!ClipFurnitureFrame(clip, g, lateral, &p_clip, &yaw_clip, &dz)) continue;
    if (dz < -kMaxClipHeightMismatch || dz > max_raise) continue;
    fitting.emplace_back(
        c, ClipPlacement::Align(g.X_WO.translation().head<2>(), g.yaw, p_clip, yaw_clip, dz));
    const auto& kinds = clip.meta().furniture;
    if (std::find(kinds.begin(), kinds.end(), g.category) != kinds.end())
      own_kind.push_back(fitting.back());
  }
  const auto& pool = own_kind.empty() ? fitting : own_kind;
  if (pool.empty()) return -1;
  const auto& [clip, p] = pool[rng.UniformInt(static_cast<int64_t>(pool.size()))];
  *placement = p;
  return clip;
}

bool ObjectSkill::FurnitureClipInit(int env_id, double lateral, Rng& rng, sim::InitialState* init) {
  ClipPlacement placement;
  const int clip =
      ChooseFurnitureClip(reference_clips_, geometry(env_id), lateral, rng, &placement);
  if (clip < 0) return false;
  const double t = PreContactTime(clip, rng);
  if (config_.object.clutter_share > 0) {
    // A clip's approach may run through the table in front of the piece: such starts fall
    // back to a standing start on free floor.
    const Eigen::Vector3d root = placement.Apply(context_.motions->StateAt(clip, t).pose.root_pos);
    if (BlockedByClutter(geometry(env_id), root.head<2>())) return false;
  }
  PlaceReference(env_id, clip, t, placement, init);
  return true;
}

sim::TaskStepResult ObjectSkill::ContactRewardStep(const sim::EnvView& view, double goal_sum,
                                                   double d, double wide_share) {
  const ObjectState& e = env_[view.env_id];
  const Eigen::Vector2d root = view.pose->root_pos.head<2>();
  const bool at_target = (e.target_W.head<2>() - root).squaredNorm() <= kFarDistanceSq;
  const double r_far = at_target ? 1.0
                                 : FarReward(e.anchor_W, root, view.pose->root_lin_vel.head<2>(),
                                             FacingOf(*view.pose), config_.target_speed);
  double r_near = NearReward(goal_sum, wide_share + config_.object.wide_near_share,
                             config_.object.precise_near_share);
  const double facing_share = config_.object.near_facing_share;
  if (facing_share > 0) {
    const Eigen::Vector2d front = e.anchor_W - e.target_W.head<2>();
    const double n = front.norm();
    const double cos_front = n > 1e-9 ? FacingOf(*view.pose).dot(front / n) : 1.0;
    r_near *= 1.0 - facing_share + facing_share * std::max(0.0, cos_front);
  }
  const double r = kNearWeight * r_near + (1.0 - kNearWeight) * r_far;
  return Finish(view, r, d < config_.object.contact_success_threshold);
}

sim::TaskStepResult ObjectSkill::Finish(const sim::EnvView& view, double reward, bool success) {
  const int i = view.env_id;
  sim::TaskStepResult r;
  r.reward = static_cast<float>(reward);
  r.success = success;
  env_[i].hold = success ? env_[i].hold + 1 : 0;
  r.completed = env_[i].hold >= config_.success_hold_steps;
  if (r.completed) r.truncate = true;
  if (config_.object.max_contact_force > 0 && ContactForce(view) > config_.object.max_contact_force)
    r.terminate = true;
  return r;
}

void ObjectState::Serialize(StateArchive* a, int num_objects) {
  a->Int("object", &object, 0, num_objects - 1);
  a->Int("hold", &hold, 0, std::numeric_limits<int>::max());
  a->Real("error", &error);
  a->Reals("target", &target_W);
  a->Reals("anchor", &anchor_W);
  a->Real("level", &level);
  a->Flag("started", &started);
  // Once the flag "reference" (0/1), which older snapshots hold; 2 is a hand-off start.
  int start = reference ? 1 : handoff ? 2 : 0;
  a->Int("start", &start, 0, 2);
  reference = start == 1;
  handoff = start == 2;
}

void ObjectSkill::SerializeTaskState(int, StateArchive*) {}

void ObjectSkill::SerializeSkillState(int env_id, StateArchive* a) {
  env_[env_id].Serialize(a, static_cast<int>(objects_.size()));
  SerializeTaskState(env_id, a);
}

}  // namespace sims::task
