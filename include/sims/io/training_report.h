// Training report: an HTML page of SVG line plots from a training CSV log (train_policy's
// log.csv). Grouped plots for what a researcher checks first (rewards, success and falls,
// discriminator accuracy, throughput, losses), a table of final/best values, and one small
// plot per CSV column so nothing logged is hidden. Self-contained: no scripts, no network.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sims::io {

/// A numeric CSV table (header row of names; "nan"/"inf"/empty cells are NaN).
struct CsvTable {
  std::vector<std::string> columns;         ///< Header names.
  std::vector<std::vector<double>> values;  ///< values[c][row].

  /// Rows.
  std::size_t rows() const { return values.empty() ? 0 : values[0].size(); }
  /// Index of a column, or −1.
  int Find(const std::string& name) const;
};

/// Reads a CSV log; errors name the file, the line and the column.
CsvTable ReadCsvTable(const std::filesystem::path& path);

/// One grouped plot: several columns on shared axes.
struct ReportPlot {
  std::string title;                 ///< Plot heading.
  std::vector<std::string> columns;  ///< Columns drawn (those missing from the CSV are skipped).
};

/// The grouped plots for train_policy logs: rewards, episode return, success/falls,
/// discriminator accuracy, throughput (samples/s), policy/critic/discriminator losses.
std::vector<ReportPlot> DefaultTrainingPlots();

/// Report layout.
struct TrainingReportOptions {
  std::string x_column = "iteration";                      ///< x axis (first column if absent).
  std::vector<ReportPlot> plots = DefaultTrainingPlots();  ///< Grouped plots.
  bool all_columns = true;                                 ///< Also one small plot per column.
  int max_points = 1500;  ///< Longer series are reduced (min/max per bucket keeps spikes).
};

/// The report page as HTML text.
std::string TrainingReportHtml(const CsvTable& table, const std::string& title,
                               const TrainingReportOptions& options = {});

/// Reads `csv` and writes the report to `html` atomically.
void WriteTrainingReport(const std::filesystem::path& csv, const std::filesystem::path& html,
                         const std::string& title, const TrainingReportOptions& options = {});

}  // namespace sims::io
