#include "sims/io/motion_record.h"

#include <cmath>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/humanoid/model_builder.h"
#include "sims/motion/skeleton.h"

namespace sims::io {

using nlohmann::json;

double MotionRecord::duration() const { return frames.empty() ? 0.0 : (num_frames() - 1) / fps; }

int MotionRecord::KeyframeAt(int frame) const {
  int best = -1;
  for (int k = 0; k < static_cast<int>(keyframes.size()); ++k) {
    const auto& a = keyframes[k];
    if (a.reached() && a.start_frame <= frame &&
        (best < 0 || a.start_frame >= keyframes[best].start_frame))
      best = k;
  }
  return best;
}

void MotionRecord::Validate(const std::string& source) const {
  if (!(fps > 0) || !std::isfinite(fps))
    ThrowInputError(source, "fps", "a positive frame rate", std::to_string(fps));
  const double tol = 0.5 / fps;
  for (int i = 0; i < num_frames(); ++i) {
    const RecordFrame& f = frames[i];
    const std::string field = "frames[" + std::to_string(i) + "]";
    if (std::abs(f.time - i / fps) > tol)
      ThrowInputError(source, field + ".t", "frame i at time i / fps = " + std::to_string(i / fps),
                      std::to_string(f.time));
    bool finite =
        f.root_pos.allFinite() && f.root_rot.coeffs().allFinite() && f.dof_pos.allFinite();
    for (int b = 0; b < humanoid::kNumBodies; ++b)
      finite = finite && f.body_pos[b].allFinite() && f.body_rot[b].coeffs().allFinite();
    if (!finite) ThrowInputError(source, field, "finite numbers", "NaN or infinity");
  }
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    const auto& a = keyframes[k];
    const std::string field = "keyframes[" + std::to_string(k) + "]";
    if (a.start_frame == -1 && a.end_frame == -1) continue;
    if (a.start_frame < 0 || a.end_frame < a.start_frame || a.end_frame >= num_frames())
      ThrowInputError(source, field + ".start_frame/end_frame",
                      "0 <= start_frame <= end_frame < num_frames (" +
                          std::to_string(num_frames()) + "), or both -1 when never reached",
                      std::to_string(a.start_frame) + ".." + std::to_string(a.end_frame));
  }
}

// ---------------------------------------------------------------------------------------------
// Builder.

struct MotionRecordBuilder::Scratch {
  humanoid::MjDataPtr data;
  humanoid::BodyStates bodies;
};

MotionRecordBuilder::MotionRecordBuilder(std::shared_ptr<const humanoid::Humanoid> humanoid,
                                         double fps)
    : humanoid_(humanoid ? std::move(humanoid) : motion::HumanoidSkeleton::DefaultHumanoid()),
      scratch_(std::make_unique<Scratch>()) {
  SIMS_CHECK_MSG(fps > 0, "MotionRecordBuilder needs a positive fps");
  scratch_->data = humanoid::MakeData(humanoid_->model());
  record_.fps = fps;
}

MotionRecordBuilder::~MotionRecordBuilder() = default;

void MotionRecordBuilder::SetTitle(const std::string& title) { record_.title = title; }

void MotionRecordBuilder::SetScene(const SceneRef& scene) { record_.scene = scene; }

int MotionRecordBuilder::AddFrame(const humanoid::HumanoidPose& pose) {
  humanoid::ForwardKinematics(*humanoid_, pose, scratch_->data.get(), &scratch_->bodies);
  RecordFrame f;
  f.time = record_.num_frames() / record_.fps;
  f.root_pos = pose.root_pos;
  f.root_rot = pose.root_rot.normalized();
  f.dof_pos = pose.dof_pos;
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    f.body_pos[b] = scratch_->bodies.pos[b];
    f.body_rot[b] = scratch_->bodies.rot[b].normalized();
  }
  record_.frames.push_back(f);
  return record_.num_frames() - 1;
}

void MotionRecordBuilder::BeginKeyframe(KeyframeAnnotation annotation) {
  if (open_) EndKeyframe(false, "superseded before it finished");
  annotation.start_frame = record_.num_frames();
  annotation.end_frame = -1;
  open_ = std::move(annotation);
}

void MotionRecordBuilder::EndKeyframe(bool success, const std::string& detail) {
  SIMS_CHECK_MSG(open_.has_value(), "EndKeyframe without BeginKeyframe");
  KeyframeAnnotation a = std::move(*open_);
  open_.reset();
  if (record_.num_frames() <= a.start_frame) {
    // No frame was recorded while it was open: it never ran.
    a.start_frame = a.end_frame = -1;
  } else {
    a.end_frame = record_.num_frames() - 1;
  }
  a.success = success;
  if (!detail.empty()) a.detail = detail;
  record_.keyframes.push_back(std::move(a));
}

