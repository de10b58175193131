// Embedding bank and the run-time caption → z path (SIMS §3.3).
//
// bank.json (written by train_text_motion):
//   {"format": "sims-embedding-bank-1", "dim": 64, "text_encoder": "...",
//    "captions": [{"text": "...", "clip": "...", "z": [64 floats]}, ...],
//    "clips": [{"clip": "...", "z": [64 floats]}, ...]}
// Caption entries hold the unit MLP_d(t) of each training caption; clip entries the unit motion
// embedding of each training clip. StyleEmbedder turns a new caption into z through the frozen
// text encoder and MLP_d and reports the nearest bank entries by cosine similarity, so a user sees
// how a style was understood.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "sims/language/motion_text.h"
#include "sims/language/text_encoder.h"

namespace sims::language {

/// One bank entry (a caption of a clip, or a clip with empty text).
struct BankEntry {
  std::string text;   ///< Caption text ("" for clip entries).
  std::string clip;   ///< Clip name.
  Eigen::VectorXf z;  ///< Unit embedding.
};

/// A nearest-neighbour answer.
struct StyleMatch {
  std::string text;  ///< Caption text ("" for clips).
  std::string clip;  ///< Clip name.
  float cosine = 0;  ///< Cosine similarity with the query z.
};

/// Caption → z and clip → z tables with cosine nearest-neighbour search.
class EmbeddingBank {
 public:
  /// Embedding size (0 until the first entry).
  int dim() const { return dim_; }
  /// Description of the text encoder used to build the bank.
  const std::string& text_encoder() const { return text_encoder_; }
  /// Sets the text encoder description.
  void set_text_encoder(const std::string& s) { text_encoder_ = s; }

  /// Adds a caption entry (z is normalised).
  void AddCaption(const std::string& text, const std::string& clip, const Eigen::VectorXf& z);
  /// Adds or replaces a clip entry (z is normalised).
  void AddClip(const std::string& clip, const Eigen::VectorXf& z);
  /// Caption entries in insertion order.
  const std::vector<BankEntry>& captions() const { return captions_; }
  /// Clip entries in insertion order.
  const std::vector<BankEntry>& clips() const { return clips_; }
  /// z of a clip, or nullptr.
  const Eigen::VectorXf* ClipZ(const std::string& clip) const;

  /// The `k` caption entries most similar to `z` (highest cosine first; a caption text shared by
  /// several clips is listed once, with the first such clip).
  std::vector<StyleMatch> NearestCaptions(const Eigen::VectorXf& z, int k) const;
  /// The `k` clip entries most similar to `z`.
  std::vector<StyleMatch> NearestClips(const Eigen::VectorXf& z, int k) const;

  /// Writes bank.json atomically.
  void Save(const std::filesystem::path& path) const;
  /// Reads bank.json; errors name the file and field.
  static EmbeddingBank Load(const std::filesystem::path& path);

 private:
  void CheckDim(const Eigen::VectorXf& z);
  int dim_ = 0;
  std::string text_encoder_;
  std::vector<BankEntry> captions_, clips_;
};

/// Result of StyleEmbedder::Lookup.
struct StyleQuery {
  std::string caption;               ///< The query.
  Eigen::VectorXf z;                 ///< Unit z (MLP_d of the text feature).
  std::vector<StyleMatch> captions;  ///< Nearest training captions.
  std::vector<StyleMatch> clips;     ///< Nearest training clips.
};

/// {"caption", "z", "captions": [{"text", "clip", "cosine"}], "clips": [{"clip", "cosine"}]}.
nlohmann::json StyleQueryToJson(const StyleQuery& q);
/// Human-readable report of a query (nearest captions and clips with cosines).
std::string FormatStyleQuery(const StyleQuery& q);

/// Run-time caption → z with the trained model, its text encoder and its bank.
class StyleEmbedder {
 public:
  /// Assembles from parts (shares them).
  StyleEmbedder(MotionTextModel model, std::shared_ptr<const TextEncoder> encoder,
                EmbeddingBank bank);
  /// Loads model.pt/model.json/bank.json from a train_text_motion output folder and rebuilds the
  /// text encoder it was trained with; checks the encoder's feature size matches.
  static StyleEmbedder Load(const std::filesystem::path& dir);

  /// Unit z of a caption (what the policy and discriminator are conditioned on).
  Eigen::VectorXf Embed(const std::string& caption) const;
  /// z plus the `k` nearest training captions and clips.
  StyleQuery Lookup(const std::string& caption, int k = 5) const;
  /// z of a training clip (from the bank), or nullptr.
  const Eigen::VectorXf* ClipZ(const std::string& clip) const { return bank_.ClipZ(clip); }

  /// The model.
  const MotionTextModel& model() const { return model_; }
  /// The text encoder.
  const TextEncoder& encoder() const { return *encoder_; }
  /// The bank.
  const EmbeddingBank& bank() const { return bank_; }

 private:
  MotionTextModel model_;
  std::shared_ptr<const TextEncoder> encoder_;
  EmbeddingBank bank_;
};

}  // namespace sims::language
