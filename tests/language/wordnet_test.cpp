#include "sims/language/wordnet.h"

#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>

#include "common/test_util.h"

namespace sims::language {
namespace {

namespace fs = std::filesystem;

TEST(WordNetTest, MorphyAndSynonymsFromDebianDictionary) {
  const fs::path dict = WordNetLexicon::DefaultDictDir();
  if (!fs::exists(dict / "index.noun"))
    GTEST_SKIP() << "Debian wordnet-base not installed (cmake/setup.sh installs it)";
  const auto lex = WordNetLexicon::FromDictDir(dict, [](const std::string&) { return true; });
  auto has = [](const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
  };
  EXPECT_TRUE(has(lex.BaseForms("sat"), "sit"));     // irregular (verb.exc)
  EXPECT_TRUE(has(lex.BaseForms("walks"), "walk"));  // suffix rule
  EXPECT_TRUE(has(lex.BaseForms("chairs"), "chair"));
  EXPECT_TRUE(has(lex.BaseForms("happier"), "happy"));  // adj.exc
  EXPECT_TRUE(lex.BaseForms("walk").empty());
  EXPECT_TRUE(lex.IsLemma("sofa"));
  EXPECT_TRUE(has(lex.Synonyms("sofa"), "couch"));
  // Save/Load round trip.
  const fs::path out = sims::testing::TempDir("wordnet") / "wordnet.txt";
  lex.Save(out);
  const auto back = WordNetLexicon::Load(out);
  EXPECT_EQ(back.num_lemmas(), lex.num_lemmas());
  EXPECT_EQ(back.num_exceptions(), lex.num_exceptions());
  EXPECT_EQ(back.Synonyms("sofa"), lex.Synonyms("sofa"));
}

}  // namespace
}  // namespace sims::language
