#include "sims/task/styles.h"

#include "sims/core/rng.h"
#include "sims/motion/motion_library.h"

namespace sims::task {

Eigen::VectorXf StyleTable::CodeFor(const std::string& key) {
  // FNV-1a of the key seeds a Gaussian vector: stable across runs, platforms and clip order.
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : key) h = (h ^ c) * 1099511628211ull;
  Rng rng(h);
  Eigen::VectorXf z(kStyleDim);
  for (int k = 0; k < kStyleDim; ++k) z[k] = static_cast<float>(rng.Normal());
  return z.normalized();
}

StyleTable::StyleTable(std::vector<Eigen::VectorXf> z) : z_(std::move(z)) {
  for (auto& v : z_) v.normalize();
}

StyleTable StyleTable::FromClipNames(const motion::MotionLibrary& library) {
  std::vector<Eigen::VectorXf> z;
  for (int i = 0; i < library.num_clips(); ++i) {
    const auto& meta = library.clip(i).meta();
    z.push_back(CodeFor(meta.name + (meta.mirrored ? "#mirror" : "")));
  }
  return StyleTable(std::move(z));
}

}  // namespace sims::task
