// volmap-run — run a mapping method over a VOLMAP dataset folder, and report on the results.
//   volmap-run <dataset_dir> --method <tutte3d|map|tlc|executable> [--groups G1,G2] [--domains cube,tet]
//              [--meshes bone,duck] [--jobs N] [--timeout s] [--out results_dir] [--resume] [--keep-outputs] [--json]
//              [--method-args "--threads 1 --no-refine"] [--label map-fixed]
//   volmap-run report <results_dir> [--compare other_results_dir] [-o report.html] [--csv summary.csv]
//   volmap-run table <results_dir> [--compare other_results_dir] [-o table.md]
//       the per-domain Markdown table (certified / growth / time per domain) for every label in the
//       folder(s), also printed
//   volmap-run list <dataset_dir> [--groups ..] [--domains ..]          (case ids, one per line)
//   volmap-run case <dataset_dir> <case_id> --method m --out dir [--timeout s]
//       one case, recorded in <out>/records/<group>/<name>_<dom>.json (used by the Snakemake workflow)
// Results: <out>/results.jsonl, one JSON object per case (see lib benchmark_runner.hpp).
// --json (before or after a subcommand) prints one JSON object instead of text. Exit 0 means the
// runs were made and recorded (whether each case was certified is in its record), 2 bad input.
#include "support/tool_common.hpp"

#include <volmap/io/atomic_file.hpp>
#include "support/benchmark_report.hpp"
#include "support/benchmark_runner.hpp"
#include "support/dataset.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <memory>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

constexpr int kMaxJobs = 256;
std::atomic<int> g_child_pids[kMaxJobs];
std::atomic<bool> g_stop_requested{false};

// On SIGINT/SIGTERM: announce the stop, kill the running candidates' process groups, then leave.
// Results already appended stay; a case whose candidate the kill ends is not recorded (the runner
// checks the announcement first), so --resume redoes it.
extern "C" void on_interrupt(int sig) {
  g_stop_requested.store(true);
  for (auto& pid : g_child_pids) {
    const int p = pid.load();
    if (p > 0) kill(-p, SIGKILL);
  }
  volmap::remove_registered_temp_files();
  _exit(128 + sig);
}

