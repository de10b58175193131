#include "sims/core/markup.h"

#include <gtest/gtest.h>

namespace sims {
namespace {

TEST(MarkupTest, EscapesTheFiveSpecialCharacters) {
  EXPECT_EQ(EscapeMarkup(R"(a<b & "c" > 'd')"), "a&lt;b &amp; &quot;c&quot; &gt; &#39;d&#39;");
  EXPECT_EQ(EscapeMarkup(""), "");
  EXPECT_EQ(EscapeMarkup("plain café"), "plain café");  // UTF-8 passes through
  EXPECT_EQ(EscapeMarkup("&amp;"), "&amp;amp;");        // an entity is text like any other
}

}  // namespace
}  // namespace sims
