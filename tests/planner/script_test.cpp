#include "sims/planner/script.h"

#include <gtest/gtest.h>

namespace sims::planner {
namespace {
TEST(ScriptTest, Placeholder) {
  ShortScript s =
      ParseShortScriptText(R"({"summary": "x", "emotion": "tired, sad", "scene": "bedroom",
    "keyframes": [{"skill": "loco", "emotion/style": "tired", "caption": "walks slowly with head bowed", "furniture": "floor"},
                  {"skill": "liedown", "emotion/style": "sad", "caption": "curls up on the side", "furnitures": "bed"}]})",
                           "inline");
  EXPECT_EQ(s.keyframes.size(), 2u);
}
}  // namespace
}  // namespace sims::planner
