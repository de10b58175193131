// End-to-end check of SIMS eq. 3-5 on synthetic data: after training, held-out paraphrases of a
// style's captions must retrieve a clip of that style, and captions of different styles must lie
// farther apart than paraphrases of one style.
#include <cmath>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "sims/core/log.h"
#include "sims/core/rng.h"
#include "sims/language/embedding_bank.h"
#include "sims/language/motion_text.h"
#include "sims/language/text_encoder.h"

namespace sims::language {
namespace {

struct Style {
  std::string name;
  std::vector<std::string> train;     // captions seen in training
  std::vector<std::string> held_out;  // paraphrases never seen
};

const std::vector<Style>& Styles() {
  static const std::vector<Style> styles = {
      {"sad",
       {"a person walks sadly", "someone walking with a sad face", "a sad man walks slowly",
        "walking in a depressed way"},
       {"an unhappy person is walking", "a gloomy walk full of sorrow"}},
      {"happy",
       {"a person walks happily", "someone walking with a joyful smile", "a cheerful man walks",
        "walking in a happy excited way"},
       {"a glad person is walking", "a delighted walk full of joy"}},
      {"angry",
       {"a person walks angrily", "someone stomping around in anger",
        "an angry man walks aggressively", "walking in a furious way"},
       {"a mad person is walking with rage", "an irritated annoyed walk"}},
      {"old",
       {"an old man walks", "an elderly person walking slowly with a cane",
        "walking like a grandfather", "an aged person walks"},
       {"a senior citizen is walking", "a frail old woman walks"}},
      {"drunk",
       {"a drunk person staggers", "someone walking drunk and swaying",
        "a drunken man stumbles around", "walking like he had too much alcohol"},
       {"an intoxicated person is walking", "a tipsy man wobbles after beer"}},
      {"robot",
       {"a person walks like a robot", "someone walking stiffly like a machine",
        "a robotic mechanical walk", "walking like an android"},
       {"moving like a stiff metal automaton", "a rigid robot-like gait"}},
  };
  return styles;
}

// Synthetic (clearly not mocap) feature sequences: each style has its own per-feature amplitude,
// offset and frequency; clips of a style differ in phase, amplitude jitter and noise.
std::vector<CaptionedSequence> SyntheticStyleClips(int feature_dim, int clips_per_style) {
  std::vector<CaptionedSequence> data;
  for (std::size_t s = 0; s < Styles().size(); ++s) {
    Rng style_rng(100 + s);
    Eigen::VectorXf amp(feature_dim), offset(feature_dim), phase(feature_dim);
    for (int k = 0; k < feature_dim; ++k) {
      amp[k] = static_cast<float>(style_rng.Uniform(0.2, 1.5));
      offset[k] = static_cast<float>(style_rng.Normal(0, 1));
      phase[k] = static_cast<float>(style_rng.Uniform(0, 6.28));
    }
    const double freq = 0.5 + 0.4 * static_cast<double>(s);
    for (int c = 0; c < clips_per_style; ++c) {
      Rng rng(1000 + 10 * s + c);
      CaptionedSequence seq;
      seq.clip_name = Styles()[s].name + "_" + std::to_string(c);
      seq.fps = 30;
      const int frames = 60 + static_cast<int>(rng.UniformInt(40));
      const double shift = rng.Uniform(0, 6.28), gain = rng.Uniform(0.85, 1.15);
      seq.features.resize(frames, feature_dim);
      for (int t = 0; t < frames; ++t)
        for (int k = 0; k < feature_dim; ++k)
          seq.features(t, k) = static_cast<float>(
              offset[k] + gain * amp[k] * std::sin(freq * t / 5.0 + phase[k] + shift) +
              0.05 * rng.Normal());
      seq.captions = Styles()[s].train;
      data.push_back(std::move(seq));
    }
  }
  return data;
}

std::string StyleOf(const std::string& clip) { return clip.substr(0, clip.find('_')); }

TEST(RetrievalTest, HeldOutParaphrasesFindTheirStyle) {
  if (!BuiltinTextEncoder::DataAvailable())
    GTEST_SKIP() << "GloVe subset / CLIP vocabulary not prepared: run cmake/setup.sh, then "
                    "build/bin/prepare_assets";
  const auto data = SyntheticStyleClips(/*feature_dim=*/24, /*clips_per_style=*/2);
  MotionTextTrainConfig cfg;
  cfg.model.feature_dim = 24;
  cfg.model.seq_frames = 60;
  cfg.model.frames_per_token = 6;
  cfg.model.d_model = 32;
  cfg.model.num_heads = 2;
  cfg.model.encoder_layers = 1;
  cfg.model.decoder_layers = 1;
  cfg.model.ff_dim = 64;
  cfg.model.mlp_hidden = {128};
  cfg.steps = 300;
  cfg.align_weight = 1.0;  // what this small run was tuned with (the default is 0.1)
  cfg.batch_size = 32;
  cfg.learning_rate = 2e-3;
  cfg.log_every = 100;
  cfg.checkpoint_every = 300;
  cfg.out_dir = sims::testing::TempDir("retrieval").string();
  auto encoder = std::make_shared<BuiltinTextEncoder>(cfg.text_encoder);
  const MotionTextLosses losses = TrainMotionText(cfg, data, *encoder);
  EXPECT_LT(losses.align, 0.3);

  const StyleEmbedder embedder(MotionTextModel::Load(cfg.out_dir), encoder,
                               EmbeddingBank::Load(std::string(cfg.out_dir) + "/bank.json"));
  int correct = 0, total = 0;
  for (const Style& style : Styles()) {
    for (const std::string& caption : style.held_out) {
      const StyleQuery q = embedder.Lookup(caption, 1);
      ASSERT_EQ(q.clips.size(), 1u);
      const bool ok = StyleOf(q.clips[0].clip) == style.name;
      correct += ok ? 1 : 0;
      ++total;
      if (!ok)
        spdlog::warn("'{}' -> clip {} (cos {:.3f}), nearest caption '{}'", caption, q.clips[0].clip,
                     q.clips[0].cosine, q.captions[0].text);
    }
  }
  const double accuracy = static_cast<double>(correct) / total;
  RecordProperty("held_out_accuracy", std::to_string(accuracy));
  std::printf("[ retrieval ] held-out paraphrase -> clip accuracy %d/%d = %.2f\n", correct, total,
              accuracy);
  EXPECT_GE(accuracy, 0.8);

  // Paraphrases of one style are closer in z than captions of different styles.
  double same = 0, diff = 0;
  int n_same = 0, n_diff = 0;
  std::vector<std::pair<std::size_t, Eigen::VectorXf>> zs;
  for (std::size_t s = 0; s < Styles().size(); ++s)
    for (const auto& c : Styles()[s].held_out) zs.emplace_back(s, embedder.Embed(c));
  for (std::size_t i = 0; i < zs.size(); ++i)
    for (std::size_t j = i + 1; j < zs.size(); ++j) {
      const double cos = zs[i].second.dot(zs[j].second);
      if (zs[i].first == zs[j].first) {
        same += cos;
        ++n_same;
      } else {
        diff += cos;
        ++n_diff;
      }
    }
  same /= n_same;
  diff /= n_diff;
  std::printf("[ retrieval ] mean cosine: same style %.3f, different styles %.3f\n", same, diff);
  EXPECT_GT(same, diff + 0.2);
}

}  // namespace
}  // namespace sims::language
