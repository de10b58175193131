#include "sims/motion/synthetic.h"

#include <cmath>
#include <iostream>
#include <map>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/humanoid/features.h"
#include "sims/humanoid/model_builder.h"
#include "sims/humanoid/state.h"
#include "sims/motion/motion_library.h"
#include "sims/motion/skeleton.h"

namespace sims::motion {
namespace {

// The whole catalogue with the default options, generated once: exactly the clips
// make_synthetic_motions writes to data/motions/synthetic (two variants per recipe), so the
// quality checks below cover the jittered variants training sees, not only the base recipes.
const std::vector<MotionClip>& Catalogue() {
  static const std::vector<MotionClip> clips = GenerateSyntheticClips(SyntheticOptions{});
  return clips;
}

const MotionClip& ByName(const std::string& name) {
  for (const auto& c : Catalogue())
    if (c.meta().name == name) return c;
  ADD_FAILURE() << "no clip " << name;
  return Catalogue().front();
}

double Correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = a.size();
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    sab += (a[i] - ma) * (b[i] - mb), saa += (a[i] - ma) * (a[i] - ma),
        sbb += (b[i] - mb) * (b[i] - mb);
  return sab / std::sqrt(saa * sbb);
}

TEST(SyntheticTest, CatalogueCoversSkillsWithLabels) {
  std::map<std::string, int> skills;
  std::map<std::string, int> emotions;
  for (const MotionClip& c : Catalogue()) {
    const MotionMeta& m = c.meta();
    ++skills[m.skill];
    ++emotions[m.emotion];
    EXPECT_TRUE(m.synthetic) << m.name;
    EXPECT_NE(m.source.find("synthetic"), std::string::npos);
    EXPECT_GE(m.captions.size(), 3u) << m.name;
    EXPECT_LE(m.captions.size(), 5u) << m.name;
    EXPECT_NO_THROW(ValidateConfig(m, m.name));
    EXPECT_FALSE(m.furniture.empty()) << m.name;
    EXPECT_GT(c.duration(), 3.0) << m.name;
    EXPECT_EQ(c.fps(), 30.0);
  }
  for (const char* s : {"walk", "idle", "sit", "lie", "reach", "getup"})
    EXPECT_GE(skills[s], 2) << s;
  // Every recipe comes as its base clip and one "_v1" variant (SyntheticOptions::variants);
  // the beds of extra heights and the sofa lie-downs ("_h<cm>") come once each.
  EXPECT_EQ(SyntheticOptions{}.variants, 2);
  int base = 0, v1 = 0, sofa = 0, stool = 0;
  for (const MotionClip& c : Catalogue()) {
    const std::string& n = c.meta().name;
    if (n.rfind("lie_down_sofa_h", 0) == 0) {
      ++sofa;
      EXPECT_EQ(c.meta().furniture, std::vector<std::string>{"sofa"});
      EXPECT_EQ(c.meta().skill, "lie");
      continue;
    }
    if (n.find("_bed_h") != std::string::npos) continue;
    if (n.find("_stool_h") != std::string::npos) {
      ++stool;
      continue;
    }
    const bool variant = n.size() > 3 && n.compare(n.size() - 3, 3, "_v1") == 0;
    (variant ? v1 : base) += 1;
  }
  EXPECT_EQ(v1, base);
  EXPECT_EQ(sofa, 2);   // configs/motion/synthetic_catalog.json: sofa_lie.heights
  EXPECT_EQ(stool, 4);  // seats[2].extra_heights: a sit-down and a get-up at each
  EXPECT_GE(skills["walk"], 20);
  for (const char* e :
       {"neutral", "sad", "tired", "drunk", "hurried", "angry", "happy", "relaxed", "stressed"})
    EXPECT_GE(emotions[e], 1) << e;
  // Sit/lie clips carry their furniture.
  EXPECT_GT(ByName("sit_down_chair").meta().params.at("furniture_height"), 0.35);
  EXPECT_GT(ByName("lie_down_bed").meta().params.at("furniture_height"), 0.35);
}

// Reference starts on a bed need a clip within 5 cm of its height (object_skill.h; get-up may
// lift a lying start onto a higher bed, getup_params.h): the extra height covers the low held-out
// beds (0.38–0.43 m) below the variants, with a lie-down and a get-up on the same bed.
TEST(SyntheticTest, ExtraBedHeightGetsALieDownAndAGetUp) {
  const MotionClip& lie = ByName("lie_down_bed_h42");
  const MotionClip& up = ByName("getup_from_bed_h42");
  EXPECT_EQ(lie.meta().skill, "lie");
  EXPECT_EQ(up.meta().skill, "getup");
  EXPECT_NEAR(lie.meta().params.at("furniture_height"), 0.42, 1e-9);
  EXPECT_NEAR(up.meta().params.at("furniture_height"), 0.42, 1e-9);
  // The get-up starts lying on the bed and ends standing.
  EXPECT_GT(up.frames().front().root_pos.z(), 0.42);
  EXPECT_NEAR(up.frames().back().root_pos.z(), humanoid::kDefaultRootHeight, 0.1);
}

// A seat's extra heights: a sit-down and a get-up on a stool of exactly that height, each
// labelled for the recipe's furniture, the get-up starting seated and ending standing.
TEST(SyntheticTest, ExtraSeatHeightsGetASitDownAndAGetUp) {
  for (const double h : {0.37, 0.53}) {
    const std::string suffix = "_h" + std::to_string(std::lround(100 * h));
    SCOPED_TRACE(suffix);
    const MotionClip& sit = ByName("sit_down_stool" + suffix);
    const MotionClip& up = ByName("getup_from_stool" + suffix);
    EXPECT_EQ(sit.meta().skill, "sit");
    EXPECT_EQ(up.meta().skill, "getup");
    EXPECT_EQ(up.meta().furniture, (std::vector<std::string>{"stool", "armchair"}));
    EXPECT_NEAR(sit.meta().params.at("furniture_height"), h, 1e-9);
    EXPECT_NEAR(up.meta().params.at("furniture_height"), h, 1e-9);
    EXPECT_LT(up.frames().front().root_pos.z(), h + 0.2);
    EXPECT_NEAR(up.frames().back().root_pos.z(), humanoid::kDefaultRootHeight, 0.1);
  }
}

// The sit approach composites: a walk-up and a 180° turn that end where the sit-down clip
// begins, then that clip unchanged after the crossfade (its furniture parameters still hold).
TEST(SyntheticTest, ApproachCompositesEndInTheSitDownClip) {
  for (const char* seat : {"chair", "sofa", "stool"}) {
    SCOPED_TRACE(seat);
    const MotionClip& sit = ByName(std::string("sit_down_") + seat);
    const MotionClip& c = ByName(std::string("sit_approach_") + seat);
    EXPECT_EQ(c.meta().skill, "sit");
    EXPECT_EQ(c.meta().params, sit.meta().params);
    const int lead = c.num_frames() - sit.num_frames();
    ASSERT_GT(lead, 90);  // more than 3 s of walking up and turning
    const int blend = 9;  // 0.3 s
    for (int k = blend; k < sit.num_frames(); k += 7) {
      EXPECT_NEAR((c.frame(lead + k).root_pos - sit.frame(k).root_pos).norm(), 0, 1e-12);
      EXPECT_NEAR((c.frame(lead + k).dof_pos - sit.frame(k).dof_pos).norm(), 0, 1e-12);
    }
    // It starts ~2 m in front of the seat (+x), facing it (−x), and turns round on the way.
    const Eigen::Vector3d start = c.frame(0).root_pos;
    EXPECT_GT(start.x() - sit.frame(0).root_pos.x(), 1.5);
    EXPECT_LT(std::abs(start.y() - sit.frame(0).root_pos.y()), 0.3);
    const Eigen::Vector3d fwd = c.frame(0).root_rot * Eigen::Vector3d::UnitX();
    EXPECT_LT(fwd.x(), -0.9);
  }
}

TEST(SyntheticTest, ComposeAfterJoinsAtTheClipStart) {
  const MotionClip& walk = ByName("walk_normal");
  const MotionClip& sit = ByName("sit_down_chair");
  const MotionClip c = ComposeAfter(walk.Slice(0, 40), sit, 0.0);
  ASSERT_EQ(c.num_frames(), 39 + sit.num_frames());
  // The lead's last frame would sit on the clip's first: the frame before it is one walk
  // step behind, heading the same way as the clip starts.
  const Eigen::Vector3d step = c.frame(39).root_pos - c.frame(38).root_pos;
  EXPECT_LT(Eigen::Vector2d(step.x(), step.y()).norm(), 0.1);
  EXPECT_NEAR((c.frame(39).root_pos - sit.frame(0).root_pos).norm(), 0, 1e-12);
  EXPECT_EQ(c.meta().name, sit.meta().name);
}

// Joint limits, no floor penetration, little self-contact, planted feet do not slide.
TEST(SyntheticTest, ClipsArePlausible) {
  for (const MotionClip& c : Catalogue()) {
    const ClipQuality q = MeasureClipQuality(c);
    SCOPED_TRACE(c.meta().name);
    EXPECT_LE(q.max_limit_excess, 1e-9);
    EXPECT_GE(q.min_sole_height, -1e-3);
    EXPECT_LE(q.max_floor_penetration, 1e-3);
    EXPECT_LE(q.max_self_penetration, 0.03);
    EXPECT_LE(q.max_stance_slide, 0.05);
  }
}

TEST(SyntheticTest, WalkIsNatural) {
  const MotionClip& c = ByName("walk_normal");
  const int n = c.num_frames();
  std::vector<double> r_arm(n), l_hip(n), z(n);
  for (int f = 0; f < n; ++f) {
    r_arm[f] = c.frame(f).dof_pos[7];   // right_shoulder_y (negative = forward)
    l_hip[f] = c.frame(f).dof_pos[22];  // left_hip_y (negative = forward)
    z[f] = c.frame(f).root_pos.z();
  }
  // The right arm swings forward with the left leg.
  EXPECT_GT(Correlation(r_arm, l_hip), 0.6);
  // The pelvis bobs by a few centimetres, lowest in double support.
  const auto [lo, hi] = std::minmax_element(z.begin(), z.end());
  EXPECT_GT(*hi - *lo, 0.02);
  EXPECT_LT(*hi - *lo, 0.08);
  // Average speed matches the recipe (1.2 m/s).
  EXPECT_NEAR(c.meta().params.at("end_x") / c.duration(), 1.2, 0.05);
  EXPECT_NEAR((c.frame(n - 1).root_pos - c.frame(0).root_pos).head<2>().norm() / c.duration(), 1.2,
              0.06);
  // Heel strike: when a sole lands, its lowest corner is at the heel.
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  int strikes = 0, heel_first = 0;
  std::array<double, 2> prev_h = {1, 1};
  for (int f = 0; f < n; ++f) {
    SkeletonPose sp;
    SkeletonForwardKinematics(skel, c.frame(f).root_pos, c.frame(f).root_rot, c.frame(f).dof_pos,
                              &sp);
    for (int side = 0; side < 2; ++side) {
      const auto corners = FootBoxCorners(skel, sp, side == 1);
      int lowest = 0;
      for (int k = 1; k < 8; ++k)
        if (corners[k].z() < corners[lowest].z()) lowest = k;
      const double h = corners[lowest].z();
      if (prev_h[side] > 0.004 && h <= 0.004) {
        ++strikes;
        heel_first += (lowest & 1) == 0;  // corner bit 0 = x sign: heel corners have x < 0
      }
      prev_h[side] = h;
    }
  }
  EXPECT_GE(strikes, 10);
  EXPECT_GE(heel_first, strikes - 1);
}

TEST(SyntheticTest, TurnsAndStops) {
  const MotionClip& turn = ByName("walk_turn_in_place_left_90");
  EXPECT_NEAR(turn.meta().params.at("end_yaw"), M_PI / 2, 1e-6);
  EXPECT_NEAR(humanoid::HeadingAngle(turn.frame(turn.num_frames() - 1).root_rot), M_PI / 2, 0.1);
  const MotionClip& stop = ByName("walk_start_stop_normal");
  const double d = (stop.frame(stop.num_frames() - 1).root_pos - stop.frame(0).root_pos).norm();
  EXPECT_GT(d, 3.0);
  EXPECT_LT(d, 6.0);
  // Standing still at both ends.
  EXPECT_LT(stop.root_lin_vel(0).norm(), 0.05);
  EXPECT_LT(stop.root_lin_vel(stop.num_frames() - 1).norm(), 0.05);
}

TEST(SyntheticTest, ReachAndSitHitTheirTargets) {
  const MotionClip& r = ByName("reach_right_medium");
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  const MotionFrame& f = r.frame(static_cast<int>(2.0 * r.fps()));
  SkeletonPose sp;
  SkeletonForwardKinematics(skel, f.root_pos, f.root_rot, f.dof_pos, &sp);
  const auto& p = r.meta().params;
  EXPECT_LT((sp.pos[humanoid::kRightHand] -
             Eigen::Vector3d(p.at("target_x"), p.at("target_y"), p.at("target_z")))
                .norm(),
            0.03);
  const MotionClip& s = ByName("sit_down_chair");
  const double seat = s.meta().params.at("furniture_height");
  const double pelvis = s.frame(s.num_frames() - 1).root_pos.z();
  EXPECT_GT(pelvis - seat, 0.05);
  EXPECT_LT(pelvis - seat, 0.16);
}

TEST(SyntheticTest, DeterministicForASeed) {
  SyntheticOptions o;
  o.variants = 2;
  o.skills = {"reach"};
  o.seed = 5;
  const auto a = GenerateSyntheticClips(o);
  const auto b = GenerateSyntheticClips(o);
  o.seed = 6;
  const auto c = GenerateSyntheticClips(o);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), 24u);  // 6 reaches × 2 variants, plus their walk-up composites
  bool differs = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].num_frames(), b[i].num_frames());
    for (int f = 0; f < a[i].num_frames(); ++f) {
      ASSERT_EQ(a[i].frame(f).dof_pos, b[i].frame(f).dof_pos);
      ASSERT_EQ(a[i].frame(f).root_pos, b[i].frame(f).root_pos);
    }
    differs = differs || a[i].meta().params != c[i].meta().params;
  }
  EXPECT_TRUE(differs);
}

