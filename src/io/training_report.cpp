#include "sims/io/training_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/markup.h"

namespace sims::io {

int CsvTable::Find(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return static_cast<int>(i);
  return -1;
}

namespace {

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) out.push_back(Trim(c));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

std::string Num(double v) {
  if (!std::isfinite(v)) return "–";
  char buf[32];
  const double a = std::abs(v);
  if (a != 0 && (a >= 1e6 || a < 1e-3))
    std::snprintf(buf, sizeof(buf), "%.3g", v);
  else
    std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

// "Nice" tick positions (1, 2, 5 × 10^k) covering [lo, hi].
std::vector<double> Ticks(double lo, double hi, int target = 5) {
  const double span = hi - lo;
  if (!(span > 0)) return {lo};
  const double raw = span / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * mag) {
      step = m * mag;
      break;
    }
  std::vector<double> t;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step)
    t.push_back(std::abs(v) < 1e-12 * span ? 0.0 : v);
  return t;
}

const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                          "#9467bd", "#8c564b", "#e377c2", "#17becf"};

// Indices of the points to draw: all of them, or per bucket the first, min and max.
std::vector<std::size_t> Reduce(const std::vector<double>& y, int max_points) {
  std::vector<std::size_t> idx;
  const std::size_t n = y.size();
  if (static_cast<int>(n) <= max_points) {
    for (std::size_t i = 0; i < n; ++i) idx.push_back(i);
    return idx;
  }
  const std::size_t buckets = std::max(1, max_points / 3);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t s = b * n / buckets, e = (b + 1) * n / buckets;
    std::size_t lo = s, hi = s;
    for (std::size_t i = s; i < e; ++i) {
      if (!std::isfinite(y[i])) continue;
      if (!std::isfinite(y[lo]) || y[i] < y[lo]) lo = i;
      if (!std::isfinite(y[hi]) || y[i] > y[hi]) hi = i;
    }
    idx.push_back(s);
    idx.push_back(std::min(lo, hi));
    idx.push_back(std::max(lo, hi));
  }
  idx.push_back(n - 1);
  std::sort(idx.begin(), idx.end());
  idx.erase(std::unique(idx.begin(), idx.end()), idx.end());
  return idx;
}

