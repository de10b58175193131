// MP4 video of a motion record in its scene: MuJoCo renders the humanoid and the scene's
// physics geometry offscreen through an OSMesa (software GL) context — no display, no GPU —
// with a camera that follows the character (Gaussian-smoothed over the whole clip, so it
// neither lags nor shakes), see-through walls and furniture wherever they would hide the
// character, and a caption overlay of the current
// keyframe (skill, caption, emotion, outcome). Frames are piped as raw RGB to ffmpeg (H.264).
#pragma once

#include <filesystem>
#include <string>

#include "sims/core/config.h"
#include "sims/humanoid/model_builder.h"
#include "sims/io/motion_record.h"
#include "sims/scene/scene.h"

namespace sims::io {

/// Video settings.
struct VideoOptions {
  int width = 640;                    ///< Frame width (even).
  int height = 480;                   ///< Frame height (even).
  double fps = 0;                     ///< Output rate; 0 = the record's rate.
  int max_frames = 0;                 ///< Render at most this many frames (0 = all).
  double camera_distance = 3.5;       ///< Camera distance from the character (m).
  double camera_elevation_deg = -20;  ///< Camera pitch (negative looks down).
  double view_angle_deg = 40;         ///< Camera position around the character, relative to
                                      ///< its facing (0 = in front, 90 = at its left).
  bool follow_heading = true;         ///< Rotate with the character's (smoothed) heading.
  double position_smoothing_s = 0.5;  ///< Gaussian sigma of the look-at point (s).
  double heading_smoothing_s = 2.0;   ///< Gaussian sigma of the heading (s).
  double look_at_height = 0.8;        ///< Look-at height above the floor when standing (m).
  bool captions = true;               ///< Keyframe overlay and time stamp.
  bool shadows = true;                ///< Shadow pass (costs render time).
  int shadow_size = 1024;             ///< Shadow map resolution.
  bool reflections = false;           ///< Floor reflection pass (doubles render time).
  int multisamples = 0;               ///< MSAA samples (4 looks smoother, ~2x slower).
  double occluder_alpha = 0.2;        ///< Opacity of walls/furniture between camera and
                                      ///< character (1 = never fade).
  int crf = 20;                       ///< H.264 quality (lower = better, larger).
  std::string ffmpeg = "ffmpeg";      ///< ffmpeg executable.
  bool progress = true;               ///< Log progress with rate and ETA.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(width));
    a->Visit(SIMS_NVP(height));
    a->Visit(SIMS_NVP(fps));
    a->Visit(SIMS_NVP(max_frames));
    a->Visit(SIMS_NVP(camera_distance));
    a->Visit(SIMS_NVP(camera_elevation_deg));
    a->Visit(SIMS_NVP(view_angle_deg));
    a->Visit(SIMS_NVP(follow_heading));
    a->Visit(SIMS_NVP(position_smoothing_s));
    a->Visit(SIMS_NVP(heading_smoothing_s));
    a->Visit(SIMS_NVP(look_at_height));
    a->Visit(SIMS_NVP(captions));
    a->Visit(SIMS_NVP(shadows));
    a->Visit(SIMS_NVP(shadow_size));
    a->Visit(SIMS_NVP(reflections));
    a->Visit(SIMS_NVP(multisamples));
    a->Visit(SIMS_NVP(occluder_alpha));
    a->Visit(SIMS_NVP(crf));
    a->Visit(SIMS_NVP(ffmpeg));
    a->Visit(SIMS_NVP(progress));
  }
  /// Even sizes within 16..4096, positive distances, crf in 0..51.
  void Validate() const;
};

/// What a render did.
struct VideoStats {
  int frames = 0;                  ///< Frames written.
  int width = 0;                   ///< Frame width.
  int height = 0;                  ///< Frame height.
  double fps = 0;                  ///< Video frame rate.
  double seconds = 0;              ///< Wall time of the whole render (incl. model build, encode).
  double render_fps = 0;           ///< Frames per wall-clock second in the frame loop.
  double gl_seconds = 0;           ///< Time in MuJoCo rendering and pixel read-back.
  double encode_wait_seconds = 0;  ///< Time blocked writing to ffmpeg.
};

/// Renders `record` in `scene` (its physics geometry, compiled with sim::CompileSceneGeometry)
/// to `mp4` (written to a temporary file, renamed on success).
VideoStats RenderVideo(const MotionRecord& record, const scene::Scene& scene,
                       const std::filesystem::path& mp4, const VideoOptions& options = {});

/// Same with already compiled static geometry (e.g. the story run's physics scene).
VideoStats RenderVideo(const MotionRecord& record, const humanoid::StaticGeometry& geometry,
                       const std::filesystem::path& mp4, const VideoOptions& options = {});

}  // namespace sims::io
