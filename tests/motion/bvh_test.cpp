#include "sims/motion/bvh.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/error.h"

namespace sims::motion {
namespace {

const char kCmu[] = "/usr/share/assimp/models/BVH/01_01.bvh";
const char kBoxing[] = "/usr/share/assimp/models/BVH/Boxing_Toes.bvh";

void ExpectSame(const BvhMotion& a, const BvhMotion& b) {
  ASSERT_EQ(a.joints.size(), b.joints.size());
  for (std::size_t j = 0; j < a.joints.size(); ++j) {
    EXPECT_EQ(a.joints[j].name, b.joints[j].name);
    EXPECT_EQ(a.joints[j].parent, b.joints[j].parent);
    EXPECT_EQ(a.joints[j].channels, b.joints[j].channels);
    EXPECT_EQ(a.joints[j].has_end_site, b.joints[j].has_end_site);
    EXPECT_LT((a.joints[j].offset - b.joints[j].offset).norm(), 1e-9);
    EXPECT_LT((a.joints[j].end_site - b.joints[j].end_site).norm(), 1e-9);
  }
  EXPECT_EQ(a.num_frames, b.num_frames);
  EXPECT_NEAR(a.frame_time, b.frame_time, 1e-12);
  ASSERT_EQ(a.values.size(), b.values.size());
  double worst = 0;
  for (std::size_t i = 0; i < a.values.size(); ++i)
    worst = std::max(worst, std::abs(a.values[i] - b.values[i]) / (1.0 + std::abs(a.values[i])));
  EXPECT_LT(worst, 1e-8);
}

std::string ErrorOf(const std::filesystem::path& p) {
  return sims::testing::ErrorOf([&] { ReadBvh(p); });
}

TEST(BvhTest, ReadsCmuClip) {
  if (!std::filesystem::exists(kCmu)) GTEST_SKIP() << "assimp-testmodels not installed";
  const BvhMotion bvh = ReadBvh(kCmu);
  EXPECT_EQ(bvh.joints.size(), 31u);
  EXPECT_EQ(bvh.num_channels(), 96);
  EXPECT_EQ(bvh.num_frames, 2752);
  EXPECT_NEAR(bvh.fps(), 120.0, 0.01);
  EXPECT_EQ(bvh.joints[0].name, "Hips");
  const int knee = bvh.FindJoint("LeftLeg");
  ASSERT_GE(knee, 0);
  EXPECT_EQ(bvh.joints[bvh.joints[knee].parent].name, "LeftUpLeg");
  EXPECT_NEAR(bvh.frame(0)[0], 9.3722, 1e-9);
}

TEST(BvhTest, RoundTripIsExact) {
  std::vector<std::filesystem::path> files = {testing::TestData("motion/tiny_zxy.bvh")};
  for (const char* f : {kCmu, kBoxing})
    if (std::filesystem::exists(f)) files.push_back(f);
  const auto dir = testing::TempDir("bvh");
  for (const auto& f : files) {
    const BvhMotion a = ReadBvh(f);
    WriteBvh(a, dir / "out.bvh");
    const BvhMotion b = ReadBvh(dir / "out.bvh");
    SCOPED_TRACE(f.string());
    ExpectSame(a, b);
  }
}

TEST(BvhTest, ChannelOrderAndGlobalPose) {
  const BvhMotion bvh = ReadBvh(testing::TestData("motion/tiny_zxy.bvh"));
  ASSERT_EQ(bvh.joints.size(), 4u);
  EXPECT_EQ(bvh.num_channels(), 13);
  const double d = M_PI / 180;
  // Hips channels Zrotation Xrotation Yrotation: R = Rz·Rx·Ry.
  const Eigen::Quaterniond want = Eigen::AngleAxisd(10 * d, Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(-5 * d, Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(2.5 * d, Eigen::Vector3d::UnitY());
  EXPECT_LT(BvhLocalRotation(bvh, 0, 1).angularDistance(want), 1e-12);
  // Hip channels Y X Z; the knee has a single X channel.
  const Eigen::Quaterniond hip = Eigen::AngleAxisd(12 * d, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(14 * d, Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(16 * d, Eigen::Vector3d::UnitZ());
  EXPECT_LT(BvhLocalRotation(bvh, 2, 2).angularDistance(hip), 1e-12);
  const Eigen::Quaterniond knee(Eigen::AngleAxisd(-60 * d, Eigen::Vector3d::UnitX()));
  EXPECT_LT(BvhLocalRotation(bvh, 3, 2).angularDistance(knee), 1e-12);
  std::vector<Eigen::Quaterniond> rot;
  std::vector<Eigen::Vector3d> pos;
  BvhGlobalPose(bvh, -1, &rot, &pos);
  EXPECT_LT((pos[3] - Eigen::Vector3d(9, -40, 0)).norm(), 1e-12);
  BvhGlobalPose(bvh, 1, &rot, &pos);
  EXPECT_LT((pos[0] - Eigen::Vector3d(1, 90.5, 0.25)).norm(), 1e-12);
  EXPECT_LT((pos[1] - (pos[0] + rot[0] * Eigen::Vector3d(0, 10, 0))).norm(), 1e-12);
}

TEST(BvhTest, MalformedFilesGiveClearErrors) {
  const std::string truncated = ErrorOf(testing::TestData("motion/truncated.bvh"));
  EXPECT_NE(truncated.find("truncated.bvh"), std::string::npos) << truncated;
  EXPECT_NE(truncated.find("truncated file"), std::string::npos) << truncated;
  const std::string channels = ErrorOf(testing::TestData("motion/bad_channel_count.bvh"));
  EXPECT_NE(channels.find("bad_channel_count.bvh:10"), std::string::npos) << channels;
  EXPECT_NE(channels.find("CHANNELS of 'Chest'"), std::string::npos) << channels;
  const std::string zero = ErrorOf(testing::TestData("motion/zero_frames.bvh"));
  EXPECT_NE(zero.find("Frames"), std::string::npos) << zero;
  EXPECT_NE(zero.find("at least 1 frame"), std::string::npos) << zero;
  const std::string row = ErrorOf(testing::TestData("motion/short_row.bvh"));
  EXPECT_NE(row.find("frame 1"), std::string::npos) << row;
  EXPECT_NE(row.find("expected 13 values"), std::string::npos) << row;
  const std::string missing = ErrorOf(testing::TestData("motion/no_such_file.bvh"));
  EXPECT_NE(missing.find("no_such_file.bvh"), std::string::npos) << missing;
  EXPECT_THROW(ParseBvh("HIERARCHY\nROOT A\n{\nOFFSET 0 0 x\n}\n", "inline"), Error);
  EXPECT_THROW(ParseBvh("", "empty"), Error);
  EXPECT_THROW(ParseBvh("HIERARCHY ROOT A { OFFSET 0 0 0 CHANNELS 1 Xrotation } MOTION Frames: 1 "
                        "Frame Time: -1\n0\n",
                        "negative frame time"),
               Error);
  // Fuzzer finding (tools/fuzz.sh bvh): a frame time of 15408337 s made retargeting resample
  // two frames into ~5e8 (out of memory); now the frame time is rejected, naming the field.
  const std::string hours = ErrorOf(testing::TestData("fuzz/bvh/frame_time_of_hours.bvh"));
  EXPECT_NE(hours.find("Frame Time"), std::string::npos) << hours;
  EXPECT_NE(hours.find("(0, 1]"), std::string::npos) << hours;
}

}  // namespace
}  // namespace sims::motion
