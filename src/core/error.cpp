#include "sims/core/error.h"

#include <cstdio>
#include <cstdlib>

namespace sims {

namespace {
std::string JoinFieldMessage(const std::string& field, const std::string& expected,
                             const std::string& got) {
  std::string s = "field '" + field + "': expected " + expected;
  if (!got.empty()) s += ", got " + got;
  return s;
}
}  // namespace

FieldError::FieldError(std::string field, std::string expected, std::string got)
    : Error(JoinFieldMessage(field, expected, got)),
      field_(std::move(field)),
      expected_(std::move(expected)),
      got_(std::move(got)) {}

FieldError FieldError::WithPrefix(const std::string& prefix) const {
  if (prefix.empty()) return *this;
  std::string joined = field_.empty()     ? prefix
                       : field_[0] == '[' ? prefix + field_
                                          : prefix + "." + field_;
  return FieldError(joined, expected_, got_);
}

std::string FormatInputError(std::string_view source, std::string_view field,
                             std::string_view expected, std::string_view got) {
  std::string s(source);
  if (!field.empty()) {
    s += ": field '";
    s += field;
    s += "'";
  }
  s += ": expected ";
  s += expected;
  if (!got.empty()) {
    s += ", got ";
    s += got;
  }
  return s;
}

void ThrowInputError(std::string_view source, std::string_view field, std::string_view expected,
                     std::string_view got) {
  throw Error(FormatInputError(source, field, expected, got));
}

void Require(bool ok, const std::string& field, const std::string& expected) {
  if (!ok) throw FieldError(field, expected);
}

namespace internal {
void AbortInvariant(const char* condition, const char* file, int line, const std::string& message) {
  std::fprintf(stderr, "SIMS invariant violated at %s:%d: %s%s%s\n", file, line, condition,
               message.empty() ? "" : " -- ", message.c_str());
  std::fflush(stderr);
  std::abort();
}
}  // namespace internal

}  // namespace sims