// One SVG plot of `cols` against x. Every series is a <polyline class='series'
// data-series='name'> (split at missing values into several polylines).
std::string Plot(const CsvTable& t, int x_col, const std::vector<int>& cols,
                 const std::string& title, double w, double h, int max_points) {
  const double left = 62, right = 12, bottom = 34;
  const double top = cols.size() > 1 ? 26 + 13 * ((cols.size() + 2) / 3) : 26;  // room for legend
  const double pw = w - left - right, ph = h - top - bottom;
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  const std::vector<double>& x = t.values[x_col];
  for (int c : cols)
    for (std::size_t i = 0; i < t.rows(); ++i) {
      const double y = t.values[c][i];
      if (!std::isfinite(y) || !std::isfinite(x[i])) continue;
      xmin = std::min(xmin, x[i]), xmax = std::max(xmax, x[i]);
      ymin = std::min(ymin, y), ymax = std::max(ymax, y);
    }
  std::ostringstream s;
  s << "<figure><svg xmlns='http://www.w3.org/2000/svg' width='" << w << "' height='" << h
    << "' viewBox='0 0 " << w << " " << h << "'>";
  s << "<text x='" << left << "' y='16' class='title'>" << EscapeMarkup(title) << "</text>";
  s << "<rect x='" << left << "' y='" << top << "' width='" << pw << "' height='" << ph
    << "' class='frame'/>";
  if (xmin > xmax) {
    s << "<text x='" << left + 10 << "' y='" << top + ph / 2 << "' class='tick'>no data yet</text>";
    // The series still exist (empty) so every column is accounted for.
    for (int c : cols)
      s << "<polyline class='series' data-series='" << EscapeMarkup(t.columns[c])
        << "' points=''/>";
  } else {
    if (xmax == xmin) xmin -= 0.5, xmax += 0.5;
    if (ymax == ymin) {
      const double pad = std::max(std::abs(ymin) * 0.05, 1e-6);
      ymin -= pad, ymax += pad;
    } else {
      const double pad = 0.04 * (ymax - ymin);
      ymin -= pad, ymax += pad;
    }
    auto X = [&](double v) { return left + (v - xmin) / (xmax - xmin) * pw; };
    auto Y = [&](double v) { return top + ph - (v - ymin) / (ymax - ymin) * ph; };
    for (double v : Ticks(ymin, ymax)) {
      s << "<line x1='" << left << "' x2='" << left + pw << "' y1='" << Y(v) << "' y2='" << Y(v)
        << "' class='grid'/><text x='" << left - 4 << "' y='" << Y(v) + 4
        << "' class='tick' text-anchor='end'>" << Num(v) << "</text>";
    }
    for (double v : Ticks(xmin, xmax)) {
      s << "<line y1='" << top << "' y2='" << top + ph << "' x1='" << X(v) << "' x2='" << X(v)
        << "' class='grid'/><text x='" << X(v) << "' y='" << top + ph + 14
        << "' class='tick' text-anchor='middle'>" << Num(v) << "</text>";
    }
    s << "<text x='" << left + pw << "' y='" << h - 4 << "' class='tick' text-anchor='end'>"
      << EscapeMarkup(t.columns[x_col]) << "</text>";
    for (std::size_t k = 0; k < cols.size(); ++k) {
      const std::vector<double>& y = t.values[cols[k]];
      const char* color = kPalette[k % std::size(kPalette)];
      std::ostringstream pts;
      pts.precision(5);
      bool any = false;
      auto flush = [&]() {
        s << "<polyline class='series' data-series='" << EscapeMarkup(t.columns[cols[k]])
          << "' stroke='" << color << "' points='" << pts.str() << "'><title>"
          << EscapeMarkup(t.columns[cols[k]]) << "</title></polyline>";
        pts.str("");
        any = false;
      };
      for (std::size_t i : Reduce(y, max_points)) {
        if (!std::isfinite(y[i]) || !std::isfinite(x[i])) {
          if (any) flush();
          continue;
        }
        pts << X(x[i]) << "," << Y(y[i]) << " ";
        any = true;
      }
      if (any) flush();
      if (cols.size() > 1) {
        const double lx = left + 150 * (k % 3), ly = 32 + 13 * (k / 3);
        s << "<line x1='" << lx << "' x2='" << lx + 14 << "' y1='" << ly - 4 << "' y2='" << ly - 4
          << "' stroke='" << color << "' stroke-width='2'/><text x='" << lx + 18 << "' y='" << ly
          << "' class='legend'>" << EscapeMarkup(t.columns[cols[k]]) << "</text>";
      }
    }
  }
  s << "</svg></figure>\n";
  return s.str();
}

}  // namespace

CsvTable ReadCsvTable(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) ThrowInputError(path.string(), "", "a training log (CSV)", "no such file");
  CsvTable t;
  std::string line;
  if (!std::getline(in, line) || Trim(line).empty())
    ThrowInputError(path.string(), "line 1", "a header row of column names", "empty file");
  t.columns = SplitCsv(Trim(line));
  t.values.resize(t.columns.size());
  int lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    if (Trim(line).empty()) continue;
    const auto cells = SplitCsv(Trim(line));
    // A crash can leave a truncated last row; anything shorter is padded with NaN.
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      double v = std::nan("");
      if (c < cells.size() && !cells[c].empty()) {
        const std::string& s = cells[c];
        char* end = nullptr;
        v = std::strtod(s.c_str(), &end);
        if (end == s.c_str() || *end != '\0')  // strtod also reads nan, -nan and inf
          ThrowInputError(path.string(),
                          "line " + std::to_string(lineno) + ", column " + t.columns[c], "a number",
                          s);
      }
      t.values[c].push_back(v);
    }
  }
  return t;
}

