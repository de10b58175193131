// Style embeddings z (64-d, unit norm) per motion clip. Until text embeddings exist for a
// clip, each clip gets a fixed pseudo-random unit code derived from its name, so the same
// clip always has the same z across runs and machines.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace sims::motion {
class MotionLibrary;
}

namespace sims::task {

inline constexpr int kStyleDim = 64;  ///< SIMS §3.3.

/// z for each clip of a library, indexed like the library's clips.
class StyleTable {
 public:
  /// Per-clip codes from clip names (mirrored clips get their own code).
  static StyleTable FromClipNames(const motion::MotionLibrary& library);
  /// Explicit embeddings (e.g. from the language module); each is normalised.
  explicit StyleTable(std::vector<Eigen::VectorXf> z);
  /// Number of styles.
  int size() const { return static_cast<int>(z_.size()); }
  /// z of style i.
  const Eigen::VectorXf& z(int i) const { return z_[i]; }
  /// All embeddings.
  const std::vector<Eigen::VectorXf>& all() const { return z_; }
  /// Deterministic unit code for a string.
  static Eigen::VectorXf CodeFor(const std::string& key);

 private:
  std::vector<Eigen::VectorXf> z_;
};

}  // namespace sims::task
