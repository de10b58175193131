#include "sims/io/video.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "common/test_util.h"
#include "io/io_test_util.h"
#include "sims/core/error.h"
#include "sims/io/subprocess.h"

namespace sims::io {
namespace {

// Decodes an MP4 to raw RGB frames with ffmpeg.
std::vector<std::vector<unsigned char>> DecodeFrames(const std::filesystem::path& mp4, int w,
                                                     int h) {
  std::string raw;
  const int code = RunCommand({"ffmpeg", "-hide_banner", "-loglevel", "error", "-i", mp4.string(),
                               "-f", "rawvideo", "-pix_fmt", "rgb24", "pipe:1"},
                              &raw);
  EXPECT_EQ(code, 0) << raw.substr(0, 500);
  const std::size_t frame = static_cast<std::size_t>(w) * h * 3;
  std::vector<std::vector<unsigned char>> frames;
  for (std::size_t off = 0; off + frame <= raw.size(); off += frame)
    frames.emplace_back(raw.begin() + off, raw.begin() + off + frame);
  return frames;
}

double StdDev(const std::vector<unsigned char>& px) {
  double sum = 0, sq = 0;
  for (unsigned char v : px) sum += v, sq += double(v) * v;
  const double mean = sum / px.size();
  return std::sqrt(std::max(0.0, sq / px.size() - mean * mean));
}

TEST(VideoTest, RendersTinyClipThatFfprobeReads) {
  if (!ProgramAvailable("ffmpeg") || !ProgramAvailable("ffprobe"))
    GTEST_SKIP() << "ffmpeg/ffprobe not installed (Debian package ffmpeg, cmake/setup.sh)";
  const MotionRecord rec = testing::TestRecord(19.0 / 30.0);  // 20 frames
  ASSERT_EQ(rec.num_frames(), 20);
  const auto dir = sims::testing::TempDir("io_video");
  const auto mp4 = dir / "story.mp4";
  VideoOptions opt;
  opt.width = 160;
  opt.height = 120;
  opt.progress = false;
  const VideoStats stats = RenderVideo(rec, testing::TestScene(), mp4, opt);
  EXPECT_EQ(stats.frames, 20);
  EXPECT_GT(stats.render_fps, 0);
  ASSERT_TRUE(std::filesystem::exists(mp4));
  // Only the finished file is left: no temporaries, no logs.
  int entries = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) ++entries, (void)e;
  EXPECT_EQ(entries, 1);

  std::string probe;
  ASSERT_EQ(RunCommand({"ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames",
                        "-show_entries", "stream=nb_read_frames,width,height,codec_name", "-of",
                        "default=noprint_wrappers=1", mp4.string()},
                       &probe),
            0)
      << probe;
  EXPECT_NE(probe.find("width=160"), std::string::npos) << probe;
  EXPECT_NE(probe.find("height=120"), std::string::npos) << probe;
  EXPECT_NE(probe.find("nb_read_frames=20"), std::string::npos) << probe;
  EXPECT_NE(probe.find("codec_name=h264"), std::string::npos) << probe;

  const auto frames = DecodeFrames(mp4, 160, 120);
  ASSERT_EQ(frames.size(), 20u);
  for (const auto& f : frames) EXPECT_GT(StdDev(f), 10.0);  // not a uniform image
  // The character walks and turns: first and last frames differ noticeably.
  double diff = 0;
  for (std::size_t i = 0; i < frames[0].size(); ++i)
    diff += std::abs(int(frames[0][i]) - int(frames.back()[i]));
  EXPECT_GT(diff / frames[0].size(), 1.0);
}

TEST(VideoTest, BadOptionsAndMissingFfmpegAreClearErrors) {
  const MotionRecord rec = testing::TestRecord(0.2);
  const auto dir = sims::testing::TempDir("io_video_bad");
  VideoOptions opt;
  opt.width = 161;
  try {
    RenderVideo(rec, humanoid::StaticGeometry{}, dir / "a.mp4", opt);
    FAIL() << "odd width accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("width"), std::string::npos) << e.what();
  }
  opt = VideoOptions{};
  opt.ffmpeg = "sims-no-such-ffmpeg";
  try {
    RenderVideo(rec, humanoid::StaticGeometry{}, dir / "a.mp4", opt);
    FAIL() << "missing ffmpeg accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sims-no-such-ffmpeg"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "a.mp4"));
}

}  // namespace
}  // namespace sims::io
