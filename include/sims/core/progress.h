// Progress reporting for long loops: count, rate and ETA, printed at most once per interval.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace sims {

/// Prints "<label> 120/1000 (12.0%) 45.1 <unit>/s, ETA 00:19:30 <extra>" lines to the log.
class ProgressReporter {
 public:
  /// `total` may be 0 when unknown (no ETA then); `unit` names what is counted; `start` is
  /// the count already done before this process (resumed runs), excluded from the rate.
  ProgressReporter(std::string label, int64_t total, std::string unit = "it",
                   double interval_s = 2.0, int64_t start = 0);
  /// Reports that `done` units are complete; prints if the interval elapsed or on completion.
  void Update(int64_t done, const std::string& extra = {});
  /// Prints the final line (total time and mean rate).
  void Finish(const std::string& extra = {});
  /// Units per second since construction.
  double Rate() const;
  /// Seconds since construction.
  double ElapsedSeconds() const;
  /// Formats seconds as HH:MM:SS.
  static std::string FormatDuration(double seconds);

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_, unit_;
  int64_t total_;
  int64_t done_ = 0;
  int64_t start_done_ = 0;
  double interval_s_;
  Clock::time_point start_, last_print_;
  bool printed_final_ = false;
};

}  // namespace sims
