#include "sims/task/skill_state.h"

#include <gtest/gtest.h>

#include <limits>

#include "sims/core/error.h"

namespace sims::task {
namespace {

// A state with one field of every kind the archive knows.
struct ToyState {
  double speed = 0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  int phase = 0;
  bool started = false;
  Rng rng{0};

  void Serialize(StateArchive* a) {
    a->Real("speed", &speed);
    a->Reals("target", &target);
    a->Int("phase", &phase, 0, 3);
    a->Flag("started", &started);
    a->RngState("rng", &rng);
  }
};

std::vector<double> Write(ToyState st) {
  std::vector<double> out;
  StateArchive a(&out);
  st.Serialize(&a);
  return out;
}

ToyState Read(const std::vector<double>& in) {
  StateReader r("toy skill state", in.data(), in.size());
  StateArchive a(&r);
  ToyState st;
  st.Serialize(&a);
  r.ExpectEnd();
  return st;
}

TEST(StateArchiveTest, OneSerializeWritesAndReadsBackEveryField) {
  ToyState st;
  st.speed = -1.25;
  st.target = {0.5, -2.0, 1e-9};
  st.phase = 3;
  st.started = true;
  st.rng = Rng(0xfeedbeefcafe1234ull);
  st.rng.NextU64();
  const std::vector<double> flat = Write(st);
  // 1 + 3 + 1 + 1 + 4 words × 2 halves: the layout snapshots already on disk use.
  ASSERT_EQ(flat.size(), 14u);
  EXPECT_EQ(flat[0], -1.25);
  EXPECT_EQ(flat[4], 3.0);
  EXPECT_EQ(flat[5], 1.0);
  ToyState back = Read(flat);
  EXPECT_EQ(back.speed, st.speed);
  EXPECT_EQ(back.target, st.target);
  EXPECT_EQ(back.phase, 3);
  EXPECT_TRUE(back.started);
  // The generator state survives exactly (64-bit words do not fit a double; halves do).
  EXPECT_EQ(back.rng.state(), st.rng.state());
  EXPECT_EQ(back.rng.NextU64(), st.rng.NextU64());
}

TEST(StateArchiveTest, ReadingChecksRangesAndNaNsNamingTheField) {
  ToyState st;
  std::vector<double> flat = Write(st);
  flat[4] = 4;  // phase out of [0, 3]
  try {
    Read(flat);
    FAIL() << "accepted phase 4";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("phase"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("toy skill state"), std::string::npos) << e.what();
  }
  flat = Write(st);
  flat[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Read(flat), Error);
  flat = Write(st);
  flat[5] = 0.5;  // a flag must be 0 or 1
  EXPECT_THROW(Read(flat), Error);
  flat = Write(st);
  flat.pop_back();
  EXPECT_THROW(Read(flat), Error);
  flat = Write(st);
  flat.push_back(0);
  EXPECT_THROW(Read(flat), Error);  // trailing values
}

}  // namespace
}  // namespace sims::task