TEST(SyntheticTest, DatasetLoadsIntoALibrary) {
  const auto dir = testing::TempDir("synthetic");
  std::vector<MotionClip> some = {ByName("walk_normal"), ByName("sit_idle_upright"),
                                  ByName("lie_idle_back")};
  const auto manifest = WriteMotionDataset(some, dir, "test");
  MotionLibraryOptions o;
  o.mirror = true;
  const MotionLibrary lib = MotionLibrary::Load(manifest, nullptr, o);
  EXPECT_EQ(lib.num_clips(), 6);
  EXPECT_EQ(lib.weight(0), 2.0);  // walks weigh double
  EXPECT_EQ(lib.Find("walk").size(), 2u);
  std::vector<float> demos(8 * 1250);
  Rng rng(1);
  lib.SampleAmpDemos(rng, 8, demos.data());
  for (float v : demos) ASSERT_TRUE(std::isfinite(v));
}

// Whole-body centre of mass of a frame (MuJoCo's subtree COM of the root body).
Eigen::Vector3d CentreOfMass(const humanoid::Humanoid& h, mjData* d, const MotionFrame& f) {
  humanoid::HumanoidPose p;
  p.root_pos = f.root_pos;
  p.root_rot = f.root_rot;
  p.dof_pos = f.dof_pos;
  humanoid::BodyStates bodies;
  humanoid::ForwardKinematics(h, p, d, &bodies);
  const double* c = d->subtree_com + 3 * h.model()->body_rootid[1];
  return Eigen::Vector3d(c[0], c[1], c[2]);
}

}  // namespace