// After run_case / run_benchmark return: when a stop was announced, the handler is ending the
// process; nothing may be written or printed meanwhile.
void wait_for_a_stop_to_end_the_process() {
  if (g_stop_requested.load())
    for (;;) ::pause();
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == ',') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else if (c != ' ') {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

std::string tools_dir() {
  std::error_code ec;
  const auto self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : self.parent_path().string();
}

// One MethodRun per label found in the results folder(s); with a second folder, labels get the
// folder's name appended so both sides stay apart.
std::vector<volmap::MethodRun> load_runs(const std::string& results_dir, const std::string& compare_dir) {
  std::vector<volmap::MethodRun> runs;
  for (const auto& dir : {results_dir, compare_dir}) {
    if (dir.empty()) continue;
    const auto file = fs::path(dir) / "results.jsonl";
    if (!fs::is_regular_file(file)) throw volmap::Error(volmap::ErrorKind::Io, file.string(), 0, "no results file");
    std::vector<volmap::MethodRun> found;
    const auto records = volmap::read_results(file.string());
    if (records.empty()) throw volmap::Error(volmap::ErrorKind::BadInput, file.string(), 0, "holds no records");
    for (auto r : records) {
      const std::string label = compare_dir.empty() ? r.label : r.label + " (" + fs::path(dir).filename().string() + ")";
      auto it = std::find_if(found.begin(), found.end(), [&](const auto& m) { return m.label == label; });
      if (it == found.end()) it = found.insert(found.end(), volmap::MethodRun{label, {}});
      it->records.push_back(std::move(r));
    }
    runs.insert(runs.end(), found.begin(), found.end());
  }
  return runs;
}

std::string format_duration(double s) {
  if (!(s >= 0) || s > 1e7) return "?";
  char buf[32];
  const int total = static_cast<int>(s + 0.5);
  if (total >= 3600) std::snprintf(buf, sizeof buf, "%dh%02dm", total / 3600, (total / 60) % 60);
  else std::snprintf(buf, sizeof buf, "%dm%02ds", total / 60, total % 60);
  return buf;
}

// Every option of the tool and its subcommands.
struct Args {
  std::string dataset, method, groups, domains, meshes, out = "volmap-results", method_args, label;
  int jobs = 1;
  double timeout = 0;
  bool resume = false, keep = false, json = false;
  std::string results_dir, compare_dir, html_path, csv_path;  // report
  std::string table_dir, table_compare, table_path;           // table
  std::string list_dataset;                                   // list
  std::string case_dataset, case_id;                          // case
};

struct Subcommands {
  CLI::App* report = nullptr;
  CLI::App* table = nullptr;
  CLI::App* list = nullptr;
  CLI::App* one = nullptr;
};

Subcommands add_options(CLI::App& app, Args& a) {
  app.add_option("dataset_dir", a.dataset, "VOLMAP layout root (G<k>/<name>.mesh, G<k>_<dom>/<name>_<dom>.txt)");
  app.add_option("--method", a.method, "tutte3d, map, tlc, or a candidate executable (<exe> in.mesh map.txt out.mesh)");
  app.add_option("--method-args", a.method_args,
                 "extra candidate arguments, split on spaces and passed after in, map, out, e.g. "
                 "--method-args=\"--threads 1 --time-limit 30 --no-refine\" (built-ins also get --json, "
                 "--refined-input and, with --timeout and no --time-limit here, --time-limit 0.8*timeout)");
  app.add_option("--label", a.label,
                 "name of this configuration in the results (default: the method name), so the same method "
                 "with other --method-args can share --out, e.g. --label map-fixed");
  app.add_option("--groups", a.groups, "comma-separated groups, e.g. G1,G2 (default: all)");
  app.add_option("--domains", a.domains, "comma-separated domains among cube,tet,pyr,octa,star,sphere,pc (default: all)");
  app.add_option("--meshes", a.meshes, "comma-separated mesh names, e.g. bone,duck (default: all)");
  app.add_option("--jobs,-j", a.jobs, "parallel cases")->check(CLI::Range(1, kMaxJobs));
  app.add_option("--timeout", a.timeout, "seconds per candidate run (0 = none)")->check(volmap_tools::finite_non_negative());
  app.add_option("--out", a.out, "results folder (results.jsonl + per-case logs)");
  app.add_flag("--resume", a.resume, "skip cases already recorded in the results folder for this label");
  app.add_flag("--keep-outputs", a.keep, "keep every written mesh (default: only logs and JSON)");
  app.add_flag("--json", a.json, "print one JSON summary object at the end");

  Subcommands sub;
  sub.report = app.add_subcommand("report", "write report.html and summary.csv from results folders");
  sub.report->add_option("results_dir", a.results_dir, "a results folder of volmap-run")->required();
  sub.report->add_option("--compare", a.compare_dir, "a second results folder shown side by side");
  sub.report->add_option("-o,--output", a.html_path, "HTML report path (default <results_dir>/report.html)");
  sub.report->add_option("--csv", a.csv_path, "CSV summary path (default <results_dir>/summary.csv)");
  sub.table = app.add_subcommand("table", "the per-domain table (Markdown) for every label in a results folder");
  sub.table->add_option("results_dir", a.table_dir, "a results folder of volmap-run")->required();
  sub.table->add_option("--compare", a.table_compare, "a second results folder, its labels shown beside");
  sub.table->add_option("-o,--output", a.table_path, "Markdown path (default <results_dir>/table.md); also printed");
  sub.list = app.add_subcommand("list", "print the case ids of a dataset folder, one per line");
  sub.list->add_option("dataset_dir", a.list_dataset, "VOLMAP layout root")->required();
  sub.list->add_option("--groups", a.groups, "comma-separated groups");
  sub.list->add_option("--domains", a.domains, "comma-separated domains");
  sub.list->add_option("--meshes", a.meshes, "comma-separated mesh names");
  sub.one = app.add_subcommand("case", "run one case and write its record as a JSON file");
  sub.one->add_option("dataset_dir", a.case_dataset, "VOLMAP layout root")->required();
  sub.one->add_option("case_id", a.case_id, "<group>/<name>_<domain>, as printed by `list`")->required();
  sub.one->add_option("--method", a.method, "tutte3d, map, tlc, or a candidate executable")->required();
  sub.one->add_option("--out", a.out, "results folder");
  sub.one->add_option("--timeout", a.timeout, "seconds for the candidate (0 = none)")->check(volmap_tools::finite_non_negative());
  sub.one->add_flag("--keep-outputs", a.keep, "keep the written meshes");
  for (auto* s : {sub.report, sub.table, sub.list, sub.one}) s->add_flag("--json", a.json, "print one JSON object instead of text");
  app.require_subcommand(0, 1);
  return sub;
}

// `table`: the per-domain Markdown table of every label, written and printed.
int run_table(Args& a) {
  if (a.table_path.empty()) a.table_path = (fs::path(a.table_dir) / "table.md").string();
  volmap_tools::RunFiles files;
  files.input((fs::path(a.table_dir) / "results.jsonl").string(), "results file");
  if (!a.table_compare.empty()) files.input((fs::path(a.table_compare) / "results.jsonl").string(), "--compare results file");
  volmap::AtomicOutput& out = files.output(a.table_path, "table");
  const auto runs = load_runs(a.table_dir, a.table_compare);
  const std::string md = volmap::mapping_table_markdown(runs);
  volmap::write_text(out, md);
  files.commit();
  if (a.json)
    return volmap_tools::print_json({{"table", fs::absolute(a.table_path).string()}, {"markdown", md}}, volmap_tools::kExitOk);
  std::cout << md << "\ntable: " << fs::absolute(a.table_path).string() << "\n";
  return volmap_tools::kExitOk;
}

// `report`: report.html and summary.csv of one results folder (and a second one beside it).
int run_report(Args& a) {
  if (a.html_path.empty()) a.html_path = (fs::path(a.results_dir) / "report.html").string();
  if (a.csv_path.empty()) a.csv_path = (fs::path(a.results_dir) / "summary.csv").string();
  volmap_tools::RunFiles files;
  files.input((fs::path(a.results_dir) / "results.jsonl").string(), "results file");
  if (!a.compare_dir.empty()) files.input((fs::path(a.compare_dir) / "results.jsonl").string(), "--compare results file");
  volmap::AtomicOutput& html = files.output(a.html_path, "HTML report");
  volmap::AtomicOutput& csv = files.output(a.csv_path, "CSV summary");
  const auto runs = load_runs(a.results_dir, a.compare_dir);
  volmap::write_text(html, volmap::render_report_html(runs, "volmap benchmark report"));
  volmap::write_text(csv, volmap::summary_csv(runs));
  files.commit();
  if (a.json)
    return volmap_tools::print_json({{"report", fs::absolute(a.html_path).string()}, {"summary", fs::absolute(a.csv_path).string()},
                                     {"runs", runs.size()}},
                                    volmap_tools::kExitOk);
  std::cout << "report: " << fs::absolute(a.html_path).string() << "\nsummary: " << fs::absolute(a.csv_path).string() << "\n";
  return volmap_tools::kExitOk;
}

// `list`: the case ids of a dataset folder.
int run_list(const Args& a) {
  nlohmann::json ids = nlohmann::json::array();
  for (const auto& c : volmap::discover_cases(a.list_dataset, split_list(a.groups), split_list(a.domains), split_list(a.meshes)))
    if (a.json) ids.push_back(c.id());
    else std::cout << c.id() << "\n";
  return a.json ? volmap_tools::print_json({{"cases", ids}}, volmap_tools::kExitOk) : volmap_tools::kExitOk;
}

// `case`: one case, its record written as <out>/records/<group>/<name>_<dom>.json.
int run_one_case(const Args& a) {
  const auto all = volmap::discover_cases(a.case_dataset);
  const auto it = std::find_if(all.begin(), all.end(), [&](const auto& c) { return c.id() == a.case_id; });
  if (it == all.end()) throw volmap::Error(volmap::ErrorKind::BadInput, a.case_dataset, 0, "no case '" + a.case_id + "'");
  volmap::RunOptions options;
  options.out_dir = a.out;
  options.tools_dir = tools_dir();
  options.timeout_s = a.timeout;
  options.keep_outputs = a.keep;
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  const auto record = volmap::run_case(*it, volmap::resolve_method(a.method, options.tools_dir), options, &g_child_pids[0]);
  wait_for_a_stop_to_end_the_process();
  const auto path = fs::path(a.out) / "records" / it->group / (it->name + "_" + it->domain + ".json");
  fs::create_directories(path.parent_path());
  volmap::write_text_atomically(path.string(), volmap::record_to_json_line(record) + "\n");
  if (a.json)
    return volmap_tools::print_json({{"case", a.case_id}, {"certified", record.certified}, {"record", path.string()}},
                                    volmap_tools::kExitOk);
  std::cout << a.case_id << ": " << (record.certified ? "certified" : "not certified") << "\n";
  return volmap_tools::kExitOk;
}

// Progress on stderr: a bar with the ETA on a terminal, else one line per finished case.
std::function<void(const volmap::RunProgress&)> progress_printer() {
  const bool tty = isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  auto first_done = std::make_shared<std::size_t>(SIZE_MAX);
  return [=](const volmap::RunProgress& p) {
    if (*first_done == SIZE_MAX) *first_done = p.done - 1;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double per_case = elapsed / double(std::max<std::size_t>(1, p.done - *first_done));
    const double eta = per_case * double(p.total - p.done);
    if (tty) {
      const int width = 30;
      const int filled = p.total ? int(width * double(p.done) / double(p.total)) : width;
      std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, '.') << "] " << p.done << "/"
                << p.total << "  failures " << p.failures << "  ETA " << format_duration(eta) << "  "
                << (p.last ? p.last->case_id : "") << "\x1b[K" << std::flush;
      if (p.done == p.total) std::cerr << "\n";
    } else if (p.last) {
      std::cerr << "[" << p.done << "/" << p.total << "] " << p.last->case_id << ": "
                << (p.last->certified ? "certified" : "NOT certified") << " (" << p.last->time_s << " s"
                << (p.last->failure.empty() ? "" : ", " + p.last->failure) << ")\n";
    }
  };
}

