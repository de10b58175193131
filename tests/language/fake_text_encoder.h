// A data-free text encoder for tests: hashed bag of words, deterministic.
#pragma once

#include <functional>
#include <string>

#include "sims/language/text_encoder.h"
#include "sims/language/tokenizer.h"

namespace sims::language::fake {

/// Sum of fixed pseudo-random unit vectors, one per word (FNV-1a hash seeds them), normalised.
class HashTextEncoder : public TextEncoder {
 public:
  explicit HashTextEncoder(int dim = 32) : dim_(dim) {}
  int dim() const override { return dim_; }
  Eigen::VectorXf Encode(const std::string& caption) const override {
    Eigen::VectorXf acc = Eigen::VectorXf::Zero(dim_);
    for (const auto& w : ClipTokenizer::Words(caption)) {
      uint64_t h = 1469598103934665603ULL;
      for (unsigned char c : w) h = (h ^ c) * 1099511628211ULL;
      for (int i = 0; i < dim_; ++i) {
        h ^= h >> 33;
        h *= 0xff51afd7ed558ccdULL;
        h ^= h >> 33;
        acc[i] += static_cast<float>(static_cast<int64_t>(h % 2001) - 1000) / 1000.f;
      }
    }
    const float n = acc.norm();
    return n > 0 ? Eigen::VectorXf(acc / n) : acc;
  }
  std::string Describe() const override { return "test:hash" + std::to_string(dim_); }

 private:
  int dim_;
};

}  // namespace sims::language::fake
