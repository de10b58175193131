// Error tiers (Drake style): user mistakes throw sims::Error with a message naming the
// file, field and expectation; broken invariants abort; hot-loop checks are debug-only.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace sims {

/// A caller or input mistake; what() names the file/flag, the field and what was expected.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A config value that fails validation; the loader prefixes the file and the field path.
class FieldError : public Error {
 public:
  /// `field` is relative to the struct being validated; `expected` reads "expected <expected>".
  FieldError(std::string field, std::string expected, std::string got = {});
  /// Dotted path of the offending field (e.g. "ppo.clip").
  const std::string& field() const { return field_; }
  /// What the field must be.
  const std::string& expected() const { return expected_; }
  /// What was found, if known.
  const std::string& got() const { return got_; }
  /// Returns a copy with `prefix.` prepended to the field path.
  FieldError WithPrefix(const std::string& prefix) const;

 private:
  std::string field_, expected_, got_;
};

/// Formats "<source>: field '<field>': expected <expected>[, got <got>]".
std::string FormatInputError(std::string_view source, std::string_view field,
                             std::string_view expected, std::string_view got = {});

/// Throws sims::Error formatted by FormatInputError.
[[noreturn]] void ThrowInputError(std::string_view source, std::string_view field,
                                  std::string_view expected, std::string_view got = {});

/// Throws FieldError(field, expected) when `ok` is false (use inside Validate()).
void Require(bool ok, const std::string& field, const std::string& expected);

namespace internal {
/// Prints the failed invariant with its location and aborts.
[[noreturn]] void AbortInvariant(const char* condition, const char* file, int line,
                                 const std::string& message);
}  // namespace internal

}  // namespace sims

/// Invariant check that stays on in release builds; aborts on failure (a bug, not bad input).
#define SIMS_CHECK(cond)                                                          \
  do {                                                                            \
    if (!(cond)) ::sims::internal::AbortInvariant(#cond, __FILE__, __LINE__, {}); \
  } while (0)

/// SIMS_CHECK with an explanatory message (any expression convertible to std::string).
#define SIMS_CHECK_MSG(cond, msg)                                                    \
  do {                                                                               \
    if (!(cond)) ::sims::internal::AbortInvariant(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)

#ifndef NDEBUG
/// Debug-only invariant for hot loops.
#define SIMS_DCHECK(cond) SIMS_CHECK(cond)
#else
#define SIMS_DCHECK(cond) \
  do {                    \
  } while (0)
#endif
