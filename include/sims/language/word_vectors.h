// A compact table of word vectors (the GloVe 100-d subset written by `prepare_assets`).
//
// Binary layout of glove_subset.bin (little-endian):
//   "SIMSWV01" | uint32 dim | uint32 count | count × {uint32 rank, uint16 length, bytes} |
//   count × dim float32 (row per word).
// `rank` is the word's position in the source's frequency-ordered word list (0 = most frequent).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace sims::language {

/// Word → vector lookup with frequency ranks; immutable once built.
class WordVectors {
 public:
  /// Empty table of `dim`-dimensional vectors.
  explicit WordVectors(int dim = 0) : dim_(dim) {}

  /// Loads a glove_subset.bin file; throws sims::Error naming the file on any defect.
  static WordVectors Load(const std::filesystem::path& path);
  /// DataPath("language/glove_subset.bin").
  static std::filesystem::path DefaultPath();
  /// Writes the binary file atomically.
  void Save(const std::filesystem::path& path) const;

  /// Adds a word (ignored if present); `vec` must have dim() entries.
  void Add(const std::string& word, uint32_t rank, const float* vec);
  /// Sorts entries by rank so files are reproducible.
  void SortByRank();

  /// Vector dimension.
  int dim() const { return dim_; }
  /// Number of words.
  int size() const { return static_cast<int>(words_.size()); }
  /// Row index of `word`, or -1.
  int Find(const std::string& word) const;
  /// True if the word is present.
  bool Contains(const std::string& word) const { return Find(word) >= 0; }
  /// The word at row `i`.
  const std::string& Word(int i) const { return words_[static_cast<std::size_t>(i)]; }
  /// Frequency rank of row `i` in the source corpus.
  uint32_t Rank(int i) const { return ranks_[static_cast<std::size_t>(i)]; }
  /// Vector of row `i`.
  Eigen::Map<const Eigen::VectorXf> Vector(int i) const {
    return Eigen::Map<const Eigen::VectorXf>(data_.data() + static_cast<std::size_t>(i) * dim_,
                                             dim_);
  }

 private:
  int dim_;
  std::vector<std::string> words_;
  std::vector<uint32_t> ranks_;
  std::vector<float> data_;
  std::unordered_map<std::string, int> index_;
};

}  // namespace sims::language
