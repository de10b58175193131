#include "sims/language/word_vectors.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <numeric>
#include <sstream>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"

namespace sims::language {

namespace {

constexpr char kMagic[8] = {'S', 'I', 'M', 'S', 'W', 'V', '0', '1'};

template <typename T>
void Put(std::string* out, T v) {
  out->append(reinterpret_cast<const char*>(&v), sizeof(T));
}

class Reader {
 public:
  Reader(const std::string& bytes, const std::filesystem::path& path)
      : bytes_(bytes), path_(path) {}
  template <typename T>
  T Get(const char* field) {
    T v;
    Take(reinterpret_cast<char*>(&v), sizeof(T), field);
    return v;
  }
  void Take(char* out, std::size_t n, const char* field) {
    if (pos_ + n > bytes_.size())
      ThrowInputError(path_.string(), field, "a complete word-vector file",
                      "truncated (re-run prepare_assets --only glove --force)");
    std::memcpy(out, bytes_.data() + pos_, n);
    pos_ += n;
  }
  std::size_t remaining() const { return bytes_.size() - pos_; }

 private:
  const std::string& bytes_;
  const std::filesystem::path& path_;
  std::size_t pos_ = 0;
};

}  // namespace

std::filesystem::path WordVectors::DefaultPath() { return DataPath("language/glove_subset.bin"); }

void WordVectors::Add(const std::string& word, uint32_t rank, const float* vec) {
  if (index_.count(word)) return;
  index_.emplace(word, size());
  words_.push_back(word);
  ranks_.push_back(rank);
  data_.insert(data_.end(), vec, vec + dim_);
}

void WordVectors::SortByRank() {
  std::vector<int> order(words_.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return ranks_[static_cast<std::size_t>(a)] < ranks_[static_cast<std::size_t>(b)];
  });
  WordVectors sorted(dim_);
  for (int i : order) sorted.Add(words_[i], ranks_[i], data_.data() + std::size_t(i) * dim_);
  *this = std::move(sorted);
}

int WordVectors::Find(const std::string& word) const {
  const auto it = index_.find(word);
  return it == index_.end() ? -1 : it->second;
}

void WordVectors::Save(const std::filesystem::path& path) const {
  std::string out;
  out.reserve(16 + words_.size() * 16 + data_.size() * sizeof(float));
  out.append(kMagic, sizeof(kMagic));
  Put<uint32_t>(&out, static_cast<uint32_t>(dim_));
  Put<uint32_t>(&out, static_cast<uint32_t>(words_.size()));
  for (std::size_t i = 0; i < words_.size(); ++i) {
    SIMS_CHECK(words_[i].size() < 65536);
    Put<uint32_t>(&out, ranks_[i]);
    Put<uint16_t>(&out, static_cast<uint16_t>(words_[i].size()));
    out += words_[i];
  }
  out.append(reinterpret_cast<const char*>(data_.data()), data_.size() * sizeof(float));
  WriteFileAtomic(path, out);
}

WordVectors WordVectors::Load(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    ThrowInputError(path.string(), "", "the GloVe subset file",
                    "file not found (run `prepare_assets --only glove` after cmake/setup.sh)");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  Reader r(bytes, path);
  char magic[8];
  r.Take(magic, 8, "header");
  if (std::memcmp(magic, kMagic, 8) != 0)
    ThrowInputError(path.string(), "header", "magic SIMSWV01", "another file type");
  const uint32_t dim = r.Get<uint32_t>("dim");
  const uint32_t count = r.Get<uint32_t>("count");
  if (dim == 0 || dim > 4096) ThrowInputError(path.string(), "dim", "1..4096", std::to_string(dim));
  WordVectors wv(static_cast<int>(dim));
  wv.words_.reserve(count);
  wv.ranks_.reserve(count);
  wv.index_.reserve(count);
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t rank = r.Get<uint32_t>("rank");
    const uint16_t len = r.Get<uint16_t>("word length");
    std::string w(len, '\0');
    r.Take(w.data(), len, "word");
    wv.index_.emplace(w, static_cast<int>(i));
    wv.words_.push_back(std::move(w));
    wv.ranks_.push_back(rank);
  }
  const std::size_t floats = std::size_t(count) * dim;
  if (r.remaining() != floats * sizeof(float))
    ThrowInputError(path.string(), "vectors", std::to_string(floats) + " float32 values",
                    std::to_string(r.remaining()) + " bytes");
  wv.data_.resize(floats);
  r.Take(reinterpret_cast<char*>(wv.data_.data()), floats * sizeof(float), "vectors");
  return wv;
}

}  // namespace sims::language
