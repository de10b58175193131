// Reading a skill's snapshot values (Skill::SaveEnvState's doubles) back with every value
// checked: a snapshot comes from a checkpoint file, so an index, count or flag that is not an
// integer in range (or a NaN anywhere) is bad input, not a cast.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "sims/core/error.h"

namespace sims::task {

/// Reads doubles in order, each checked, throwing an input error that names the skill's state
/// and the field.
class StateReader {
 public:
  /// `what` names the state in errors ("sit skill state").
  StateReader(std::string what, const double* data, size_t size)
      : what_(std::move(what)), data_(data), size_(size) {}

  /// Values read so far.
  size_t used() const { return pos_; }
  /// Values not read yet.
  size_t left() const { return size_ - pos_; }

  /// The next value: any number but NaN.
  double Real(const char* field) {
    const double v = Next(field);
    if (std::isnan(v)) ThrowInputError(what_, field, "a number", "NaN");
    return v;
  }
  /// The next value: an integer in [lo, hi].
  long long Int(const char* field, long long lo, long long hi) {
    const double v = Next(field);
    if (!(v >= static_cast<double>(lo) && v <= static_cast<double>(hi)) || v != std::floor(v))
      ThrowInputError(what_, field,
                      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
                      std::to_string(v));
    return static_cast<long long>(v);
  }
  /// The next value: 0 or 1.
  bool Flag(const char* field) { return Int(field, 0, 1) != 0; }
  /// Throws unless every value was read.
  void ExpectEnd() const {
    if (pos_ != size_)
      ThrowInputError(what_, "size", std::to_string(pos_) + " values",
                      std::to_string(size_) + " values");
  }

 private:
  double Next(const char* field) {
    if (pos_ >= size_) ThrowInputError(what_, field, "a value", "the end of the snapshot");
    return data_[pos_++];
  }

  std::string what_;
  const double* data_;
  size_t size_;
  size_t pos_ = 0;
};

}  // namespace sims::task
