#include "sims/io/video_frames.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <regex>

#include "sims/core/error.h"
#include "sims/io/subprocess.h"

namespace sims::io {

namespace {

const char* kInstallHint = "installed (Debian package ffmpeg; cmake/setup.sh installs it)";

std::string Tail(const std::string& s, std::size_t n = 300) {
  std::string t = s.size() > n ? s.substr(s.size() - n) : s;
  while (!t.empty() && (t.back() == '\n' || t.back() == ' ')) t.pop_back();
  return t;
}

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3f", v);
  return buf;
}

void RequireProgram(const std::string& program) {
  if (!ProgramAvailable(program)) ThrowInputError(program, "", kInstallHint, "not found in PATH");
}

}  // namespace

void FrameSamplingOptions::Validate() const {
  if (mode != "fixed" && mode != "scene")
    ThrowInputError("frame sampling", "mode", "'fixed' or 'scene'", "'" + mode + "'");
  if (count < 1 || count > 64)
    ThrowInputError("frame sampling", "count", "1 to 64 frames", std::to_string(count));
  if (!(scene_threshold > 0 && scene_threshold < 1))
    ThrowInputError("frame sampling", "scene_threshold", "a number in (0, 1)",
                    std::to_string(scene_threshold));
  if (width < 16 || width > 4096)
    ThrowInputError("frame sampling", "width", "16 to 4096 pixels", std::to_string(width));
  if (jpeg_quality < 2 || jpeg_quality > 31)
    ThrowInputError("frame sampling", "jpeg_quality", "2 (best) to 31",
                    std::to_string(jpeg_quality));
}

double VideoDuration(const std::filesystem::path& video, const FrameSamplingOptions& options) {
  if (!std::filesystem::is_regular_file(video))
    ThrowInputError(video.string(), "", "a readable video file", "no such file");
  RequireProgram(options.ffprobe);
  std::string out;
  int code = RunCommand({options.ffprobe, "-v", "error", "-show_entries", "format=duration", "-of",
                         "default=noprint_wrappers=1:nokey=1", video.string()},
                        &out);
  char* end = nullptr;
  double d = std::strtod(out.c_str(), &end);
  if (code != 0 || end == out.c_str() || !(d > 0) || !std::isfinite(d))
    ThrowInputError(video.string(), "", "a video ffprobe can read (with a duration)",
                    "ffprobe said: " + Tail(out));
  return d;
}

std::vector<VideoFrame> SampleVideoFrames(const std::filesystem::path& video,
                                          const FrameSamplingOptions& options,
                                          const std::filesystem::path& out_dir) {
  options.Validate();
  const double duration = VideoDuration(video, options);
  RequireProgram(options.ffmpeg);
  std::filesystem::create_directories(out_dir);
  const std::string scale = "scale=" + std::to_string(options.width) + ":-2";
  const std::string quality = std::to_string(options.jpeg_quality);
  auto name = [&](int i) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%03d.jpg", i);
    return out_dir / buf;
  };
  std::vector<VideoFrame> frames;
  if (options.mode == "fixed") {
    // One seek per frame: exact, evenly spread times, and fast on long videos (input seeking).
    for (int i = 0; i < options.count; ++i) {
      double t = (i + 0.5) * duration / options.count;
      std::string log;
      int code = RunCommand(
          {options.ffmpeg, "-nostdin", "-v", "error", "-y", "-ss", Number(t), "-i", video.string(),
           "-frames:v", "1", "-vf", scale, "-q:v", quality, name(i).string()},
          &log);
      if (code != 0 || !std::filesystem::is_regular_file(name(i)))
        ThrowInputError(video.string(), "", "a video ffmpeg can decode",
                        "ffmpeg failed at " + Number(t) + " s: " + Tail(log));
      frames.push_back({name(i), t});
    }
    return frames;
  }
  // Scene mode: one pass writes every cut (plus frame 0) with showinfo times, then keeps an
  // even subset of them, renumbered.
  std::filesystem::path scratch = out_dir / ".scene";
  std::filesystem::remove_all(scratch);
  std::filesystem::create_directories(scratch);
  std::string log;
  const std::string filter = "select='eq(n\\,0)+gt(scene\\," + Number(options.scene_threshold) +
                             ")'," + "showinfo," + scale;
  int code = RunCommand({options.ffmpeg, "-nostdin", "-nostats", "-v", "info", "-y", "-i",
                         video.string(), "-vf", filter, "-vsync", "vfr", "-frames:v", "500", "-q:v",
                         quality, (scratch / "%04d.jpg").string()},
                        &log);
  std::vector<double> times;
  static const std::regex kPts("pts_time:([0-9.eE+-]+)");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), kPts); it != std::sregex_iterator();
       ++it)
    times.push_back(std::strtod((*it)[1].str().c_str(), nullptr));
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(scratch)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (code != 0 || files.empty()) {
    std::filesystem::remove_all(scratch);
    ThrowInputError(video.string(), "", "a video ffmpeg can decode", "ffmpeg said: " + Tail(log));
  }
  const int have = static_cast<int>(files.size());
  const int keep = std::min(have, options.count);
  for (int i = 0; i < keep; ++i) {
    // Evenly spaced indices over the cuts, first cut always kept.
    int src = keep == 1 ? 0 : static_cast<int>(std::lround(i * (have - 1.0) / (keep - 1.0)));
    std::filesystem::rename(files[src], name(i));
    frames.push_back({name(i), src < static_cast<int>(times.size()) ? times[src] : 0.0});
  }
  std::filesystem::remove_all(scratch);
  return frames;
}

}  // namespace sims::io
