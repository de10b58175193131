// Theme → short-script retrieval: BM25 over each script's summary and captions, the emotion of
// the theme step, room types named in the theme and, when a text encoder is plugged in, cosine
// similarity of text embeddings. Scores are comparable across scripts for one query.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/core/config.h"
#include "sims/planner/script.h"

namespace sims::planner {

/// Maps a text to an embedding (e.g. language::TextEncoder::Encode); empty = not available.
using TextEmbedder = std::function<Eigen::VectorXf(const std::string&)>;

/// Okapi BM25 over stemmed content words.
class Bm25Index {
 public:
  /// Indexes the documents; k1 and b are the usual BM25 parameters.
  explicit Bm25Index(const std::vector<std::string>& documents, double k1 = 1.2, double b = 0.75);
  /// BM25 score of every document for the query (same order as the documents).
  std::vector<double> Score(const std::string& query) const;
  /// Number of documents.
  std::size_t size() const { return docs_.size(); }

 private:
  std::vector<std::map<std::string, int>> docs_;
  std::vector<int> lengths_;
  std::map<std::string, int> df_;
  double avg_len_ = 1.0, k1_, b_;
};

/// Weights of the retrieval score.
struct RetrievalConfig {
  double bm25_k1 = 1.2;       ///< BM25 term saturation.
  double bm25_b = 0.75;       ///< BM25 length normalisation.
  double w_text = 1.0;        ///< Weight of the normalised BM25 score (step 70%, whole theme 30%).
  double w_emotion = 1.0;     ///< Weight of the emotion match.
  double w_room = 0.5;        ///< Weight of a room type the theme names.
  double w_embedding = 0.5;   ///< Weight of embedding cosine similarity (if an embedder is set).
  double w_same_room = 0.15;  ///< Bonus for staying in the previous step's room type.
  double pick_margin = 0.1;   ///< Scripts within this margin of the best are equally good.
  int pick_top = 3;           ///< At most this many near-best scripts are drawn from (by seed).

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(bm25_k1));
    a->Visit(SIMS_NVP(bm25_b));
    a->Visit(SIMS_NVP(w_text));
    a->Visit(SIMS_NVP(w_emotion));
    a->Visit(SIMS_NVP(w_room));
    a->Visit(SIMS_NVP(w_embedding));
    a->Visit(SIMS_NVP(w_same_room));
    a->Visit(SIMS_NVP(pick_margin));
    a->Visit(SIMS_NVP(pick_top));
  }
  /// Non-negative weights, pick_top ≥ 1.
  void Validate() const;
};

/// One scored script.
struct ScoredScript {
  int index = -1;          ///< Index in the database.
  double score = 0.0;      ///< Total score.
  double text = 0.0;       ///< Normalised BM25 part (0..1).
  double emotion = 0.0;    ///< Emotion match (0..1).
  double room = 0.0;       ///< Room match (0 or 1).
  double embedding = 0.0;  ///< Cosine similarity (0 without an embedder).
};

/// A retrieval query: one step of the arc within the whole theme.
struct RetrievalQuery {
  std::string text;                 ///< The step's text.
  std::string theme;                ///< The whole theme.
  std::string emotion = "neutral";  ///< The step's emotion.
  std::vector<std::string> rooms;   ///< Room types the theme names (preferred).
  std::string previous_room;        ///< Room type of the previous step ("" for the first).
};

/// Ranks the database's scripts for queries.
class ScriptRetriever {
 public:
  /// Keeps references to `db` and `vocab`; both must outlive the retriever.
  ScriptRetriever(const ScriptDatabase& db, const Vocabulary& vocab, RetrievalConfig config = {},
                  TextEmbedder embedder = {});
  /// All scripts, best first (ties broken by database order).
  std::vector<ScoredScript> Rank(const RetrievalQuery& query) const;
  /// Room types named in a text ("in the kitchen" → dining room), in order of appearance.
  std::vector<std::string> RoomsIn(const std::string& text) const;
  /// The query text with furniture aliases replaced by canonical names (couch → sofa).
  std::string ExpandFurniture(const std::string& text) const;
  /// The database.
  const ScriptDatabase& db() const { return db_; }
  /// The configuration.
  const RetrievalConfig& config() const { return config_; }

 private:
  const ScriptDatabase& db_;
  const Vocabulary& vocab_;
  RetrievalConfig config_;
  TextEmbedder embedder_;
  Bm25Index index_;
  mutable std::vector<Eigen::VectorXf> doc_embeddings_;
};

}  // namespace sims::planner
