#include "sims/io/video.h"

#include <GL/osmesa.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/progress.h"
#include "sims/humanoid/humanoid.h"
#include "sims/humanoid/state.h"
#include "sims/io/subprocess.h"
#include "sims/sim/scene_physics.h"

namespace sims::io {

void VideoOptions::Validate() const {
  Require(width >= 16 && width <= 4096 && width % 2 == 0, "width", "an even size in 16..4096");
  Require(height >= 16 && height <= 4096 && height % 2 == 0, "height", "an even size in 16..4096");
  Require(fps >= 0, "fps", "0 (the record's rate) or a positive rate");
  Require(max_frames >= 0, "max_frames", "0 (all) or a positive count");
  Require(camera_distance > 0, "camera_distance", "a positive distance");
  Require(position_smoothing_s >= 0 && heading_smoothing_s >= 0, "position_smoothing_s",
          "non-negative smoothing times");
  Require(occluder_alpha >= 0 && occluder_alpha <= 1, "occluder_alpha", "an opacity in [0, 1]");
  Require(shadow_size >= 64 && shadow_size <= 8192, "shadow_size", "a size in 64..8192");
  Require(multisamples >= 0 && multisamples <= 16, "multisamples", "0..16 samples");
  Require(crf >= 0 && crf <= 51, "crf", "an H.264 quality in 0..51");
  Require(!ffmpeg.empty(), "ffmpeg", "an executable name");
}

namespace {

using Clock = std::chrono::steady_clock;

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};

// An OSMesa context made current on this thread for the lifetime of the object.
class OsMesaContext {
 public:
  OsMesaContext(int width, int height) : buffer_(static_cast<std::size_t>(width) * height * 4) {
    ctx_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
    if (!ctx_)
      ThrowInputError("OSMesa", "", "a software GL context (Debian libosmesa6)", "creation failed");
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, width, height)) {
      OSMesaDestroyContext(ctx_);
      ThrowInputError("OSMesa", "", "a current GL context", "OSMesaMakeCurrent failed");
    }
  }
  ~OsMesaContext() { OSMesaDestroyContext(ctx_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

 private:
  std::vector<unsigned char> buffer_;
  OSMesaContext ctx_ = nullptr;
};

// MuJoCo's visualisation objects, freed in reverse order.
struct MjvState {
  mjvScene scn;
  mjrContext con;
  mjvOption opt;
  mjvCamera cam;
  MjvState(const mjModel* m, int maxgeom, int fontscale) {
    mjv_defaultScene(&scn);
    mjr_defaultContext(&con);
    mjv_defaultOption(&opt);
    mjv_defaultCamera(&cam);
    mjv_makeScene(m, &scn, maxgeom);
    mjr_makeContext(m, &con, fontscale);
  }
  ~MjvState() {
    mjr_freeContext(&con);
    mjv_freeScene(&scn);
  }
};

// Heading (yaw of the pelvis x axis) per frame, unwrapped; frames where the axis points
// straight up or down keep the previous heading.
std::vector<double> Headings(const MotionRecord& rec) {
  std::vector<double> h(rec.frames.size(), 0.0);
  double prev = 0;
  int first = -1;
  for (std::size_t i = 0; i < rec.frames.size(); ++i) {
    const Eigen::Vector3d x = rec.frames[i].root_rot * Eigen::Vector3d::UnitX();
    double a = prev;
    if (x.head<2>().norm() > 0.2) {
      a = std::atan2(x.y(), x.x());
      if (first >= 0) a = prev + std::remainder(a - prev, 2 * M_PI);
      if (first < 0) first = static_cast<int>(i);
    }
    h[i] = prev = a;
  }
  // Frames before the first well-defined heading take it.
  for (int i = 0; i < first; ++i) h[i] = h[first];
  return h;
}

// Greedy word wrap into lines of at most `width` characters.
std::vector<std::string> Wrap(const std::string& text, int width) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string word, line;
  while (in >> word) {
    if (!line.empty() && static_cast<int>(line.size() + 1 + word.size()) > width) {
      lines.push_back(line);
      line.clear();
    }
    if (static_cast<int>(word.size()) > width) word = word.substr(0, width - 3) + "...";
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

// MuJoCo's fonts are ASCII; anything else becomes '?'.
std::string Ascii(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c >= 0x80 && c < 0xC0) continue;  // UTF-8 continuation bytes
    out.push_back(c >= 0x20 && c < 0x7F ? static_cast<char>(c) : '?');
  }
  return out;
}