void MotionRecordBuilder::AddKeyframe(const KeyframeAnnotation& annotation) {
  record_.keyframes.push_back(annotation);
}

MotionRecord MotionRecordBuilder::Finish() {
  if (open_) EndKeyframe(false, "unfinished");
  record_.Validate("MotionRecordBuilder");
  MotionRecord out = std::move(record_);
  record_ = MotionRecord{};
  record_.fps = out.fps;
  return out;
}

// ---------------------------------------------------------------------------------------------
// JSON.

namespace {

double Round6(double v) { return std::round(v * 1e6) / 1e6; }

json Vec(const Eigen::Vector3d& v) {
  return json::array({Round6(v.x()), Round6(v.y()), Round6(v.z())});
}

json Quat(const Eigen::Quaterniond& q) {
  return json::array({Round6(q.w()), Round6(q.x()), Round6(q.y()), Round6(q.z())});
}

// Reads fields of one JSON value and reports the dotted path of whatever is wrong.
class Reader {
 public:
  Reader(const std::string& source) : source_(source) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& expected,
                         const json* got) const {
    std::string g;
    if (got) {
      g = got->dump();
      if (g.size() > 60) g = g.substr(0, 57) + "...";
    } else {
      g = "missing";
    }
    ThrowInputError(source_, field, expected, g);
  }

  const json& Get(const json& obj, const std::string& parent, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) Fail(Join(parent, key), "a value", nullptr);
    return *it;
  }

  double Number(const json& v, const std::string& field) const {
    if (!v.is_number()) Fail(field, "a number", &v);
    const double d = v.get<double>();
    if (!std::isfinite(d)) Fail(field, "a finite number", &v);
    return d;
  }

  int Int(const json& v, const std::string& field) const {
    if (!v.is_number_integer()) Fail(field, "an integer", &v);
    return v.get<int>();
  }

  std::string String(const json& obj, const std::string& parent, const char* key,
                     bool required = false) const {
    auto it = obj.find(key);
    if (it == obj.end()) {
      if (required) Fail(Join(parent, key), "a string", nullptr);
      return {};
    }
    if (!it->is_string()) Fail(Join(parent, key), "a string", &*it);
    return it->get<std::string>();
  }

  template <int N>
  Eigen::Matrix<double, N, 1> Array(const json& v, const std::string& field) const {
    if (!v.is_array() || v.size() != N)
      Fail(field, "an array of " + std::to_string(N) + " numbers", &v);
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i) out[i] = Number(v[i], field + "[" + std::to_string(i) + "]");
    return out;
  }

  Eigen::Quaterniond Quaternion(const json& v, const std::string& field) const {
    const Eigen::Vector4d q = Array<4>(v, field);
    if (q.norm() < 0.5 || q.norm() > 1.5) Fail(field, "a unit quaternion [w, x, y, z]", &v);
    return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
  }

  static std::string Join(const std::string& parent, const char* key) {
    return parent.empty() ? std::string(key) : parent + "." + key;
  }

 private:
  std::string source_;
};

}  // namespace

json MotionRecordToJson(const MotionRecord& record) {
  json j;
  j["format"] = kMotionRecordFormat;
  j["version"] = kMotionRecordVersion;
  j["title"] = record.title;
  j["fps"] = record.fps;
  j["scene"] = {{"name", record.scene.name}, {"source", record.scene.source}};
  const auto& skel = motion::HumanoidSkeleton::Default();
  json bodies = json::array(), parents = json::array(), dofs = json::array();
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    bodies.push_back(humanoid::BodyNames()[b]);
    parents.push_back(skel.parent[b]);
  }
  for (const char* d : humanoid::DofNames()) dofs.push_back(d);
  j["skeleton"] = {{"bodies", bodies}, {"parents", parents}, {"dofs", dofs},
                   {"up", "z"},        {"units", "m"},       {"quaternion", "wxyz"}};
  j["num_frames"] = record.num_frames();
  json frames = json::array();
  for (const RecordFrame& f : record.frames) {
    json dof = json::array();
    for (int i = 0; i < humanoid::kNumDofs; ++i) dof.push_back(Round6(f.dof_pos[i]));
    json bp = json::array(), br = json::array();
    for (int b = 0; b < humanoid::kNumBodies; ++b) {
      bp.push_back(Vec(f.body_pos[b]));
      br.push_back(Quat(f.body_rot[b]));
    }
    frames.push_back({{"t", Round6(f.time)},
                      {"root_pos", Vec(f.root_pos)},
                      {"root_rot", Quat(f.root_rot)},
                      {"dof_pos", dof},
                      {"body_pos", bp},
                      {"body_rot", br}});
  }
  j["frames"] = std::move(frames);
  json kfs = json::array();
  for (const auto& a : record.keyframes) {
    kfs.push_back({{"index", a.index},
                   {"skill", a.skill},
                   {"caption", a.caption},
                   {"emotion", a.emotion},
                   {"furniture", a.furniture},
                   {"start_frame", a.start_frame},
                   {"end_frame", a.end_frame},
                   {"success", a.success},
                   {"detail", a.detail}});
  }
  j["keyframes"] = std::move(kfs);
  return j;
}

