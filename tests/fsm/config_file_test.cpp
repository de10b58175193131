// configs/story.json (run_story --options) against StoryOptions' C++ defaults: the file is the
// documented starting point for a user's options, so it must say what run_story does without it.
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/config.h"
#include "sims/core/paths.h"
#include "sims/fsm/story_runner.h"

namespace sims::fsm {
namespace {

TEST(ConfigFileTest, StoryJsonMatchesStoryOptionsDefaults) {
  const auto diffs =
      testing::ConfigFileDifferences(ConfigPath("story.json"), ConfigToJson(StoryOptions{}));
  std::string all;
  for (const std::string& d : diffs) all += "\n  " + d;
  EXPECT_TRUE(diffs.empty()) << "configs/story.json differs from StoryOptions{}:" << all;
}

}  // namespace
}  // namespace sims::fsm
