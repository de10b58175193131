#include "sims/core/progress.h"

#include <cstdio>

#include "sims/core/log.h"

namespace sims {

ProgressReporter::ProgressReporter(std::string label, int64_t total, std::string unit,
                                   double interval_s, int64_t start)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      done_(start),
      start_done_(start),
      interval_s_(interval_s),
      start_(Clock::now()),
      last_print_(start_) {}

double ProgressReporter::ElapsedSeconds() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

double ProgressReporter::Rate() const {
  const double t = ElapsedSeconds();
  return t > 0 ? static_cast<double>(done_ - start_done_) / t : 0.0;
}

std::string ProgressReporter::FormatDuration(double seconds) {
  if (!(seconds >= 0) || seconds > 1e8) return "--:--:--";
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%02ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

void ProgressReporter::Update(int64_t done, const std::string& extra) {
  done_ = done;
  const auto now = Clock::now();
  const bool complete = total_ > 0 && done >= total_;
  if (!complete && std::chrono::duration<double>(now - last_print_).count() < interval_s_) return;
  last_print_ = now;
  const double rate = Rate();
  std::string line = label_ + " " + std::to_string(done);
  if (total_ > 0) {
    char pct[32];
    std::snprintf(pct, sizeof(pct), "/%lld (%.1f%%)", static_cast<long long>(total_),
                  100.0 * static_cast<double>(done) / static_cast<double>(total_));
    line += pct;
  }
  char r[64];
  std::snprintf(r, sizeof(r), " %.1f %s/s", rate, unit_.c_str());
  line += r;
  if (total_ > 0 && rate > 0)
    line += ", ETA " + FormatDuration(static_cast<double>(total_ - done) / rate);
  if (!extra.empty()) line += "  " + extra;
  spdlog::info("{}", line);
}

void ProgressReporter::Finish(const std::string& extra) {
  if (printed_final_) return;
  printed_final_ = true;
  char r[96];
  std::snprintf(r, sizeof(r), " done: %lld %s in %s (%.1f %s/s)", static_cast<long long>(done_),
                unit_.c_str(), FormatDuration(ElapsedSeconds()).c_str(), Rate(), unit_.c_str());
  spdlog::info("{}{}{}", label_, r, extra.empty() ? "" : "  " + extra);
}

}  // namespace sims
