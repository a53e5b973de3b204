// volmap/benchmark_runner.hpp — running a candidate mapper over VOLMAP cases and recording results.
//
// A candidate obeys the VOLMAP contract `<exe> <in.mesh> <map.txt> <out.mesh>` (built-ins add
// `--refined-input <path>`; external candidates may write a refined source to the path in the
// environment variable VOLMAP_REFINED_INPUT). For every case the runner runs the candidate with a
// timeout, then the exact check (volmap-map-check --absolute --boundary) and the metrics
// (volmap-metrics) on what the candidate wrote, as separate processes, so no candidate or checker
// failure can stop a run. Each case yields one CaseRecord, appended as one JSON line to
// <out>/results.jsonl with a single O_APPEND write: killing the runner loses at most the cases
// in flight, and `resume` skips every case already recorded for the method.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <volmap/dataset.hpp>

namespace volmap {

struct CaseRecord {
  std::string case_id, group, name, domain, method;
  int exit_code = -1;          // candidate's exit code (-1 when killed or not started)
  int term_signal = 0;         // candidate killed by this signal
  bool timed_out = false;
  std::string failure;         // short reason when the candidate did not produce a checkable map
  double time_s = 0, peak_rss_mb = 0;
  bool certified = false;      // exact check passed on the written files
  long long tets_in = -1, tets_out = -1, positive = -1, zero = -1, negative = -1;
  double growth = 1.0;         // output tets / original input tets
  // VOLMAP metrics (output-volume-weighted means over valid tets); empty when unavailable.
  std::optional<double> conformal, dirichlet, symmetric_dirichlet, arap, mips3d;
};

std::string record_to_json_line(const CaseRecord& record);  // one line, no newline
// Parses one results line; std::nullopt for a torn or foreign line.
std::optional<CaseRecord> record_from_json_line(const std::string& line);
// All records of a results file (torn lines skipped). Empty when the file does not exist.
std::vector<CaseRecord> read_results(const std::string& results_jsonl);

struct MethodSpec {
  std::string name;                  // "tutte3d", "map", "tlc" or the executable's file name
  std::vector<std::string> command;  // argv prefix; the runner appends in, map, out
  bool builtin = false;              // built-ins understand --refined-input
};
// "tutte3d", "map", "tlc" resolve to the tools in tools_dir; anything else must be an executable.
MethodSpec resolve_method(const std::string& method, const std::string& tools_dir);

struct RunOptions {
  std::string out_dir;        // results.jsonl + cases/<group>/<name>_<dom>/...
  std::string tools_dir;      // where volmap-map-check and volmap-metrics live
  int jobs = 1;
  double timeout_s = 0;       // per candidate run; 0 = none
  bool resume = false;        // skip cases already in results.jsonl for this method
  bool keep_outputs = false;  // keep the written meshes (default: only logs and JSON stay)
};

struct RunProgress {
  std::size_t done = 0, total = 0, failures = 0, skipped = 0;
  const CaseRecord* last = nullptr;
};

// Runs every case not yet recorded. `on_progress` is called (serialised) after each case.
// `child_pids` (size >= jobs, optional) receives the running children's pids for signal handlers.
// Throws Error(BadInput) when results exist for this method and resume is off.
std::vector<CaseRecord> run_benchmark(const std::vector<BenchmarkCase>& cases, const MethodSpec& method,
                                      const RunOptions& options,
                                      const std::function<void(const RunProgress&)>& on_progress = {},
                                      std::atomic<int>* child_pids = nullptr);

// One case, exposed for tests.
CaseRecord run_case(const BenchmarkCase& c, const MethodSpec& method, const RunOptions& options,
                    std::atomic<int>* child_pid = nullptr);

}  // namespace volmap
