// volmap/benchmark_report.hpp — the self-contained HTML report (inline SVG plots, no network, no
// external assets) and the CSV summary of one or more benchmark runs (see benchmark_runner.hpp).
#pragma once

#include <string>
#include <vector>

#include <volmap/benchmark_runner.hpp>

namespace volmap {

struct MethodRun {
  std::string label;               // shown in legends: the method name (+ folder when compared)
  std::vector<CaseRecord> records;
};

// Per (group, domain) figures of one run.
struct SummaryRow {
  std::string method, group, domain;
  std::size_t cases = 0, certified = 0, timed_out = 0, crashed = 0;
  double success_rate = 0, median_time_s = 0, max_time_s = 0, median_growth = 1, max_growth = 1;
  double mean_mips3d = 0, mean_conformal = 0;  // over certified cases with metrics (0 when none)
  double mean_mips3d_all = 0, mean_conformal_all = 0;  // over every case with metrics
};
std::vector<SummaryRow> summarize(const MethodRun& run);

std::string summary_csv(const std::vector<MethodRun>& runs);
std::string render_report_html(const std::vector<MethodRun>& runs, const std::string& title);

}  // namespace volmap
