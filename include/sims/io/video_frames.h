// Frames sampled from a video file with Debian's ffmpeg/ffprobe, as downscaled JPEGs, for a
// vision-language model to describe (extract_script). Two samplings: fixed-rate (N frames at the
// centres of N equal slices of the video) and scene-change (the first frame plus every frame
// whose ffmpeg scene score exceeds a threshold, thinned evenly to N).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sims::io {

/// How frames are chosen and encoded.
struct FrameSamplingOptions {
  std::string mode = "fixed";       ///< "fixed" (evenly spaced) or "scene" (scene changes).
  int count = 8;                    ///< Number of frames wanted (scene mode may return fewer).
  double scene_threshold = 0.3;     ///< ffmpeg scene score in (0, 1) that counts as a cut.
  int width = 384;                  ///< Output width in pixels (height keeps the aspect ratio).
  int jpeg_quality = 5;             ///< ffmpeg -q:v, 2 (best) … 31 (smallest).
  std::string ffmpeg = "ffmpeg";    ///< ffmpeg executable.
  std::string ffprobe = "ffprobe";  ///< ffprobe executable (same Debian package).

  /// Throws sims::Error naming the option when a value is out of range.
  void Validate() const;
};

/// One sampled frame.
struct VideoFrame {
  std::filesystem::path path;  ///< The JPEG file.
  double time_s = 0.0;         ///< Its time in the video.
};

/// Duration of a video in seconds (ffprobe); throws sims::Error naming the file when it is
/// missing, unreadable or has no duration.
double VideoDuration(const std::filesystem::path& video, const FrameSamplingOptions& options = {});

/// Samples frames of `video` into `out_dir` as 000.jpg, 001.jpg, ... in time order (the folder
/// is created; files of an earlier sampling there are overwritten). Throws sims::Error naming
/// the file when ffmpeg is missing or cannot read the video.
std::vector<VideoFrame> SampleVideoFrames(const std::filesystem::path& video,
                                          const FrameSamplingOptions& options,
                                          const std::filesystem::path& out_dir);

}  // namespace sims::io
