#include "sims/language/embedding_bank.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <set>

#include "sims/core/config.h"
#include "sims/core/error.h"

namespace sims::language {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kFormat = "sims-embedding-bank-1";

Eigen::VectorXf Unit(const Eigen::VectorXf& z) {
  const float n = z.norm();
  return n > 0 ? Eigen::VectorXf(z / n) : z;
}

// The k best entries by cosine; with `unique_text`, repeated caption texts (the same caption on
// several clips has the same z) are listed once, with the first clip that carries them.
std::vector<StyleMatch> Nearest(const std::vector<BankEntry>& entries, const Eigen::VectorXf& z,
                                int k, bool unique_text) {
  const Eigen::VectorXf q = Unit(z);
  std::vector<std::pair<float, std::size_t>> scored;
  scored.reserve(entries.size());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (entries[i].z.size() != q.size()) continue;
    scored.emplace_back(entries[i].z.dot(q), i);
  }
  // Ties resolve by insertion order so answers are reproducible.
  std::sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  std::vector<StyleMatch> out;
  std::set<std::string> seen;
  for (const auto& [cosine, i] : scored) {
    if (static_cast<int>(out.size()) >= k) break;
    const auto& e = entries[i];
    if (unique_text && !seen.insert(e.text).second) continue;
    out.push_back({e.text, e.clip, cosine});
  }
  return out;
}

Eigen::VectorXf ReadZ(const json& j, const std::string& src, const std::string& field, int dim) {
  if (!j.is_array() || (dim > 0 && static_cast<int>(j.size()) != dim))
    ThrowInputError(src, field, "an array of " + std::to_string(dim) + " numbers");
  Eigen::VectorXf z(static_cast<Eigen::Index>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number()) ThrowInputError(src, field, "numbers", j[i].dump());
    z[static_cast<Eigen::Index>(i)] = j[i].get<float>();
  }
  return z;
}

}  // namespace

void EmbeddingBank::CheckDim(const Eigen::VectorXf& z) {
  if (dim_ == 0) dim_ = static_cast<int>(z.size());
  SIMS_CHECK_MSG(z.size() == dim_, "embedding bank entries must share one size");
}

void EmbeddingBank::AddCaption(const std::string& text, const std::string& clip,
                               const Eigen::VectorXf& z) {
  CheckDim(z);
  captions_.push_back({text, clip, Unit(z)});
}

void EmbeddingBank::AddClip(const std::string& clip, const Eigen::VectorXf& z) {
  CheckDim(z);
  for (auto& e : clips_) {
    if (e.clip == clip) {
      e.z = Unit(z);
      return;
    }
  }
  clips_.push_back({"", clip, Unit(z)});
}

const Eigen::VectorXf* EmbeddingBank::ClipZ(const std::string& clip) const {
  for (const auto& e : clips_)
    if (e.clip == clip) return &e.z;
  return nullptr;
}

std::vector<StyleMatch> EmbeddingBank::NearestCaptions(const Eigen::VectorXf& z, int k) const {
  return Nearest(captions_, z, k, /*unique_text=*/true);
}

std::vector<StyleMatch> EmbeddingBank::NearestClips(const Eigen::VectorXf& z, int k) const {
  return Nearest(clips_, z, k, /*unique_text=*/false);
}

void EmbeddingBank::Save(const fs::path& path) const {
  auto zjson = [](const Eigen::VectorXf& z) {
    return json(std::vector<float>(z.data(), z.data() + z.size()));
  };
  json caps = json::array(), clips = json::array();
  for (const auto& e : captions_)
    caps.push_back({{"text", e.text}, {"clip", e.clip}, {"z", zjson(e.z)}});
  for (const auto& e : clips_) clips.push_back({{"clip", e.clip}, {"z", zjson(e.z)}});
  WriteFileAtomic(path, json{{"format", kFormat},
                             {"dim", dim_},
                             {"text_encoder", text_encoder_},
                             {"captions", caps},
                             {"clips", clips}}
                                .dump() +
                            "\n");
}

