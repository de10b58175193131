#include "sims/language/motion_text.h"

#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "language/fake_text_encoder.h"
#include "sims/core/error.h"
#include "sims/core/rng.h"
#include "sims/language/embedding_bank.h"

namespace sims::language {
namespace {

namespace fs = std::filesystem;

MotionTextModelConfig TinyModel(int feature_dim = 6) {
  MotionTextModelConfig c;
  c.feature_dim = feature_dim;
  c.seq_frames = 12;
  c.frames_per_token = 3;
  c.d_model = 16;
  c.num_heads = 2;
  c.encoder_layers = 1;
  c.decoder_layers = 1;
  c.ff_dim = 32;
  c.z_dim = 8;
  c.mlp_hidden = {16};
  return c;
}

CaptionedSequence RandomClip(const std::string& name, int frames, int dim, uint64_t seed) {
  Rng rng(seed);
  CaptionedSequence s;
  s.clip_name = name;
  s.features.resize(frames, dim);
  for (int r = 0; r < frames; ++r)
    for (int c = 0; c < dim; ++c) s.features(r, c) = static_cast<float>(rng.Normal());
  s.captions = {name + " moves", "a " + name + " clip"};
  return s;
}

TEST(WindowTest, ResamplesLongClipsAndSpreadsShortOnes) {
  MotionTextModelConfig c;  // 300 frames at 30 fps
  // 120 fps, 20 s: every 4th frame from the window start.
  auto idx = WindowFrameIndices(2400, 120.0, c, 0.0);
  ASSERT_EQ(idx.size(), 300u);
  EXPECT_EQ(idx[0], 0);
  EXPECT_EQ(idx[1], 4);
  EXPECT_EQ(idx[299], 1196);
  idx = WindowFrameIndices(2400, 120.0, c, 1.0);
  EXPECT_EQ(idx[0], 1200);
  EXPECT_EQ(idx[299], 2396);
  // 30 fps, 5 s (shorter than the 10 s window): indices cover the whole clip in order.
  idx = WindowFrameIndices(150, 30.0, c, 0.7);
  EXPECT_EQ(idx.front(), 0);
  EXPECT_EQ(idx.back(), 149);
  for (std::size_t i = 1; i < idx.size(); ++i) EXPECT_GE(idx[i], idx[i - 1]);
}

TEST(DatasetTest, SaveLoadRoundTripAndErrors) {
  const fs::path dir = sims::testing::TempDir("text_motion_data");
  CaptionedSequence s = RandomClip("sad_walk", 7, 5, 3);
  s.fps = 60;
  SaveCaptionedSequence(dir / "a.json", s);
  const auto back = LoadCaptionedSequence(dir / "a.json");
  EXPECT_EQ(back.clip_name, "sad_walk");
  EXPECT_EQ(back.fps, 60);
  EXPECT_EQ(back.captions, s.captions);
  EXPECT_TRUE(back.features.isApprox(s.features, 1e-5f));

  std::ofstream(dir / "b.json")
      << R"({"captions": ["x"], "features": [[1,2,3,4,5],[1,2,"x",4,5]]})";
  try {
    LoadCaptionedSequences(dir);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("b.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("features[1][2]"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "b.json") << R"({"captions": ["x"], "features": [[1,2,3]]})";
  EXPECT_THROW(LoadCaptionedSequences(dir), Error);  // feature size differs from a.json
  fs::remove(dir / "b.json");
  EXPECT_EQ(LoadCaptionedSequences(dir).size(), 1u);
}

TEST(MotionTextModelTest, UnitNormDeterministicAndPersistent) {
  const auto cfg = TinyModel();
  MotionTextModel a(cfg, 10, 42), b(cfg, 10, 42), c(cfg, 10, 43);
  const auto clip = RandomClip("x", 30, 6, 1);
  const Eigen::MatrixXf w = SampleWindow(clip, cfg, 0.5);
  const Eigen::VectorXf za = a.EncodeMotion(w);
  ASSERT_EQ(za.size(), 8);
  EXPECT_NEAR(za.norm(), 1.f, 1e-5f);
  EXPECT_EQ(za, b.EncodeMotion(w));
  EXPECT_FALSE(za.isApprox(c.EncodeMotion(w), 1e-3f));
  EXPECT_NEAR(a.EncodeClip(clip).norm(), 1.f, 1e-5f);
  const Eigen::VectorXf t = Eigen::VectorXf::LinSpaced(10, -1, 1);
  EXPECT_NEAR(a.EncodeTextFeature(t).norm(), 1.f, 1e-5f);
  EXPECT_EQ(a.Reconstruct(w).rows(), 12);
  EXPECT_THROW(a.EncodeTextFeature(Eigen::VectorXf::Ones(3)), Error);
  EXPECT_THROW(a.EncodeMotion(Eigen::MatrixXf::Zero(5, 6)), Error);

  const fs::path dir = sims::testing::TempDir("text_motion_model");
  TextEncoderConfig tc;
  tc.lemma_weight = 0.25;
  a.Save(dir, tc, "test");
  const MotionTextModel loaded = MotionTextModel::Load(dir);
  EXPECT_EQ(loaded.EncodeMotion(w), za);
  EXPECT_EQ(loaded.EncodeTextFeature(t), a.EncodeTextFeature(t));
  EXPECT_EQ(loaded.text_encoder_config().lemma_weight, 0.25);
  EXPECT_EQ(loaded.num_parameters(), a.num_parameters());
}

TEST(EmbeddingBankTest, NearestAndRoundTrip) {
  EmbeddingBank bank;
  bank.AddCaption("walk sadly", "sad", Eigen::Vector3f(1, 0, 0));
  bank.AddCaption("walk happily", "happy", Eigen::Vector3f(0, 2, 0));
  bank.AddCaption("stroll sadly", "sad", Eigen::Vector3f(1, 0.2f, 0));
  bank.AddClip("sad", Eigen::Vector3f(1, 0.1f, 0));
  bank.AddClip("happy", Eigen::Vector3f(0, 1, 0.1f));
  const auto near = bank.NearestCaptions(Eigen::Vector3f(1, 0.05f, 0), 2);
  ASSERT_EQ(near.size(), 2u);
  EXPECT_EQ(near[0].text, "walk sadly");
  EXPECT_EQ(near[1].text, "stroll sadly");
  EXPECT_GT(near[0].cosine, near[1].cosine);
  EXPECT_EQ(bank.NearestClips(Eigen::Vector3f(0, 1, 0), 1)[0].clip, "happy");
  // The same caption on another clip is listed once.
  bank.AddCaption("walk sadly", "sad_too", Eigen::Vector3f(1, 0, 0));
  const auto unique = bank.NearestCaptions(Eigen::Vector3f(1, 0.05f, 0), 3);
  ASSERT_EQ(unique.size(), 3u);
  EXPECT_EQ(unique[0].clip, "sad");
  EXPECT_EQ(unique[1].text, "stroll sadly");
  EXPECT_NEAR(bank.ClipZ("sad")->norm(), 1.f, 1e-6f);
  EXPECT_EQ(bank.ClipZ("none"), nullptr);
  const fs::path f = sims::testing::TempDir("bank") / "bank.json";
  bank.Save(f);
  const auto back = EmbeddingBank::Load(f);
  EXPECT_EQ(back.captions().size(), 4u);
  EXPECT_EQ(back.NearestCaptions(Eigen::Vector3f(1, 0.05f, 0), 3)[2].text, "walk happily");
  std::ofstream(f)
      << R"({"format": "sims-embedding-bank-1", "dim": 3, "captions": [], "clips": [{"clip": "a", "z": [1, 2]}]})";
  EXPECT_THROW(EmbeddingBank::Load(f), Error);
}

MotionTextTrainConfig TinyTrain(const fs::path& out) {
  MotionTextTrainConfig c;
  c.model = TinyModel();
  c.out_dir = out.string();
  c.steps = 12;
  c.align_weight = 1.0;  // the weight these expectations were written with (default 0.1)
  c.batch_size = 4;
  c.log_every = 3;
  c.checkpoint_every = 6;
  c.threads = 1;
  return c;
}

TEST(TrainMotionTextTest, ResumeMatchesUninterruptedRun) {
  const fake::HashTextEncoder enc(10);
  const std::vector<CaptionedSequence> data = {RandomClip("a", 40, 6, 1), RandomClip("b", 9, 6, 2)};
  const fs::path full = sims::testing::TempDir("tm_full"), part = sims::testing::TempDir("tm_part");
  const MotionTextLosses l_full = TrainMotionText(TinyTrain(full), data, enc);
  auto cfg = TinyTrain(part);
  cfg.steps = 6;
  TrainMotionText(cfg, data, enc);
  cfg.steps = 12;
  const MotionTextLosses l_resumed = TrainMotionText(cfg, data, enc, /*resume=*/true);
  EXPECT_EQ(l_resumed.step, 12);
  EXPECT_DOUBLE_EQ(l_resumed.total, l_full.total);
  const auto m_full = MotionTextModel::Load(full), m_part = MotionTextModel::Load(part);
  const Eigen::MatrixXf w = SampleWindow(data[0], cfg.model, 0.3);
  EXPECT_EQ(m_full.EncodeMotion(w), m_part.EncodeMotion(w));

  // Outputs: resolved config, CSV with one row per logged step, bank with every caption and clip.
  for (const char* f :
       {"config.json", "checkpoint.pt", "model.pt", "model.json", "bank.json", "train_log.csv"})
    EXPECT_TRUE(fs::exists(part / f)) << f;
  std::ifstream csv(part / "train_log.csv");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) rows += line.empty() ? 0 : 1;
  EXPECT_EQ(rows, 1 + 4);
  const auto bank = EmbeddingBank::Load(part / "bank.json");
  EXPECT_EQ(bank.captions().size(), 4u);
  EXPECT_EQ(bank.clips().size(), 2u);

  // A resumed run must not silently change the network.
  cfg.model.d_model = 32;
  cfg.model.num_heads = 2;
  EXPECT_THROW(TrainMotionText(cfg, data, enc, true), Error);
}

TEST(TrainMotionTextTest, StyleEmbedderUsesStoredEncoderSettings) {
  // Loading rebuilds the text encoder from model.json; a mismatched size is a clear error.
  const fake::HashTextEncoder enc(10);
  const std::vector<CaptionedSequence> data = {RandomClip("a", 20, 6, 1)};
  const fs::path out = sims::testing::TempDir("tm_embedder");
  TrainMotionText(TinyTrain(out), data, enc);
  const MotionTextModel model = MotionTextModel::Load(out);
  auto shared = std::make_shared<fake::HashTextEncoder>(10);
  const StyleEmbedder embedder(model, shared, EmbeddingBank::Load(out / "bank.json"));
  const StyleQuery q = embedder.Lookup("a moves", 1);
  EXPECT_NEAR(q.z.norm(), 1.f, 1e-5f);
  ASSERT_EQ(q.clips.size(), 1u);
  EXPECT_EQ(q.clips[0].clip, "a");
  EXPECT_THROW(StyleEmbedder(model, std::make_shared<fake::HashTextEncoder>(11),
                             EmbeddingBank::Load(out / "bank.json")),
               Error);
}

// A missing model names the command that trains one, not just the absent file.
TEST(MotionTextModelTest, MissingModelNamesTheTrainingCommand) {
  const auto dir = sims::testing::TempDir("no_model");
  const std::string e = sims::testing::ErrorOf([&] { MotionTextModel::Load(dir); });
  EXPECT_NE(e.find((dir / "model.json").string()), std::string::npos) << e;
  EXPECT_NE(e.find("train_text_motion --manifest"), std::string::npos) << e;
  EXPECT_EQ(TrainStyleModelCommand().find("build/bin/train_text_motion"), 0u);
}

}  // namespace
}  // namespace sims::language
