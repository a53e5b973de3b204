// tools/support/benchmark_runner.hpp — running a candidate mapper over VOLMAP cases and recording results.
//
// A candidate obeys the VOLMAP contract `<exe> <in.mesh> <map.txt> <out.mesh>` (built-ins add
// `--refined-input <path>`; external candidates may write a refined source to the path in the
// environment variable VOLMAP_REFINED_INPUT). For every case the runner runs the candidate with a
// timeout, then the exact check (volmap-map-check --absolute --boundary) and the metrics
// (volmap-metrics) on what the candidate wrote, as separate processes, so no candidate or checker
// failure can stop a run. Each case yields one CaseRecord, appended as one JSON line to
// <out>/results.jsonl with a single O_APPEND write: killing the runner loses at most the cases
// in flight, and `resume` skips every case already recorded for the run's label.
//
// Method arguments and labels: extra candidate arguments (MethodSpec::args, e.g. `--threads 1
// --no-refine`) are passed after in, map, out. A label (default: the method name) names one
// configuration, so the same method with other arguments can share a results folder: resume,
// the per-case folders (cases/<label>/...) and the reports are keyed by label.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "support/dataset.hpp"

namespace volmap {

struct CaseRecord {
  std::string case_id, group, name, domain, method;
  std::string label;           // the run's label (= method when the line predates labels)
  std::string method_args;     // the extra candidate arguments, space-separated ("" = none)
  int exit_code = -1;          // candidate's exit code (-1 when killed or not started)
  int term_signal = 0;         // candidate killed by this signal
  bool timed_out = false;
  std::string failure;         // short reason when the candidate did not produce a checkable map
  double time_s = 0, peak_rss_mb = 0;
  double cpu_s = -1;           // the candidate's CPU seconds (user + system; -1 = not recorded), for loaded machines
  bool certified = false;      // exact check passed on the written files
  long long tets_in = -1, tets_out = -1, positive = -1, zero = -1, negative = -1;
  double growth = 1.0;         // output tets / original input tets
  // The candidate changed the connectivity: it said so in its --json output ("refined": true), or
  // it wrote a refined source, or tets_out != tets_in. Old lines without the field: the last test.
  bool refined = false;
  std::string certified_by;    // the stage that certified, from a built-in's --json output ("" = unknown)
  // VOLMAP metrics (output-volume-weighted means over valid tets); empty when unavailable.
  std::optional<double> conformal, dirichlet, symmetric_dirichlet, arap, mips3d;
};

std::string record_to_json_line(const CaseRecord& record);  // one line, no newline
// Parses one results line; std::nullopt for a torn or foreign line.
std::optional<CaseRecord> record_from_json_line(const std::string& line);
// All records of a results file (lines cut short by a killed runner skipped). Empty when the file
// does not exist. Throws Error(BadInput) naming the file and line for any other line that is not a
// record (garbage is never read as "no results").
std::vector<CaseRecord> read_results(const std::string& results_jsonl);

struct MethodSpec {
  std::string name;                  // "tutte3d", "map", "tlc" or the executable's file name
  std::vector<std::string> command;  // argv prefix; the runner appends in, map, out, then args
  bool builtin = false;              // built-ins understand --refined-input and --json
  std::string label;                 // results key and folder name (default: name); no '/' or spaces
  std::vector<std::string> args;     // extra candidate arguments, after in, map, out
};
// "tutte3d", "map", "tlc" resolve to the tools in tools_dir; anything else must be an executable.
// `label` empty = the method name. Throws Error(BadInput) for an unusable label.
MethodSpec resolve_method(const std::string& method, const std::string& tools_dir,
                          const std::string& label = "", const std::vector<std::string>& args = {});

// "--threads 1  --no-refine" -> {"--threads", "1", "--no-refine"} (split on whitespace; no quoting).
std::vector<std::string> split_arguments(const std::string& text);

struct RunOptions {
  std::string out_dir;        // results.jsonl + cases/<group>/<name>_<dom>/...
  std::string tools_dir;      // where volmap-map-check and volmap-metrics live
  int jobs = 1;
  double timeout_s = 0;       // per candidate run; 0 = none
  bool resume = false;        // skip cases already in results.jsonl for this label
  bool keep_outputs = false;  // keep the written meshes (default: only logs and JSON stay)
  // Set by a signal handler before it kills the running candidates: once it is set no case starts,
  // and a case that ends is not recorded (the stop cut it short, not its own failure), so --resume
  // redoes it.
  const std::atomic<bool>* stop_requested = nullptr;
};

struct RunProgress {
  std::size_t done = 0, total = 0, failures = 0, skipped = 0;
  const CaseRecord* last = nullptr;
};

// Runs every case not yet recorded. `on_progress` is called (serialised) after each case.
// `child_pids` (size >= jobs, optional) receives the running children's pids for signal handlers.
// Throws Error(BadInput) when results exist for this label and resume is off.
std::vector<CaseRecord> run_benchmark(const std::vector<BenchmarkCase>& cases, const MethodSpec& method,
                                      const RunOptions& options,
                                      const std::function<void(const RunProgress&)>& on_progress = {},
                                      std::atomic<int>* child_pids = nullptr);

// One case, exposed for tests.
CaseRecord run_case(const BenchmarkCase& c, const MethodSpec& method, const RunOptions& options,
                    std::atomic<int>* child_pid = nullptr);

}  // namespace volmap