MotionRecord MotionRecordFromJson(const json& j, const std::string& source) {
  Reader r(source);
  if (!j.is_object()) r.Fail("", "a JSON object (sims-motion-record)", &j);
  const std::string format = r.String(j, "", "format", true);
  if (format != kMotionRecordFormat)
    r.Fail("format", std::string("\"") + kMotionRecordFormat + "\"", &j["format"]);
  const json& version = r.Get(j, "", "version");
  if (r.Int(version, "version") > kMotionRecordVersion)
    r.Fail("version", "at most " + std::to_string(kMotionRecordVersion), &version);
  MotionRecord rec;
  rec.title = r.String(j, "", "title");
  rec.fps = r.Number(r.Get(j, "", "fps"), "fps");
  if (rec.fps <= 0) r.Fail("fps", "a positive frame rate", &j["fps"]);
  if (auto it = j.find("scene"); it != j.end()) {
    if (!it->is_object()) r.Fail("scene", "an object {name, source}", &*it);
    rec.scene.name = r.String(*it, "scene", "name");
    rec.scene.source = r.String(*it, "scene", "source");
  }
  if (auto it = j.find("skeleton"); it != j.end()) {
    // The skeleton block documents the layout; a record from another body layout is refused.
    const json& bodies = r.Get(*it, "skeleton", "bodies");
    bool same = bodies.is_array() && bodies.size() == humanoid::kNumBodies;
    for (int b = 0; same && b < humanoid::kNumBodies; ++b)
      same = bodies[b].is_string() && bodies[b].get<std::string>() == humanoid::BodyNames()[b];
    if (!same)
      r.Fail("skeleton.bodies", "the 15 AMP body names in order (pelvis, torso, ...)", &bodies);
  }
  const json& frames = r.Get(j, "", "frames");
  if (!frames.is_array()) r.Fail("frames", "an array of frames", &frames);
  if (auto it = j.find("num_frames");
      it != j.end() && r.Int(*it, "num_frames") != static_cast<int>(frames.size()))
    r.Fail("num_frames", "the length of frames (" + std::to_string(frames.size()) + ")", &*it);
  rec.frames.resize(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string p = "frames[" + std::to_string(i) + "]";
    const json& fj = frames[i];
    if (!fj.is_object()) r.Fail(p, "an object", &fj);
    RecordFrame& f = rec.frames[i];
    f.time = r.Number(r.Get(fj, p, "t"), p + ".t");
    f.root_pos = r.Array<3>(r.Get(fj, p, "root_pos"), p + ".root_pos");
    f.root_rot = r.Quaternion(r.Get(fj, p, "root_rot"), p + ".root_rot");
    f.dof_pos = r.Array<humanoid::kNumDofs>(r.Get(fj, p, "dof_pos"), p + ".dof_pos");
    const json& bp = r.Get(fj, p, "body_pos");
    const json& br = r.Get(fj, p, "body_rot");
    if (!bp.is_array() || bp.size() != humanoid::kNumBodies)
      r.Fail(p + ".body_pos", "15 [x, y, z] arrays", &bp);
    if (!br.is_array() || br.size() != humanoid::kNumBodies)
      r.Fail(p + ".body_rot", "15 [w, x, y, z] arrays", &br);
    for (int b = 0; b < humanoid::kNumBodies; ++b) {
      f.body_pos[b] = r.Array<3>(bp[b], p + ".body_pos[" + std::to_string(b) + "]");
      f.body_rot[b] = r.Quaternion(br[b], p + ".body_rot[" + std::to_string(b) + "]");
    }
  }
  if (auto it = j.find("keyframes"); it != j.end()) {
    if (!it->is_array()) r.Fail("keyframes", "an array", &*it);
    for (std::size_t k = 0; k < it->size(); ++k) {
      const std::string p = "keyframes[" + std::to_string(k) + "]";
      const json& kj = (*it)[k];
      if (!kj.is_object()) r.Fail(p, "an object", &kj);
      KeyframeAnnotation a;
      a.index = kj.contains("index") ? r.Int(kj["index"], p + ".index") : static_cast<int>(k);
      a.skill = r.String(kj, p, "skill", true);
      a.caption = r.String(kj, p, "caption");
      a.emotion = r.String(kj, p, "emotion");
      a.furniture = r.String(kj, p, "furniture");
      a.start_frame = r.Int(r.Get(kj, p, "start_frame"), p + ".start_frame");
      a.end_frame = r.Int(r.Get(kj, p, "end_frame"), p + ".end_frame");
      const json& s = r.Get(kj, p, "success");
      if (!s.is_boolean()) r.Fail(p + ".success", "true or false", &s);
      a.success = s.get<bool>();
      a.detail = r.String(kj, p, "detail");
      rec.keyframes.push_back(std::move(a));
    }
  }
  rec.Validate(source);
  return rec;
}

