// tools/support/benchmark_report.hpp — the self-contained HTML report (inline SVG plots, no network, no
// external assets), the CSV summary of one or more benchmark runs (see benchmark_runner.hpp), and
// the per-domain mapping table in Markdown.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "support/benchmark_runner.hpp"

namespace volmap {

struct MethodRun {
  std::string label;               // shown in legends: the run's label (+ folder when compared)
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

// One row of the mapping table of one run and group: figures over the pairs of one domain, or of
// every domain when domain == "all". Growth is the fraction of added tets, (out - in) / in.
struct MappingTableRow {
  std::string label, group, domain;
  std::size_t pairs = 0;
  std::size_t certified = 0;               // exact check passed (refinement allowed)
  std::size_t certified_fixed = 0;         // ... without refinement (same connectivity as the input)
  std::size_t certified_small_growth = 0;  // ... with (out - in) <= 5 % of in (fixed connectivity included)
  double growth_median = 0, growth_max = 0;  // over certified pairs (0 when none)
  double time_median_s = 0, time_max_s = 0;  // over every pair
  std::optional<double> mean_mips3d, mean_conformal;  // over certified pairs with metrics
};
// Rows per group, domains in VOLMAP order (others after, by name), then one "all" row per group.
std::vector<MappingTableRow> mapping_table(const MethodRun& run);
// `growth` = (out - in) / in <= 5 %, decided on the integer tet counts (ratio when they are unknown).
bool within_growth_budget(const CaseRecord& record);

// The Markdown table (one section per run and group, the method arguments, the uncertified pairs,
// then certified counts of every run side by side per domain).
std::string mapping_table_markdown(const std::vector<MethodRun>& runs);

std::string summary_csv(const std::vector<MethodRun>& runs);
std::string render_report_html(const std::vector<MethodRun>& runs, const std::string& title);

}  // namespace volmap