std::string ReadTail(const std::filesystem::path& p, std::size_t max_bytes = 2000) {
  std::ifstream in(p, std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (s.size() > max_bytes) s = s.substr(s.size() - max_bytes);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// Removes the temporary files unless released.
struct TempFiles {
  std::vector<std::filesystem::path> paths;
  ~TempFiles() {
    std::error_code ec;
    for (const auto& p : paths) std::filesystem::remove(p, ec);
  }
};

// Distance along p0→p1 (as a fraction) where the segment enters the box of half extents
// `half` centred at the origin; false when it misses.
bool SegmentHitsBox(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                    const Eigen::Vector3d& half) {
  double t0 = 0, t1 = 1;
  const Eigen::Vector3d d = p1 - p0;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (std::abs(p0[k]) > half[k]) return false;
      continue;
    }
    double a = (-half[k] - p0[k]) / d[k], b = (half[k] - p0[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

bool SegmentHitsSphere(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                       const Eigen::Vector3d& c, double r) {
  const Eigen::Vector3d d = p1 - p0;
  const double t = std::clamp((c - p0).dot(d) / std::max(d.squaredNorm(), 1e-12), 0.0, 1.0);
  return (p0 + t * d - c).norm() < r;
}

constexpr double kCameraClearance = 0.3;

// Furniture and wall pieces between the camera and the character become see-through, so the
// camera never needs to dodge them. Segments stop short of the body so the chair the
// character sits on stays solid.
void FadeOccluders(const mjModel* m, const mjData* d, const humanoid::Humanoid& h, double alpha,
                   mjvScene* scn) {
  mjtNum head[3], fwd[3], up[3];
  mjv_cameraInModel(head, fwd, up, scn);
  const Eigen::Vector3d cam(head[0], head[1], head[2]);
  std::vector<Eigen::Vector3d> targets;
  for (int b : {humanoid::kPelvis, humanoid::kTorso, humanoid::kHead}) {
    const mjtNum* x = d->xpos + 3 * h.body_id(b);
    Eigen::Vector3d p(x[0], x[1], x[2]);
    const Eigen::Vector3d to_cam = cam - p;
    const double stop = std::min(0.35, 0.5 * to_cam.norm());
    targets.push_back(p + stop * to_cam.normalized());
  }
  for (int i = 0; i < scn->ngeom; ++i) {
    mjvGeom& g = scn->geoms[i];
    if (g.category != mjCAT_STATIC || g.objtype != mjOBJ_GEOM || g.type == mjGEOM_PLANE) continue;
    const Eigen::Vector3d pos(g.pos[0], g.pos[1], g.pos[2]);
    bool hit = false;
    for (const auto& t : targets) {
      if (g.type == mjGEOM_BOX) {
        Eigen::Matrix3d R;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) R(r, c) = g.mat[3 * r + c];
        const Eigen::Vector3d half(g.size[0], g.size[1], g.size[2]);
        const Eigen::Vector3d c_local = R.transpose() * (cam - pos);
        // A piece right at the camera would fill the frame: fade it too.
        hit = (c_local.cwiseAbs() - half).maxCoeff() < kCameraClearance ||
              SegmentHitsBox(c_local, R.transpose() * (t - pos), half);
      } else {
        hit = (cam - pos).norm() < m->geom_rbound[g.objid] + kCameraClearance ||
              SegmentHitsSphere(cam, t, pos, m->geom_rbound[g.objid]);
      }
      if (hit) break;
    }
    if (hit) {
      g.rgba[3] = std::min(g.rgba[3], static_cast<float>(alpha));
      g.transparent = 1;
    }
  }
}

std::string Fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
  return buf;
}

VideoStats RenderModel(const MotionRecord& rec, humanoid::StaticGeometry geometry,
                       const std::filesystem::path& mp4, const VideoOptions& options) {
  ValidateConfig(options, "VideoOptions");
  if (rec.frames.empty()) ThrowInputError("motion record", "frames", "at least one frame", "none");
  rec.Validate("motion record");
  if (!ProgramAvailable(options.ffmpeg))
    ThrowInputError(options.ffmpeg, "", "ffmpeg installed (Debian package ffmpeg, cmake/setup.sh)",
                    "not found in PATH");
  const auto t_start = Clock::now();
  const int W = options.width, H = options.height;

  const humanoid::MjModelPtr built = humanoid::BuildModel(geometry);
  mjModel* mutable_model = mj_copyModel(nullptr, built.get());
  SIMS_CHECK(mutable_model != nullptr);
  mutable_model->vis.global.offwidth = std::max(W, 16);
  mutable_model->vis.global.offheight = std::max(H, 16);
  // Software rasterisation pays per pixel: a small shadow map and no MSAA by default.
  mutable_model->vis.quality.shadowsize = options.shadow_size;
  mutable_model->vis.quality.offsamples = options.multisamples;
  const humanoid::MjModelPtr model(mutable_model, humanoid::MjModelDeleter());
  const humanoid::Humanoid humanoid(model);
  const mjModel* m = model.get();
  humanoid::MjDataPtr data = humanoid::MakeData(m);

  OsMesaContext gl(W, H);
  MjvState vis(m, m->ngeom + 64, H > 600 ? mjFONTSCALE_150 : mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &vis.con);
  if (vis.con.currentBuffer != mjFB_OFFSCREEN)
    ThrowInputError("OSMesa", "", "offscreen framebuffer support", "mjr_setBuffer fell back");
  vis.scn.flags[mjRND_SHADOW] = options.shadows ? 1 : 0;
  vis.scn.flags[mjRND_REFLECTION] = options.reflections ? 1 : 0;
  double gl_s = 0, pipe_s = 0;
  vis.cam.type = mjCAMERA_FREE;
  vis.cam.distance = options.camera_distance;
  vis.cam.elevation = options.camera_elevation_deg;

  // Camera track over the whole record (non-causal smoothing: no lag, no shake).
  const double rec_fps = rec.fps;
  std::vector<Eigen::Vector3d> roots;
  for (const auto& f : rec.frames) roots.push_back(f.root_pos);
  roots = motion::GaussianSmooth(roots, options.position_smoothing_s * rec_fps);
  std::vector<double> heading =
      motion::GaussianSmooth(Headings(rec), options.heading_smoothing_s * rec_fps);

  const double out_fps = options.fps > 0 ? options.fps : rec_fps;
  int n_out = static_cast<int>(std::floor(rec.duration() * out_fps + 1e-9)) + 1;
  if (options.max_frames > 0) n_out = std::min(n_out, options.max_frames);

  const std::filesystem::path dir = mp4.has_parent_path() ? mp4.parent_path() : ".";
  std::filesystem::create_directories(dir);
  const std::string tag = ".tmp." + std::to_string(::getpid());
  TempFiles temps;
  const std::filesystem::path tmp = dir / ("." + mp4.filename().string() + tag + ".mp4");
  const std::filesystem::path log = dir / ("." + mp4.filename().string() + tag + ".log");
  temps.paths = {tmp, log};

  SubprocessOptions sp;
  sp.pipe_stdin = true;
  sp.stderr_file = log;
  Subprocess ffmpeg({options.ffmpeg,
                     "-hide_banner",
                     "-loglevel",
                     "error",
                     "-y",
                     "-f",
                     "rawvideo",
                     "-pix_fmt",
                     "rgb24",
                     "-s",
                     std::to_string(W) + "x" + std::to_string(H),
                     "-framerate",
                     Fixed(out_fps, 6),
                     "-i",
                     "pipe:0",
                     "-an",
                     "-c:v",
                     "libx264",
                     "-preset",
                     "veryfast",
                     "-crf",
                     std::to_string(options.crf),
                     "-pix_fmt",
                     "yuv420p",
                     "-movflags",
                     "+faststart",
                     "-f",
                     "mp4",
                     tmp.string()},
                    sp);

  std::vector<unsigned char> rgb(static_cast<std::size_t>(W) * H * 3), flipped(rgb.size());
  const mjrRect viewport{0, 0, W, H};
  const int wrap_chars = std::max(12, (W - 170) / 9);
  ProgressReporter progress("render " + mp4.filename().string(), n_out, "frames", 5.0);
  const auto t_loop = Clock::now();
  bool pipe_ok = true;
  for (int i = 0; i < n_out && pipe_ok; ++i) {
    const double t = i / out_fps;
    const int fi = std::clamp(static_cast<int>(std::lround(t * rec_fps)), 0, rec.num_frames() - 1);
    const RecordFrame& f = rec.frames[fi];
    humanoid::HumanoidPose pose;
    pose.root_pos = f.root_pos;
    pose.root_rot = f.root_rot;
    pose.dof_pos = f.dof_pos;
    humanoid::WritePose(humanoid, pose, data.get());
    mj_kinematics(m, data.get());
    mj_comPos(m, data.get());
    mj_camlight(m, data.get());

    const Eigen::Vector3d& c = roots[fi];
    for (int k = 0; k < 2; ++k) vis.cam.lookat[k] = c[k];
    vis.cam.lookat[2] =
        std::max(0.3, c.z() * options.look_at_height / humanoid::kDefaultRootHeight);
    const double yaw = options.follow_heading ? heading[fi] : 0.0;
    // MuJoCo's azimuth is the direction the camera looks; it stands opposite to it.
    vis.cam.azimuth = (yaw * 180.0 / M_PI) + options.view_angle_deg + 180.0;

    mjv_updateScene(m, data.get(), &vis.opt, nullptr, &vis.cam, mjCAT_ALL, &vis.scn);
    if (options.occluder_alpha < 1)
      FadeOccluders(m, data.get(), humanoid, options.occluder_alpha, &vis.scn);
    const auto q0 = Clock::now();
    mjr_render(viewport, &vis.scn, &vis.con);
    if (options.captions) {
      const int k = rec.KeyframeAt(fi);
      std::string labels, values;
      if (k >= 0) {
        const KeyframeAnnotation& a = rec.keyframes[k];
        labels = "Keyframe\nSkill\nEmotion";
        values = std::to_string(a.index + 1) + " / " + std::to_string(rec.keyframes.size()) + "\n" +
                 Ascii(a.skill) + "\n" + Ascii(a.emotion.empty() ? "-" : a.emotion);
        const auto lines = Wrap(Ascii(a.caption), wrap_chars);
        for (std::size_t l = 0; l < lines.size() && l < 3; ++l) {
          labels += l == 0 ? "\nCaption" : "\n ";
          values += "\n" + lines[l];
        }
        labels += "\nResult";
        values += std::string("\n") + (a.success ? "success" : "failed");
      } else if (!rec.title.empty()) {
        labels = "Story";
        values = Ascii(rec.title).substr(0, wrap_chars);
      }
      if (!labels.empty())
        mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, labels.c_str(), values.c_str(),
                    &vis.con);
      const std::string time = Fixed(fi / rec_fps, 1) + " / " + Fixed(rec.duration(), 1) + " s";
      mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMRIGHT, viewport, "Time", time.c_str(), &vis.con);
    }
    mjr_readPixels(rgb.data(), nullptr, viewport, &vis.con);
    const auto q1 = Clock::now();
    const std::size_t row = static_cast<std::size_t>(W) * 3;
    for (int y = 0; y < H; ++y)
      std::copy_n(rgb.data() + (H - 1 - y) * row, row, flipped.data() + y * row);
    pipe_ok = ffmpeg.WriteAll(flipped.data(), flipped.size());
    gl_s += std::chrono::duration<double>(q1 - q0).count();
    pipe_s += std::chrono::duration<double>(Clock::now() - q1).count();
    if (options.progress) progress.Update(i + 1);
  }
  const double loop_s = std::chrono::duration<double>(Clock::now() - t_loop).count();
  ffmpeg.ClosePipe(0);
  const int code = ffmpeg.Wait();
  if (!pipe_ok || code != 0)
    ThrowInputError(mp4.string(), "", "an MP4 encoded by ffmpeg",
                    "ffmpeg exited with " + std::to_string(code) + ": " + ReadTail(log));
  std::error_code ec;
  std::filesystem::rename(tmp, mp4, ec);
  if (ec)
    ThrowInputError(mp4.string(), "", "a writable location", "rename failed: " + ec.message());
  VideoStats stats;
  stats.frames = n_out;
  stats.width = W;
  stats.height = H;
  stats.fps = out_fps;
  stats.seconds = std::chrono::duration<double>(Clock::now() - t_start).count();
  stats.render_fps = n_out / std::max(loop_s, 1e-9);
  stats.gl_seconds = gl_s;
  stats.encode_wait_seconds = pipe_s;
  if (options.progress) progress.Finish();
  spdlog::info(
      "video {}: {} frames {}x{} at {:.0f} fps, {:.1f} frames/s (GL {:.1f} s, waiting for ffmpeg "
      "{:.1f} s), {:.1f} s total",
      mp4.string(), stats.frames, W, H, out_fps, stats.render_fps, gl_s, pipe_s, stats.seconds);
  return stats;
}

}  // namespace

VideoStats RenderVideo(const MotionRecord& record, const scene::Scene& scene,
                       const std::filesystem::path& mp4, const VideoOptions& options) {
  return RenderModel(record, sim::CompileSceneGeometry(scene), mp4, options);
}

VideoStats RenderVideo(const MotionRecord& record, const humanoid::StaticGeometry& geometry,
                       const std::filesystem::path& mp4, const VideoOptions& options) {
  return RenderModel(record, geometry, mp4, options);
}

}  // namespace sims::io
