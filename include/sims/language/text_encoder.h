// Text encoders: a caption -> a fixed-size feature vector t (the "CLIP feature" of SIMS eq. 3-5).
//
// Two implementations behind one interface, chosen by TextEncoderConfig::kind:
//  * "builtin" (offline, default): CLIP tokenisation + GloVe 100-d word vectors
//    (data/language/glove_subset.bin), SIF-weighted mean (a / (a + p(w)), p from the word's
//    frequency rank), WordNet base forms mixed in for inflected words, and a fall-back for words
//    outside the subset (base form -> WordNet synonyms -> CLIP BPE sub-word pieces). Output is
//    L2-normalised; `dim` > 0 applies a fixed, seeded orthonormal projection.
//  * "torchscript": a user-supplied TorchScript module (e.g. CLIP's text tower) called on
//    int64 token ids [B, 77] from the CLIP tokenizer, returning float [B, D].
//
// Exporting CLIP's text tower (Python, once, on a machine that has the `clip` package):
//
//   import torch, clip
//   model, _ = clip.load("ViT-B/32", device="cpu", jit=False)
//   class TextTower(torch.nn.Module):
//       def __init__(self, m):
//           super().__init__()
//           self.m = m
//       def forward(self, tokens: torch.Tensor) -> torch.Tensor:  # [B, 77] int64
//           return self.m.encode_text(tokens).float()
//   tower = TextTower(model.float().eval())
//   example = clip.tokenize(["a person sits on the chair", "a person walks"])
//   torch.jit.trace(tower, example).save("clip_text_vitb32.pt")
//
// then set {"kind": "torchscript", "torchscript_path": "clip_text_vitb32.pt"} (features are 512-d).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/core/config.h"

namespace sims::language {

/// Which text encoder to build and how (JSON-bound; see configs/language/).
struct TextEncoderConfig {
  std::string kind = "builtin";  ///< "builtin" or "torchscript".
  bool normalize = true;         ///< L2-normalise the output feature.
  // builtin
  int dim = 0;                   ///< Output size; 0 = the word-vector size (100).
  uint64_t projection_seed = 7;  ///< Seed of the fixed projection when dim != word-vector size.
  double sif_a = 1e-3;           ///< SIF smoothing a in a / (a + p(w)).
  double lemma_weight = 0.5;     ///< Weight of the WordNet base form mixed into inflected words.
  bool use_wordnet = true;       ///< Use data/language/wordnet.txt when present.
  std::string word_vectors;      ///< Path of glove_subset.bin ("" = data/language/).
  std::string wordnet;           ///< Path of wordnet.txt ("" = data/language/).
  std::string bpe;               ///< Path of clip_bpe.txt ("" = data/language/).
  // torchscript
  std::string torchscript_path;    ///< TorchScript file (required for kind "torchscript").
  std::string method = "forward";  ///< Method to call (e.g. "encode_text" on a full CLIP module).
  int context_length = 77;         ///< Token sequence length fed to the module.

  /// Binds fields to JSON.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(kind));
    a->Visit(SIMS_NVP(normalize));
    a->Visit(SIMS_NVP(dim));
    a->Visit(SIMS_NVP(projection_seed));
    a->Visit(SIMS_NVP(sif_a));
    a->Visit(SIMS_NVP(lemma_weight));
    a->Visit(SIMS_NVP(use_wordnet));
    a->Visit(SIMS_NVP(word_vectors));
    a->Visit(SIMS_NVP(wordnet));
    a->Visit(SIMS_NVP(bpe));
    a->Visit(SIMS_NVP(torchscript_path));
    a->Visit(SIMS_NVP(method));
    a->Visit(SIMS_NVP(context_length));
  }
  /// Checks ranges and the kind.
  void Validate() const;
};

/// Caption -> feature vector. Implementations are immutable and thread-safe.
class TextEncoder {
 public:
  virtual ~TextEncoder() = default;
  /// Size of the feature vector.
  virtual int dim() const = 0;
  /// Feature of one caption.
  virtual Eigen::VectorXf Encode(const std::string& caption) const = 0;
  /// Features of many captions, one row per caption ([N, dim]).
  virtual Eigen::MatrixXf EncodeBatch(const std::vector<std::string>& captions) const;
  /// Short provenance string stored with trained models (e.g. "builtin:glove100").
  virtual std::string Describe() const = 0;
};

/// How one word of a caption was represented by the built-in encoder.
struct WordTrace {
  std::string word;    ///< The pre-token.
  std::string source;  ///< "exact", "lemma", "synonym", "subword" or "unknown".
  std::string used;    ///< Word(s) whose vectors were used.
  float weight = 0;    ///< SIF weight in the pooled mean.
};

/// The offline encoder: GloVe subset + WordNet + CLIP BPE (see the file comment).
class BuiltinTextEncoder : public TextEncoder {
 public:
  /// Loads the data files named in `config` (or the data/language defaults); throws sims::Error
  /// naming the missing file and the `prepare_assets` command that creates it.
  explicit BuiltinTextEncoder(const TextEncoderConfig& config = {});
  ~BuiltinTextEncoder() override;
  int dim() const override;
  Eigen::VectorXf Encode(const std::string& caption) const override;
  std::string Describe() const override;
  /// Per-word account of how a caption was encoded (for `text_to_style --explain`).
  std::vector<WordTrace> Explain(const std::string& caption) const;
  /// True when the default data files exist (tests skip otherwise).
  static bool DataAvailable();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Builds the encoder `config` names; `source` labels errors (a config file path).
std::unique_ptr<TextEncoder> MakeTextEncoder(const TextEncoderConfig& config,
                                             const std::string& source = "text_encoder");

/// The TorchScript encoder (defined in torchscript_encoder.cpp; torch stays out of this header).
std::unique_ptr<TextEncoder> MakeTorchScriptTextEncoder(const TextEncoderConfig& config);

}  // namespace sims::language