// A slow rise from a seat or a bed balances over the feet: from seat-off (the last frame with the
// pelvis at sitting or lying height) to the end, the centre of mass stays over the soles' floor
// contact (x between the rearmost heel and the foremost toe on the floor). A rise whose COM
// stays behind the heels (the reversed sit-downs and lie-downs: 10–13 cm) tips back onto the
// furniture when a controller tracks it, so it teaches a rise no policy can copy.
TEST(SyntheticTest, GetUpFromFurnitureBalancesOverTheFeet) {
  const HumanoidSkeleton& skel = HumanoidSkeleton::Default();
  const auto h = HumanoidSkeleton::DefaultHumanoid();
  humanoid::MjDataPtr d = humanoid::MakeData(h->model());
  int checked = 0;
  for (const char* furniture : {"chair", "sofa", "stool", "bed"}) {
    for (const std::string& name :
         {std::string("getup_from_") + furniture, std::string("getup_from_") + furniture + "_v1"}) {
      SCOPED_TRACE(name);
      const MotionClip& c = ByName(name);
      const double seated = c.meta().params.at("furniture_height") + 0.13;
      int off = 0;
      for (int f = 0; f < c.num_frames(); ++f)
        if (c.frame(f).root_pos.z() < seated) off = f + 1;
      double worst = 1e9;
      int frames = 0;
      for (int f = off; f < c.num_frames(); ++f) {
        const MotionFrame& fr = c.frame(f);
        SkeletonPose sp;
        SkeletonForwardKinematics(skel, fr.root_pos, fr.root_rot, fr.dof_pos, &sp);
        double lo = 1e9, hi = -1e9;
        for (bool left : {false, true})
          for (const Eigen::Vector3d& q : FootBoxCorners(skel, sp, left))
            if (q.z() < 0.01) lo = std::min(lo, q.x()), hi = std::max(hi, q.x());
        const double x = CentreOfMass(*h, d.get(), fr).x();
        worst = std::min(worst, std::min(x - lo, hi - x));
        ++frames;
      }
      std::cout << name << ": " << frames << " frames risen, worst COM margin over the soles "
                << worst << " m\n";
      EXPECT_GT(frames, 10);
      EXPECT_GT(worst, 0.02);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 8);
}

}  // namespace sims::motion