std::vector<ReportPlot> DefaultTrainingPlots() {
  return {
      {"Reward per step", {"total_reward", "task_reward", "style_reward"}},
      {"Episode return", {"episode_return"}},
      {"Success and falls (fraction of episodes)", {"success_rate", "fall_rate", "force_end_rate"}},
      {"Success by start (reference vs default)",
       {"success_rate_reference", "success_rate_default"}},
      {"Curriculum level (spawn distance or backplay window, 0-1)", {"curriculum_level"}},
      {"Discriminator accuracy", {"disc_acc_demo", "disc_acc_agent"}},
      {"Throughput (samples/s)", {"env_samples_per_s", "train_samples_per_s"}},
      {"PPO step size (clip fraction, KL)", {"clip_fraction", "kl"}},
      {"Learning rate", {"learning_rate"}},
      {"Episode length (steps)", {"episode_length"}},
      {"Policy losses", {"actor_loss", "bounds_loss"}},
      {"Critic loss", {"critic_loss"}},
      {"Discriminator loss and gradient penalty", {"disc_loss", "grad_penalty"}},
  };
}

std::string TrainingReportHtml(const CsvTable& t, const std::string& title,
                               const TrainingReportOptions& options) {
  int x_col = t.Find(options.x_column);
  if (x_col < 0) x_col = 0;
  std::ostringstream page;
  page << "<!doctype html>\n<html><head><meta charset='utf-8'><title>" << EscapeMarkup(title)
       << "</title>\n<style>body{font-family:sans-serif;margin:16px;color:#222}"
          "figure{display:inline-block;margin:6px}"
          "svg .frame{fill:#fbfbfb;stroke:#999}svg .grid{stroke:#e3e3e3}"
          "svg .series{fill:none;stroke-width:1.6}svg .title{font-size:13px;font-weight:bold}"
          "svg .tick,svg .legend{font-size:11px;fill:#444}"
          "table{border-collapse:collapse;font-size:13px}td,th{padding:2px 10px;"
          "border-bottom:1px solid "
          "#ddd;text-align:right}th:first-child,td:first-child{text-align:left}"
          "</style></head><body>\n<h1>"
       << EscapeMarkup(title) << "</h1>\n<p>" << t.rows() << " rows of " << t.columns.size()
       << " columns; x axis: " << EscapeMarkup(t.columns.empty() ? "" : t.columns[x_col])
       << ".</p>\n";
  if (t.columns.empty()) {
    page << "<p>Empty log.</p></body></html>\n";
    return page.str();
  }
  // Final and best values of the grouped columns.
  page << "<table><tr><th>column</th><th>last</th><th>min</th><th>max</th></tr>\n";
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    if (static_cast<int>(c) == x_col) continue;
    double last = std::nan(""), lo = std::nan(""), hi = std::nan("");
    for (double v : t.values[c]) {
      if (!std::isfinite(v)) continue;
      last = v;
      lo = std::isfinite(lo) ? std::min(lo, v) : v;
      hi = std::isfinite(hi) ? std::max(hi, v) : v;
    }
    page << "<tr><td>" << EscapeMarkup(t.columns[c]) << "</td><td>" << Num(last) << "</td><td>"
         << Num(lo) << "</td><td>" << Num(hi) << "</td></tr>\n";
  }
  page << "</table>\n<h2>Learning curves</h2>\n<section id='groups'>\n";
  for (const ReportPlot& p : options.plots) {
    std::vector<int> cols;
    for (const auto& name : p.columns)
      if (int c = t.Find(name); c >= 0 && c != x_col) cols.push_back(c);
    if (!cols.empty()) page << Plot(t, x_col, cols, p.title, 560, 280, options.max_points);
  }
  page << "</section>\n";
  if (options.all_columns) {
    page << "<h2>Every logged column</h2>\n<section id='columns'>\n";
    for (std::size_t c = 0; c < t.columns.size(); ++c)
      if (static_cast<int>(c) != x_col)
        page << Plot(t, x_col, {static_cast<int>(c)}, t.columns[c], 360, 200, options.max_points);
    page << "</section>\n";
  }
  page << "</body></html>\n";
  return page.str();
}

void WriteTrainingReport(const std::filesystem::path& csv, const std::filesystem::path& html,
                         const std::string& title, const TrainingReportOptions& options) {
  WriteFileAtomic(html, TrainingReportHtml(ReadCsvTable(csv), title, options));
}

}  // namespace sims::io
