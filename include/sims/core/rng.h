// Deterministic random numbers: xoshiro256** seeded through splitmix64, with our own
// distributions so results do not depend on the standard library's implementation.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace sims {

/// A small, fast, copyable, serialisable PRNG (one per environment, EnvPool style).
class Rng {
 public:
  /// Seeds the state from one 64-bit value.
  explicit Rng(uint64_t seed = 0) { Seed(seed); }
  /// The generator of environment `env_id` for run seed `seed` (seed + env_id).
  static Rng ForEnv(uint64_t seed, int env_id) { return Rng(seed + static_cast<uint64_t>(env_id)); }

  /// Re-seeds the state.
  void Seed(uint64_t seed);
  /// Next raw 64-bit value.
  uint64_t NextU64();
  /// Uniform in [0, 1).
  double Uniform();
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Uniform integer in [0, n); n must be positive.
  int64_t UniformInt(int64_t n);
  /// Standard normal (Box–Muller, no cached spare so the state fully describes the stream).
  double Normal();
  /// Normal with mean and standard deviation.
  double Normal(double mean, double stddev) { return mean + stddev * Normal(); }
  /// True with probability p.
  bool Bernoulli(double p) { return Uniform() < p; }

  /// Full generator state (for checkpoints).
  std::array<uint64_t, 4> state() const { return s_; }
  /// Restores a state returned by state().
  void set_state(const std::array<uint64_t, 4>& s) { s_ = s; }

 private:
  std::array<uint64_t, 4> s_{};
};

}  // namespace sims