// The main command: every selected case of a dataset folder, appended to <out>/results.jsonl.
int run_dataset(const Args& a) {
  if (a.dataset.empty() || a.method.empty())
    throw volmap::Error(volmap::ErrorKind::BadInput, "usage: volmap-run <dataset_dir> --method <name|exe> (see --help)");
  const auto cases = volmap::discover_cases(a.dataset, split_list(a.groups), split_list(a.domains), split_list(a.meshes));
  if (cases.empty()) throw volmap::Error(volmap::ErrorKind::BadInput, a.dataset, 0, "no cases found in the VOLMAP layout");
  volmap::RunOptions options;
  options.out_dir = a.out;
  options.tools_dir = tools_dir();
  options.jobs = a.jobs;
  options.timeout_s = a.timeout;
  options.resume = a.resume;
  options.keep_outputs = a.keep;
  options.stop_requested = &g_stop_requested;
  const auto spec = volmap::resolve_method(a.method, options.tools_dir, a.label, volmap::split_arguments(a.method_args));

  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  const auto records = volmap::run_benchmark(cases, spec, options, progress_printer(), g_child_pids);
  wait_for_a_stop_to_end_the_process();
  // Totals over everything recorded for this label (including resumed cases).
  const std::string results = (fs::path(a.out) / "results.jsonl").string();
  std::size_t total = 0, certified = 0;
  for (const auto& r : volmap::read_results(results))
    if (r.label == spec.label) {
      ++total;
      certified += r.certified;
    }
  if (a.json)
    return volmap_tools::print_json({{"method", spec.name}, {"label", spec.label}, {"cases", cases.size()}, {"ran", records.size()},
                                     {"recorded", total}, {"certified", certified}, {"results", results}},
                                    volmap_tools::kExitOk);
  std::cout << spec.label << ": " << certified << "/" << total << " certified; results in " << results << "\n";
  return volmap_tools::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Run a volume-mapping method over a VOLMAP dataset folder; `report` renders results.", "volmap-run"};
  Args a;
  const Subcommands sub = add_options(app, a);
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    if (sub.table->parsed()) return run_table(a);
    if (sub.report->parsed()) return run_report(a);
    if (sub.list->parsed()) return run_list(a);
    if (sub.one->parsed()) return run_one_case(a);
    return run_dataset(a);
  }, &a.json);
}
