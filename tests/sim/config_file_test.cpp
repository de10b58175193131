// configs/env.json against EnvConfig's C++ defaults: the file documents the defaults, so a value
// that differs must be an intended one, listed (and explained) below.
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/config.h"
#include "sims/core/paths.h"
#include "sims/sim/env.h"

namespace sims::sim {
namespace {

TEST(ConfigFileTest, EnvJsonMatchesEnvConfigDefaults) {
  const std::set<std::string> intended = {
      // demo_env (the only reader of env.json) spreads its characters over a 2 m disc so they
      // do not all start on the same spot; everything else (training, stories) spawns at the
      // origin unless its own config says otherwise.
      "spawn_radius",
  };
  const auto diffs =
      testing::ConfigFileDifferences(ConfigPath("env.json"), ConfigToJson(EnvConfig{}), intended);
  std::string all;
  for (const std::string& d : diffs) all += "\n  " + d;
  EXPECT_TRUE(diffs.empty()) << "configs/env.json differs from EnvConfig{}:" << all;
}

}  // namespace
}  // namespace sims::sim
