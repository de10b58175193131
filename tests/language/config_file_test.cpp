// configs/language/text_motion.json (train_text_motion's default --config) against
// MotionTextTrainConfig's C++ defaults. configs/language/text_encoder_clip.json is not checked:
// it is an alternative encoder setting (CLIP through TorchScript), meant to differ.
#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/config.h"
#include "sims/core/paths.h"
#include "sims/language/motion_text.h"

namespace sims::language {
namespace {

TEST(ConfigFileTest, TextMotionJsonMatchesTrainConfigDefaults) {
  const auto diffs = testing::ConfigFileDifferences(ConfigPath("language/text_motion.json"),
                                                    ConfigToJson(MotionTextTrainConfig{}));
  std::string all;
  for (const std::string& d : diffs) all += "\n  " + d;
  EXPECT_TRUE(diffs.empty()) << "configs/language/text_motion.json differs from "
                                "MotionTextTrainConfig{}:"
                             << all;
}

}  // namespace
}  // namespace sims::language
