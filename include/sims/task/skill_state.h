// One env's skill state (the data half of a skill: the skill object is the model, shared by all
// envs) as it goes into an environment snapshot. Each skill keeps its per-env values in one struct
// with a Serialize(StateArchive*) that lists the fields once; the same function writes a snapshot
// and reads it back, so the two directions cannot drift apart. The snapshot is a flat list of
// doubles (BatchedEnv stores it per env); reading checks every value (StateReader), because a
// snapshot comes from a checkpoint file.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/core/rng.h"
#include "sims/task/state_reader.h"

namespace sims::task {

/// Writes fields to, or reads them back from, a flat snapshot (see the file comment).
class StateArchive {
 public:
  /// An archive that appends every visited field to `out`.
  explicit StateArchive(std::vector<double>* out) : out_(out) {}
  /// An archive that reads every visited field from `in` (checked).
  explicit StateArchive(StateReader* in) : in_(in) {}

  /// True when reading a snapshot back.
  bool loading() const { return in_ != nullptr; }
  /// Values left to read (0 when writing); for optional trailing fields.
  size_t left() const { return in_ ? in_->left() : 0; }

  /// Any number but NaN.
  void Real(const char* field, double* v) {
    if (in_)
      *v = in_->Real(field);
    else
      out_->push_back(*v);
  }
  /// Each coefficient as Real().
  template <class Derived>
  void Reals(const char* field, Eigen::MatrixBase<Derived>* v) {
    for (Eigen::Index k = 0; k < v->size(); ++k) Real(field, &v->derived().data()[k]);
  }
  /// An integer in [lo, hi] (checked when reading).
  template <class Integer>
  void Int(const char* field, Integer* v, long long lo, long long hi) {
    if (in_)
      *v = static_cast<Integer>(in_->Int(field, lo, hi));
    else
      out_->push_back(static_cast<double>(*v));
  }
  /// 0 or 1.
  void Flag(const char* field, bool* v) {
    if (in_)
      *v = in_->Flag(field);
    else
      out_->push_back(*v ? 1.0 : 0.0);
  }
  /// A generator's full state. A double cannot hold a 64-bit word exactly, so each of the four
  /// words is split into two 32-bit halves.
  void RngState(const char* field, Rng* rng) {
    std::array<uint64_t, 4> s = rng->state();
    for (uint64_t& w : s) {
      uint64_t hi = w >> 32, lo = w & 0xffffffffull;
      Int(field, &hi, 0, 0xffffffffll);
      Int(field, &lo, 0, 0xffffffffll);
      w = (hi << 32) | lo;
    }
    if (in_) rng->set_state(s);
  }

 private:
  std::vector<double>* out_ = nullptr;
  StateReader* in_ = nullptr;
};

}  // namespace sims::task
