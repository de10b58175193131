// The floor get-ups of the synthetic catalogue (issue 17): lying on the back or face down, then
// up onto hands and knees, kneeling, one knee and standing.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/motion/motion_library.h"
#include "sims/motion/synthetic.h"
#include "sims/motion/synthetic_catalog.h"

namespace sims::motion {
namespace {

const char* const kFloorClips[] = {"getup_from_floor_back", "getup_from_floor_back_v1",
                                   "getup_from_floor_front", "getup_from_floor_front_v1"};

// The whole shipped catalogue with the default options (seed 1, two variants per recipe):
// the variants drawn here are those of data/motions/synthetic, which depend on every section
// drawn before the floor get-ups.
const std::vector<MotionClip>& GetUps() {
  static const std::vector<MotionClip> clips = GenerateSyntheticClips(SyntheticOptions{});
  return clips;
}

const MotionClip& Named(const std::string& name) {
  for (const MotionClip& c : GetUps())
    if (c.meta().name == name) return c;
  ADD_FAILURE() << "no clip " << name;
  return GetUps().front();
}

bool StartsSupine(const MotionClip& c) { return c.meta().name.find("_back") != std::string::npos; }

// Pelvis up axis and the chest's facing direction (torso +x) of a frame.
struct Posture {
  double pelvis_z, up_z, chest_z;
};
Posture PostureOf(const MotionFrame& f) {
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  SkeletonPose sp;
  SkeletonForwardKinematics(skel, f.root_pos, f.root_rot, f.dof_pos, &sp);
  return {f.root_pos.z(), (f.root_rot * Eigen::Vector3d::UnitZ()).z(),
          (sp.rot[humanoid::kTorso] * Eigen::Vector3d::UnitX()).z()};
}

TEST(SyntheticFloorTest, FloorGetUpsComeFromBothStartsWithTheirLabels) {
  const auto dir = sims::testing::TempDir("floor_getups");
  const auto manifest = WriteMotionDataset(GetUps(), dir, "test");
  const MotionLibrary lib = MotionLibrary::Load(manifest, nullptr, MotionLibraryOptions{});
  std::set<std::string> getups;
  for (int i : lib.Find("getup")) getups.insert(lib.clip(i).meta().name);
  for (const char* name : kFloorClips) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(getups.count(name));
    const MotionMeta& m = Named(name).meta();
    EXPECT_EQ(m.skill, "getup");
    EXPECT_TRUE(m.synthetic);
    EXPECT_EQ(m.furniture, std::vector<std::string>{"floor"});
    EXPECT_EQ(m.style, StartsSupine(Named(name)) ? "from floor on back" : "from floor face down");
    EXPECT_GE(m.captions.size(), 3u);
    EXPECT_LE(m.captions.size(), 4u);
    // Marked as floor clips, with none of the furniture parameters that seat and bed clips
    // are placed by.
    EXPECT_EQ(m.params.at("floor"), 1.0);
    for (const auto& [key, value] : m.params)
      EXPECT_EQ(key.rfind("furniture", 0), std::string::npos);
    EXPECT_EQ(Named(name).fps(), 30.0);
    EXPECT_GE(Named(name).duration(), 4.0);
    EXPECT_LE(Named(name).duration(), 6.5);
  }
  // The seat and bed get-ups keep their furniture parameters and no floor marker.
  for (const char* name : {"getup_from_chair", "getup_from_bed"}) {
    EXPECT_TRUE(Named(name).meta().params.count("furniture_height")) << name;
    EXPECT_FALSE(Named(name).meta().params.count("floor")) << name;
  }
}

TEST(SyntheticFloorTest, StartsLyingAndEndsStandingStill) {
  for (const char* name : kFloorClips) {
    SCOPED_TRACE(name);
    const MotionClip& c = Named(name);
    const Posture first = PostureOf(c.frame(0));
    EXPECT_LT(first.pelvis_z, 0.35);
    EXPECT_LT(std::abs(first.up_z), 0.5);  // trunk roughly horizontal
    if (StartsSupine(c))
      EXPECT_GT(first.chest_z, 0.8);  // on the back: the chest faces up
    else
      EXPECT_LT(first.chest_z, -0.8);  // face down
    const int n = c.num_frames();
    const Posture last = PostureOf(c.frame(n - 1));
    EXPECT_GE(last.pelvis_z, 0.8);
    EXPECT_GE(last.up_z, 0.9);
    // Held still for the last 0.5 s (breathing aside).
    const int hold = static_cast<int>(0.5 * c.fps());
    for (int f = n - hold; f < n; ++f) {
      EXPECT_LT((c.frame(f).root_pos - c.frame(n - 1).root_pos).norm(), 1e-3) << f;
      EXPECT_LT(c.frame(f).root_rot.angularDistance(c.frame(n - 1).root_rot), 1e-3) << f;
    }
  }
}

TEST(SyntheticFloorTest, RootMovesSmoothly) {
  for (const char* name : kFloorClips) {
    SCOPED_TRACE(name);
    const MotionClip& c = Named(name);
    double step = 0, turn = 0, accel = 0;
    for (int f = 1; f < c.num_frames(); ++f) {
      step = std::max(step, (c.frame(f).root_pos - c.frame(f - 1).root_pos).norm());
      turn = std::max(turn, c.frame(f).root_rot.angularDistance(c.frame(f - 1).root_rot));
      if (f > 1)
        accel = std::max(
            accel,
            (c.frame(f).root_pos - 2 * c.frame(f - 1).root_pos + c.frame(f - 2).root_pos).norm());
    }
    EXPECT_LT(step, 0.04);    // m per frame (1.2 m/s)
    EXPECT_LT(turn, 0.15);    // rad per frame (4.5 rad/s)
    EXPECT_LT(accel, 0.012);  // m per frame² (11 m/s²): no jolts
  }
}

TEST(SyntheticFloorTest, RestsOnTheFloorWithinTheJointLimits) {
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  for (const char* name : kFloorClips) {
    SCOPED_TRACE(name);
    const MotionClip& c = Named(name);
    for (int f = 0; f < c.num_frames(); ++f)
      for (int i = 0; i < humanoid::kNumDofs; ++i) {
        ASSERT_GE(c.frame(f).dof_pos[i], skel.lower[i] - 1e-9) << "frame " << f << " dof " << i;
        ASSERT_LE(c.frame(f).dof_pos[i], skel.upper[i] + 1e-9) << "frame " << f << " dof " << i;
      }
    const ClipQuality q = MeasureClipQuality(c);
    // Every frame touches the floor (lying, kneeling or standing), nothing sinks into it.
    EXPECT_LE(q.max_floor_gap, 0.02);
    EXPECT_LE(q.max_floor_penetration, 1e-3);
    EXPECT_GE(q.min_sole_height, -1e-3);
    EXPECT_LE(q.max_self_penetration, 0.03);
    EXPECT_LE(q.max_stance_slide, 0.05);
  }
}

// The floor poses are named poses: a standing idle recipe can kneel or lie with them, and the
// result rests on the floor.
TEST(SyntheticFloorTest, FloorPosesAreNamedPoses) {
  SyntheticCatalog c = LoadSyntheticCatalog(DefaultSyntheticCatalogPath());
  IdleRecipe r = c.idle.recipes.front();
  c.idle.recipes.clear();
  for (const char* pose :
       {"floor_supine", "floor_prone", "hands_and_knees", "kneeling", "one_knee"}) {
    r.name = std::string("idle_") + pose;
    r.key.pose = pose;
    c.idle.recipes.push_back(r);
  }
  SyntheticOptions o;
  o.variants = 1;
  o.skills = {"idle"};
  const std::vector<MotionClip> clips = GenerateSyntheticClips(c, o);
  ASSERT_EQ(clips.size(), 5u);
  for (const MotionClip& clip : clips) {
    SCOPED_TRACE(clip.meta().name);
    const ClipQuality q = MeasureClipQuality(clip);
    EXPECT_LE(q.max_floor_gap, 0.01);
    EXPECT_LE(q.max_floor_penetration, 1e-3);
    EXPECT_LT(clip.frame(0).root_pos.z(), 0.6);  // down on the floor, not standing
  }
}

}  // namespace
}  // namespace sims::motion
