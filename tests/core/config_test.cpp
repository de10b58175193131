#include "sims/core/config.h"

#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"

namespace sims {
namespace {

struct Inner {
  double clip = 0.2;
  std::vector<int> sizes{64, 32};
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(clip));
    a->Visit(SIMS_NVP(sizes));
  }
  void Validate() const {
    Require(clip > 0 && clip < 1, "clip", "a number in (0, 1)");
    for (int s : sizes) Require(s > 0, "sizes", "positive layer sizes");
  }
};

struct Outer {
  int num_envs = 8;
  std::string name = "walk";
  bool flag = false;
  std::array<double, 3> goal{1, 2, 3};
  std::optional<double> limit;
  std::map<std::string, double> weights{{"task", 0.5}};
  Inner inner;
  std::vector<Inner> list;
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(num_envs));
    a->Visit(SIMS_NVP(name));
    a->Visit(SIMS_NVP(flag));
    a->Visit(SIMS_NVP(goal));
    a->Visit(SIMS_NVP(limit));
    a->Visit(SIMS_NVP(weights));
    a->Visit(SIMS_NVP(inner));
    a->Visit(SIMS_NVP(list));
  }
  void Validate() const { Require(num_envs > 0, "num_envs", "a positive integer"); }
};

// A struct whose keys beyond its own belong to a plugin (SkillConfig::params).
struct WithRest {
  int num_envs = 8;
  nlohmann::json rest = nlohmann::json::object();
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(num_envs));
    a->VisitRest(&rest);
  }
};

TEST(ConfigTest, VisitRestTakesTheUnnamedKeysAndWritesThemBack) {
  const nlohmann::json j = {{"num_envs", 2}, {"hop_height", 0.3}, {"hop_style", "high"}};
  const WithRest w = ConfigFromJson<WithRest>(j, "test");
  EXPECT_EQ(w.num_envs, 2);
  EXPECT_EQ(w.rest, (nlohmann::json{{"hop_height", 0.3}, {"hop_style", "high"}}));
  EXPECT_EQ(ConfigToJson(w), j);
  EXPECT_TRUE(ConfigFromJson<WithRest>(nlohmann::json::object(), "test").rest.empty());
  // A named field wins over a rest key of the same name when writing.
  WithRest clash;
  clash.rest = {{"num_envs", 99}};
  EXPECT_EQ(ConfigToJson(clash), (nlohmann::json{{"num_envs", 8}}));
}

// A field renamed after files were written with its old name (ObjectParams' hand-off keys).
struct Renamed {
  double share = 0;
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(share));
    a->VisitRenamed("old_share", SIMS_NVP(share));
  }
};

TEST(ConfigTest, RenamedFieldsReadTheOldNameAndWriteTheNew) {
  EXPECT_EQ(ConfigFromJson<Renamed>({{"old_share", 0.35}}, "test").share, 0.35);
  EXPECT_EQ(ConfigFromJson<Renamed>({{"share", 0.5}}, "test").share, 0.5);
  Renamed r;
  r.share = 0.35;
  EXPECT_EQ(ConfigToJson(r), (nlohmann::json{{"share", 0.35}}));
  try {
    (void)ConfigFromJson<Renamed>({{"share", 0.5}, {"old_share", 0.35}}, "f.json");
    FAIL() << "both names were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("old_share"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("f.json"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)ConfigFromJson<Renamed>({{"old_share", "x"}}, "test"), Error);
}

TEST(ConfigTest, DefaultsSurviveEmptyObject) {
  const Outer o = ConfigFromJson<Outer>(nlohmann::json::object(), "test");
  EXPECT_EQ(o.num_envs, 8);
  EXPECT_EQ(o.inner.sizes, (std::vector<int>{64, 32}));
  EXPECT_FALSE(o.limit.has_value());
}

TEST(ConfigTest, RoundTripIsIdentity) {
  Outer o;
  o.num_envs = 3;
  o.name = "sit";
  o.flag = true;
  o.goal = {4, 5, 6};
  o.limit = 2.5;
  o.weights["style"] = 0.25;
  o.inner.clip = 0.1;
  o.list.push_back(Inner{0.3, {7}});
  const nlohmann::json j = ConfigToJson(o);
  const Outer back = ConfigFromJson<Outer>(j, "test");
  EXPECT_EQ(ConfigToJson(back), j);
  EXPECT_EQ(back.list.at(0).sizes, std::vector<int>{7});
  EXPECT_DOUBLE_EQ(*back.limit, 2.5);
}

TEST(ConfigTest, FileRoundTrip) {
  const auto dir = testing::TempDir("config");
  Outer o;
  o.name = "lie";
  SaveConfig(dir / "c.json", o);
  EXPECT_EQ(ConfigToJson(LoadConfig<Outer>(dir / "c.json")), ConfigToJson(o));
}

std::string ErrorOf(const nlohmann::json& j) {
  return sims::testing::ErrorOf([&] { ConfigFromJson<Outer>(j, "cfg.json"); });
}

TEST(ConfigTest, ErrorsNameFileFieldAndExpectation) {
  EXPECT_EQ(ErrorOf({{"num_envs", "many"}}),
            "cfg.json: field 'num_envs': expected an integer, got \"many\"");
  EXPECT_EQ(ErrorOf({{"num_envs", 0}}), "cfg.json: field 'num_envs': expected a positive integer");
  EXPECT_EQ(ErrorOf({{"inner", {{"clip", 2.0}}}}),
            "cfg.json: field 'inner.clip': expected a number in (0, 1)");
  EXPECT_EQ(ErrorOf({{"list", {{{"sizes", {1, -2}}}}}}),
            "cfg.json: field 'list[0].sizes': expected positive layer sizes");
  EXPECT_NE(ErrorOf({{"nmu_envs", 4}}).find("field 'nmu_envs': expected a known field"),
            std::string::npos);
  EXPECT_NE(ErrorOf({{"goal", {1, 2}}}).find("field 'goal': expected an array of 3 values"),
            std::string::npos);
}

TEST(ConfigTest, ValidateConfigChecksNestedStructs) {
  Outer o;
  o.inner.clip = -1;
  EXPECT_THROW(ValidateConfig(o, "code"), Error);
}

TEST(ConfigTest, ParseErrorNamesLineAndColumn) {
  const auto dir = testing::TempDir("config");
  std::ofstream(dir / "bad.json") << "{\n  \"a\": 1,\n  'b': 2\n}\n";
  try {
    ReadJsonFile(dir / "bad.json");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json:3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadJsonFile(dir / "missing.json"), Error);
  // A number beyond double range is nlohmann's out_of_range, not a parse error.
  std::ofstream(dir / "huge.json") << "{\"a\": 3e40000000000000}";
  EXPECT_THROW(ReadJsonFile(dir / "huge.json"), Error);
}

TEST(ConfigTest, AtomicWriteLeavesNoTempFiles) {
  const auto dir = testing::TempDir("atomic");
  WriteFileAtomic(dir / "x.txt", "one");
  WriteFileAtomic(dir / "x.txt", "two");
  int files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir)) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);
  std::ifstream in(dir / "x.txt");
  std::string s;
  in >> s;
  EXPECT_EQ(s, "two");
}

}  // namespace
}  // namespace sims
