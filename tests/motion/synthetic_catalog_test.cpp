#include "sims/motion/synthetic_catalog.h"

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/error.h"

namespace sims::motion {
namespace {

uint64_t Fnv1a(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

// Writes the shipped catalogue with one edit and returns the loader's error message.
std::string ErrorWith(const std::string& json_pointer, const nlohmann::json& value) {
  nlohmann::json j = ReadJsonFile(DefaultSyntheticCatalogPath());
  j[nlohmann::json::json_pointer(json_pointer)] = value;
  const auto path = testing::TempDir("bad_catalog") / "catalog.json";
  std::ofstream(path) << j.dump(2);
  try {
    LoadSyntheticCatalog(path);
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    return what;
  }
  ADD_FAILURE() << "no error for " << json_pointer;
  return {};
}

TEST(SyntheticCatalogTest, ShippedCatalogueLoadsAndValidates) {
  const SyntheticCatalog c = LoadSyntheticCatalog(DefaultSyntheticCatalogPath());
  EXPECT_EQ(c.walk.recipes.size(), 25u);
  EXPECT_EQ(c.idle.recipes.size(), 5u);
  EXPECT_EQ(c.seats.size(), 3u);
  EXPECT_EQ(c.sit_idle.recipes.size(), 4u);
  EXPECT_EQ(c.lie_idle.recipes.size(), 3u);
  EXPECT_EQ(c.reach.recipes.size(), 6u);
  EXPECT_EQ(c.floor_getup.recipes.size(), 2u);
  ValidateConfig(c, "round trip");
  // Six reaches, two variants each by default (as in the shipped data/motions/synthetic),
  // and a walk-up composite of each.
  SyntheticOptions o;
  o.skills = {"reach"};
  EXPECT_EQ(GenerateSyntheticClips(c, o).size(), 24u);
}

TEST(SyntheticCatalogTest, MalformedCatalogueNamesFileFieldAndExpectation) {
  std::string e = ErrorWith("/walk/recipes/2/keys/0/speed", "fast");
  EXPECT_NE(e.find("walk.recipes[2].keys[0].speed"), std::string::npos) << e;
  EXPECT_NE(e.find("expected a number"), std::string::npos) << e;

  e = ErrorWith("/sit_idle/recipes/1/key/pose", "slouch");
  EXPECT_NE(e.find("sit_idle.recipes[1].key.pose"), std::string::npos) << e;
  EXPECT_NE(e.find("legs_crossed"), std::string::npos) << e;  // lists the known poses

  e = ErrorWith("/reach/recipes/0/dofs_deg/spine_y", 3);
  EXPECT_NE(e.find("reach.recipes[0].dofs_deg.spine_y"), std::string::npos) << e;
  EXPECT_NE(e.find("a joint name"), std::string::npos) << e;

  e = ErrorWith("/idle/recipes/0/captions", nlohmann::json::array());
  EXPECT_NE(e.find("idle.recipes[0].captions"), std::string::npos) << e;
  EXPECT_NE(e.find("at least one caption"), std::string::npos) << e;

  e = ErrorWith("/reach/recipes/1/name", "reach_right_low");
  EXPECT_NE(e.find("unique"), std::string::npos) << e;

  e = ErrorWith("/walk/recipes/0/gait/lean", 3);
  EXPECT_NE(e.find("walk.recipes[0].gait.lean"), std::string::npos) << e;

  e = ErrorWith("/floor_getup/recipes/1/start", "sideways");
  EXPECT_NE(e.find("floor_getup.recipes[1].start"), std::string::npos) << e;
  EXPECT_NE(e.find("\"supine\" or \"prone\""), std::string::npos) << e;

  e = ErrorWith("/seats/2/extra_heights", nlohmann::json::array({0.1}));
  EXPECT_NE(e.find("seats[2].extra_heights"), std::string::npos) << e;
  EXPECT_NE(e.find("(0.2, 1.0)"), std::string::npos) << e;

  e = ErrorWith("/floor_getup/recipes/0/key", 1);  // floor get-ups have no pose edits
  EXPECT_NE(e.find("floor_getup.recipes[0].key"), std::string::npos) << e;
}

// Reference hashes of clip files written by the generator before its recipes moved into the
// catalogue (the C++-coded recipes at 4bb6f0f, make_synthetic_motions --skills reach
// --variants 2 and --skills lie --variants 1): the catalogue must reproduce them bit for bit.
TEST(SyntheticCatalogTest, GenerationMatchesThePreCatalogueOutput) {
  const SyntheticCatalog c = LoadSyntheticCatalog(DefaultSyntheticCatalogPath());
  const auto dir = testing::TempDir("catalog_hash");
  SyntheticOptions o;
  o.skills = {"reach"};
  o.variants = 2;
  WriteMotionDataset(GenerateSyntheticClips(c, o), dir, "test");
  EXPECT_EQ(Fnv1a(dir / "reach_left_high_v1.bin"), 0x9817cd70211bc860ULL);
  EXPECT_EQ(Fnv1a(dir / "reach_left_high_v1.json"), 0x30457e470d4727f1ULL);
  o.skills = {"lie"};
  o.variants = 1;
  WriteMotionDataset(GenerateSyntheticClips(c, o), dir, "test");
  EXPECT_EQ(Fnv1a(dir / "lie_idle_side.bin"), 0x060b1041ed3d7457ULL);
  EXPECT_EQ(Fnv1a(dir / "lie_idle_side.json"), 0x1d46a831f8b3f104ULL);
}

}  // namespace
}  // namespace sims::motion