EmbeddingBank EmbeddingBank::Load(const fs::path& path) {
  const json j = ReadJsonFile(path);
  const std::string src = path.string();
  if (!j.is_object() || j.value("format", "") != kFormat)
    ThrowInputError(src, "format", std::string("\"") + kFormat + "\"");
  if (!j.contains("dim") || !j["dim"].is_number_integer() || j["dim"].get<int>() <= 0)
    ThrowInputError(src, "dim", "a positive integer");
  EmbeddingBank bank;
  const int dim = j["dim"].get<int>();
  bank.text_encoder_ = j.value("text_encoder", "");
  for (const char* key : {"captions", "clips"}) {
    if (!j.contains(key) || !j[key].is_array()) ThrowInputError(src, key, "an array of entries");
    const json& arr = j[key];
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string field = std::string(key) + "[" + std::to_string(i) + "]";
      const json& e = arr[i];
      if (!e.is_object() || !e.contains("clip") || !e["clip"].is_string() || !e.contains("z"))
        ThrowInputError(src, field, "an object with \"clip\" and \"z\"");
      const Eigen::VectorXf z = ReadZ(e["z"], src, field + ".z", dim);
      if (std::string(key) == "captions") {
        if (!e.contains("text") || !e["text"].is_string())
          ThrowInputError(src, field + ".text", "a string");
        bank.AddCaption(e["text"].get<std::string>(), e["clip"].get<std::string>(), z);
      } else {
        bank.AddClip(e["clip"].get<std::string>(), z);
      }
    }
  }
  bank.dim_ = dim;
  return bank;
}

StyleEmbedder::StyleEmbedder(MotionTextModel model, std::shared_ptr<const TextEncoder> encoder,
                             EmbeddingBank bank)
    : model_(std::move(model)), encoder_(std::move(encoder)), bank_(std::move(bank)) {
  SIMS_CHECK(encoder_ != nullptr);
  if (encoder_->dim() != model_.text_dim())
    throw Error("StyleEmbedder: the text encoder gives " + std::to_string(encoder_->dim()) +
                "-d features but the model was trained on " + std::to_string(model_.text_dim()) +
                "-d features");
}

StyleEmbedder StyleEmbedder::Load(const fs::path& dir) {
  MotionTextModel model = MotionTextModel::Load(dir);
  std::shared_ptr<const TextEncoder> encoder =
      MakeTextEncoder(model.text_encoder_config(), (dir / "model.json").string());
  EmbeddingBank bank = EmbeddingBank::Load(dir / "bank.json");
  if (bank.dim() != model.config().z_dim)
    ThrowInputError((dir / "bank.json").string(), "dim",
                    std::to_string(model.config().z_dim) + " (the model's z_dim)",
                    std::to_string(bank.dim()));
  return StyleEmbedder(std::move(model), std::move(encoder), std::move(bank));
}

Eigen::VectorXf StyleEmbedder::Embed(const std::string& caption) const {
  return model_.EncodeTextFeature(encoder_->Encode(caption));
}

nlohmann::json StyleQueryToJson(const StyleQuery& q) {
  json caps = json::array(), clips = json::array();
  for (const auto& m : q.captions)
    caps.push_back({{"text", m.text}, {"clip", m.clip}, {"cosine", m.cosine}});
  for (const auto& m : q.clips) clips.push_back({{"clip", m.clip}, {"cosine", m.cosine}});
  return {{"caption", q.caption},
          {"z", std::vector<float>(q.z.data(), q.z.data() + q.z.size())},
          {"captions", caps},
          {"clips", clips}};
}

std::string FormatStyleQuery(const StyleQuery& q) {
  std::string out = "caption: " + json(q.caption).dump() + "\nnearest training captions:\n";
  char line[64];
  for (const auto& m : q.captions) {
    std::snprintf(line, sizeof(line), "  %+.3f  ", m.cosine);
    out += line + json(m.text).dump() + "  (clip " + m.clip + ")\n";
  }
  out += "nearest clips:\n";
  for (const auto& m : q.clips) {
    std::snprintf(line, sizeof(line), "  %+.3f  ", m.cosine);
    out += line + m.clip + "\n";
  }
  return out;
}

StyleQuery StyleEmbedder::Lookup(const std::string& caption, int k) const {
  StyleQuery q;
  q.caption = caption;
  q.z = Embed(caption);
  q.captions = bank_.NearestCaptions(q.z, k);
  q.clips = bank_.NearestClips(q.z, k);
  return q;
}

}  // namespace sims::language