void SaveMotionRecord(const MotionRecord& record, const std::filesystem::path& path) {
  record.Validate(path.string());
  // One frame per line keeps the file diffable and readable without a viewer.
  json j = MotionRecordToJson(record);
  json frames = std::move(j["frames"]);
  json keyframes = std::move(j["keyframes"]);
  j.erase("frames");
  j.erase("keyframes");
  std::string head = j.dump(1);
  head.pop_back();  // the closing brace
  while (!head.empty() && (head.back() == '\n' || head.back() == ' ')) head.pop_back();
  std::string out = head + ",\n \"keyframes\": [";
  for (std::size_t k = 0; k < keyframes.size(); ++k)
    out += (k ? ",\n  " : "\n  ") + keyframes[k].dump();
  out += keyframes.empty() ? "],\n" : "\n ],\n";
  out += " \"frames\": [";
  for (std::size_t i = 0; i < frames.size(); ++i) out += (i ? ",\n  " : "\n  ") + frames[i].dump();
  out += frames.empty() ? "]\n}\n" : "\n ]\n}\n";
  WriteFileAtomic(path, out);
}

MotionRecord LoadMotionRecord(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path))
    ThrowInputError(path.string(), "", "a motion record (motion.json)", "no such file");
  return MotionRecordFromJson(ReadJsonFile(path), path.string());
}

MotionRecord LoadMotionRecordOrClip(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path))
    ThrowInputError(path.string(), "", "a motion record (motion.json) or a motion clip",
                    "no such file");
  const json j = ReadJsonFile(path);
  if (j.is_object() && j.value("format", std::string()) == kMotionRecordFormat)
    return MotionRecordFromJson(j, path.string());
  try {
    return RecordFromClip(motion::LoadClip(path));
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + " (and it is no motion record: format is not \"" +
                kMotionRecordFormat + "\")");
  }
}

motion::MotionClip RecordToClip(const MotionRecord& record) {
  if (record.frames.empty())
    ThrowInputError("motion record", "frames", "at least one frame", "none");
  std::vector<motion::MotionFrame> frames;
  frames.reserve(record.frames.size());
  for (const RecordFrame& f : record.frames) {
    motion::MotionFrame m;
    m.root_pos = f.root_pos;
    m.root_rot = f.root_rot;
    m.dof_pos = f.dof_pos;
    frames.push_back(m);
  }
  motion::MotionMeta meta;
  meta.name = record.title.empty() ? "story" : record.title;
  meta.source = "motion record";
  return motion::MotionClip(record.fps, std::move(frames), meta);
}

MotionRecord RecordFromClip(const motion::MotionClip& clip, double fps,
                            std::shared_ptr<const humanoid::Humanoid> humanoid) {
  if (clip.num_frames() == 0)
    ThrowInputError(clip.meta().name, "frames", "at least one frame", "none");
  MotionRecordBuilder builder(std::move(humanoid), fps);
  builder.SetTitle(clip.meta().name);
  KeyframeAnnotation a;
  a.skill = clip.meta().skill;
  a.caption = clip.meta().captions.empty() ? clip.meta().name : clip.meta().captions.front();
  a.emotion = clip.meta().emotion;
  builder.BeginKeyframe(a);
  const int n = std::max(1, static_cast<int>(std::floor(clip.duration() * fps + 1e-9)) + 1);
  for (int i = 0; i < n; ++i) builder.AddFrame(clip.SamplePose(i / fps));
  builder.EndKeyframe(true);
  return builder.Finish();
}

}  // namespace sims::io
