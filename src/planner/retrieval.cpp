#include "sims/planner/retrieval.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "sims/planner/text.h"

namespace sims::planner {

Bm25Index::Bm25Index(const std::vector<std::string>& documents, double k1, double b)
    : k1_(k1), b_(b) {
  double total = 0.0;
  for (const std::string& d : documents) {
    std::map<std::string, int> tf;
    std::vector<std::string> tokens = Tokens(d);
    for (const std::string& t : tokens) ++tf[t];
    for (const auto& [t, n] : tf) ++df_[t];
    lengths_.push_back(static_cast<int>(tokens.size()));
    total += static_cast<double>(tokens.size());
    docs_.push_back(std::move(tf));
  }
  if (!documents.empty()) avg_len_ = std::max(1.0, total / static_cast<double>(documents.size()));
}

std::vector<double> Bm25Index::Score(const std::string& query) const {
  std::vector<double> scores(docs_.size(), 0.0);
  std::vector<std::string> q = Tokens(query);
  std::sort(q.begin(), q.end());
  q.erase(std::unique(q.begin(), q.end()), q.end());
  const double n = static_cast<double>(docs_.size());
  for (const std::string& t : q) {
    auto it = df_.find(t);
    if (it == df_.end()) continue;
    double idf = std::log(1.0 + (n - it->second + 0.5) / (it->second + 0.5));
    for (std::size_t d = 0; d < docs_.size(); ++d) {
      auto f = docs_[d].find(t);
      if (f == docs_[d].end()) continue;
      double tf = f->second;
      double norm = k1_ * (1.0 - b_ + b_ * lengths_[d] / avg_len_);
      scores[d] += idf * tf * (k1_ + 1.0) / (tf + norm);
    }
  }
  return scores;
}

void RetrievalConfig::Validate() const {
  Require(bm25_k1 >= 0 && bm25_b >= 0 && bm25_b <= 1, "bm25_b", "k1 ≥ 0 and b in [0, 1]");
  Require(w_text >= 0 && w_emotion >= 0 && w_room >= 0 && w_embedding >= 0 && w_same_room >= 0,
          "w_text", "non-negative weights");
  Require(pick_margin >= 0, "pick_margin", "a non-negative number");
  Require(pick_top >= 1, "pick_top", "an integer ≥ 1");
}

namespace {
std::vector<std::string> DocumentTexts(const ScriptDatabase& db, const ScriptRetriever* r) {
  std::vector<std::string> docs;
  for (const ShortScript& s : db.scripts()) docs.push_back(r->ExpandFurniture(s.Text()));
  return docs;
}

std::vector<double> Normalised(std::vector<double> v) {
  double mx = v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
  if (mx > 0)
    for (double& x : v) x /= mx;
  return v;
}
}  // namespace

ScriptRetriever::ScriptRetriever(const ScriptDatabase& db, const Vocabulary& vocab,
                                 RetrievalConfig config, TextEmbedder embedder)
    : db_(db),
      vocab_(vocab),
      config_(config),
      embedder_(std::move(embedder)),
      index_(DocumentTexts(db, this), config.bm25_k1, config.bm25_b) {}

std::string ScriptRetriever::ExpandFurniture(const std::string& text) const {
  // Appends canonical names for furniture words and two-word names, so "couch" finds "sofa"
  // and "bedside table" finds "nightstand".
  std::vector<std::string> words = Words(text);
  std::string extra;
  for (std::size_t i = 0; i < words.size(); ++i) {
    for (std::size_t len = 3; len >= 1; --len) {
      if (i + len > words.size()) continue;
      std::vector<std::string> span(words.begin() + i, words.begin() + i + len);
      std::string phrase = Join(span, " ");
      if (len == 1 && IsStopWord(phrase)) continue;
      auto f = vocab_.FindFurniture(phrase);
      if (f && *f != "floor" && Vocabulary::Squash(*f) != Vocabulary::Squash(phrase)) {
        std::string name = *f;
        std::replace(name.begin(), name.end(), '_', ' ');
        extra += " " + name;
        break;
      }
    }
  }
  return text + extra;
}

std::vector<std::string> ScriptRetriever::RoomsIn(const std::string& text) const {
  std::vector<std::string> words = Words(text), rooms;
  for (std::size_t i = 0; i < words.size(); ++i) {
    for (std::size_t len = 3; len >= 1; --len) {
      if (i + len > words.size()) continue;
      std::vector<std::string> span(words.begin() + i, words.begin() + i + len);
      // Single words like "living" or "dining" alone are too ambiguous ("dining" could be a verb
      // in a theme) only when followed by nothing; accept them anyway: they are rare otherwise.
      auto r = vocab_.FindRoomType(Join(span, " "));
      if (r) {
        if (std::find(rooms.begin(), rooms.end(), *r) == rooms.end()) rooms.push_back(*r);
        i += len - 1;
        break;
      }
    }
  }
  return rooms;
}

std::vector<ScoredScript> ScriptRetriever::Rank(const RetrievalQuery& q) const {
  const auto& scripts = db_.scripts();
  std::vector<double> step = Normalised(index_.Score(ExpandFurniture(q.text)));
  std::vector<double> whole =
      Normalised(index_.Score(ExpandFurniture(q.theme.empty() ? q.text : q.theme)));
  Eigen::VectorXf query_embedding;
  if (embedder_) {
    if (doc_embeddings_.empty()) {
      for (const ShortScript& s : scripts) {
        Eigen::VectorXf e = embedder_(s.summary);
        if (e.norm() > 0) e.normalize();
        doc_embeddings_.push_back(e);
      }
    }
    query_embedding = embedder_(q.text);
    if (query_embedding.norm() > 0) query_embedding.normalize();
  }
  std::vector<ScoredScript> out;
  for (std::size_t i = 0; i < scripts.size(); ++i) {
    const ShortScript& s = scripts[i];
    ScoredScript r;
    r.index = static_cast<int>(i);
    r.text = 0.7 * step[i] + 0.3 * whole[i];
    if (s.emotion == q.emotion) {
      r.emotion = 1.0;
    } else {
      // Scripts whose keyframes carry the emotion as a secondary tag match partially.
      for (const Keyframe& k : s.keyframes)
        if (k.emotion == q.emotion) r.emotion = 0.3;
    }
    if (std::find(q.rooms.begin(), q.rooms.end(), s.scene) != q.rooms.end()) r.room = 1.0;
    if (embedder_ && query_embedding.size() == doc_embeddings_[i].size())
      r.embedding = query_embedding.dot(doc_embeddings_[i]);
    r.score = config_.w_text * r.text + config_.w_emotion * r.emotion + config_.w_room * r.room +
              config_.w_embedding * r.embedding;
    if (!q.previous_room.empty() && s.scene == q.previous_room) r.score += config_.w_same_room;
    out.push_back(r);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const ScoredScript& a, const ScoredScript& b) { return a.score > b.score; });
  return out;
}

}  // namespace sims::planner
