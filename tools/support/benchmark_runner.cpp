// The benchmark runner (see benchmark_runner.hpp for the contract and crash-safety argument).
#include "support/benchmark_runner.hpp"
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>
#include "support/process.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace volmap {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void put_optional(json& j, const char* key, const std::optional<double>& v) {
  j[key] = v ? json(*v) : json(nullptr);
}
std::optional<double> get_optional(const json& j, const char* key) {
  auto it = j.find(key);
  if (it == j.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// First non-empty line of a file, trimmed to 300 characters (the candidate's one-line reason).
std::string first_line(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) return line.size() > 300 ? line.substr(0, 300) : line;
  return "";
}

// Parses the single JSON object a --json tool printed; nullopt when there is none.
std::optional<json> parse_tool_json(const fs::path& stdout_file) {
  const std::string text = read_text(stdout_file);
  const auto open = text.find('{');
  const auto close = text.rfind('}');
  if (open == std::string::npos || close == std::string::npos || close < open) return std::nullopt;
  try {
    return json::parse(text.substr(open, close - open + 1));
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

// A number at a JSON path ("output", "negative"), or nullopt.
std::optional<double> number_at(const json& j, std::initializer_list<const char*> path) {
  const json* node = &j;
  for (const char* key : path) {
    if (!node->is_object()) return std::nullopt;
    auto it = node->find(key);
    if (it == node->end()) return std::nullopt;
    node = &*it;
  }
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}
long long count_at(const json& j, std::initializer_list<const char*> path) {
  const auto v = number_at(j, path);
  return v ? static_cast<long long>(*v) : -1;
}

// Weighted mean E of one energy from volmap-metrics --json: {"energies":{"mips3d":{"mean":..}}}.
std::optional<double> energy_mean(const json& metrics, const char* energy) {
  return number_at(metrics, {"energies", energy, "mean"});
}

// The key of a run in results (a MethodSpec built by hand may leave the label empty).
const std::string& run_label(const MethodSpec& method) { return method.label.empty() ? method.name : method.label; }

void append_line_atomically(const std::string& path, const std::string& line) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) throw_io(path, std::string("cannot append results: ") + std::strerror(errno));
  const std::string data = line + "\n";
  // One write() on an O_APPEND descriptor: the line lands whole at the end, or (if killed
  // mid-write) as a torn last line that readers skip.
  const ssize_t written = ::write(fd, data.data(), data.size());
  ::close(fd);
  if (written != static_cast<ssize_t>(data.size())) throw_io(path, "short write while appending results");
}

}  // namespace

std::string record_to_json_line(const CaseRecord& r) {
  json j{{"case", r.case_id}, {"group", r.group}, {"mesh", r.name}, {"domain", r.domain}, {"method", r.method},
         {"exit_code", r.exit_code}, {"signal", r.term_signal}, {"timed_out", r.timed_out}, {"failure", r.failure},
         {"time_s", r.time_s}, {"peak_rss_mb", r.peak_rss_mb}, {"cpu_s", r.cpu_s}, {"certified", r.certified},
         {"tets_in", r.tets_in}, {"tets_out", r.tets_out}, {"positive", r.positive}, {"zero", r.zero},
         {"negative", r.negative}, {"growth", r.growth}, {"label", r.label}, {"method_args", r.method_args},
         {"refined", r.refined}, {"certified_by", r.certified_by}};
  put_optional(j, "conformal", r.conformal);
  put_optional(j, "dirichlet", r.dirichlet);
  put_optional(j, "symmetric_dirichlet", r.symmetric_dirichlet);
  put_optional(j, "arap", r.arap);
  put_optional(j, "mips3d", r.mips3d);
  return j.dump();
}

std::optional<CaseRecord> record_from_json_line(const std::string& line) {
  json j;
  try {
    j = json::parse(line);
  } catch (const json::exception&) {
    return std::nullopt;
  }
  if (!j.is_object() || !j.contains("case") || !j.contains("method")) return std::nullopt;
  try {
    CaseRecord r;
    r.case_id = j.at("case").get<std::string>();
    r.group = j.value("group", "");
    r.name = j.value("mesh", "");
    r.domain = j.value("domain", "");
    r.method = j.at("method").get<std::string>();
    r.exit_code = j.value("exit_code", -1);
    r.term_signal = j.value("signal", 0);
    r.timed_out = j.value("timed_out", false);
    r.failure = j.value("failure", "");
    r.time_s = j.value("time_s", 0.0);
    r.peak_rss_mb = j.value("peak_rss_mb", 0.0);
    r.cpu_s = j.value("cpu_s", -1.0);
    r.certified = j.value("certified", false);
    r.tets_in = j.value("tets_in", -1LL);
    r.tets_out = j.value("tets_out", -1LL);
    r.positive = j.value("positive", -1LL);
    r.zero = j.value("zero", -1LL);
    r.negative = j.value("negative", -1LL);
    r.growth = j.value("growth", 1.0);
    // Fields added later: lines written before them get the defaults they would have had.
    r.label = j.value("label", r.method);
    if (r.label.empty()) r.label = r.method;
    r.method_args = j.value("method_args", "");
    r.refined = j.value("refined", r.tets_in > 0 && r.tets_out > 0 && r.tets_in != r.tets_out);
    r.certified_by = j.value("certified_by", "");
    r.conformal = get_optional(j, "conformal");
    r.dirichlet = get_optional(j, "dirichlet");
    r.symmetric_dirichlet = get_optional(j, "symmetric_dirichlet");
    r.arap = get_optional(j, "arap");
    r.mips3d = get_optional(j, "mips3d");
    return r;
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

// A line cut short by a runner killed mid-write: the start of a JSON object whose parse runs out of
// input (such lines are skipped; anything else unparsable is an error).
static bool is_torn_record(const std::string& line) {
  if (line.empty() || line.front() != '{') return false;
  try {
    (void)json::parse(line);
  } catch (const json::parse_error& e) {
    return e.byte >= line.size();  // the parser reached the end: truncated, not malformed
  }
  return false;
}

std::vector<CaseRecord> read_results(const std::string& results_jsonl) {
  std::vector<CaseRecord> records;
  std::error_code ec;
  if (!fs::exists(results_jsonl, ec)) return records;
  const std::string text = read_text_file(results_jsonl);
  std::size_t line_number = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (auto r = record_from_json_line(line)) {
      records.push_back(std::move(*r));
    } else if (!is_torn_record(line)) {
      throw Error(ErrorKind::BadInput, results_jsonl, line_number,
                  "not a volmap-run record (a JSON object with at least \"case\" and \"method\")");
    }
  }
  return records;
}

// The argv prefix of a method name (see resolve_method).
static MethodSpec resolve_method_command(const std::string& method, const std::string& tools_dir) {
  MethodSpec spec;
  const fs::path dir(tools_dir);
  spec.name = method;
  spec.builtin = true;
  if (method == "tutte3d") {
    spec.command = {(dir / "volmap-tutte3d").string()};
  } else if (method == "map") {
    spec.command = {(dir / "volmap-map").string()};
  } else if (method == "tlc") {
    spec.command = {(dir / "volmap-map").string(), "--method", "tlc"};
  } else {
    std::error_code ec;
    if (!fs::is_regular_file(method, ec) || ::access(method.c_str(), X_OK) != 0)
      throw Error(ErrorKind::BadInput, "method '" + method + "' is neither tutte3d, map, tlc nor an executable file");
    spec.name = fs::path(method).filename().string();
    spec.command = {fs::absolute(method).string()};
    spec.builtin = false;
    return spec;
  }
  std::error_code ec;
  if (!fs::is_regular_file(spec.command[0], ec))
    throw Error(ErrorKind::BadInput, "built-in method '" + method + "' needs " + spec.command[0] + " (not built?)");
  return spec;
}

std::vector<std::string> split_arguments(const std::string& text) {
  std::vector<std::string> args;
  std::istringstream in(text);
  for (std::string a; in >> a;) args.push_back(a);
  return args;
}

MethodSpec resolve_method(const std::string& method, const std::string& tools_dir, const std::string& label,
                          const std::vector<std::string>& args) {
  if (!label.empty() && (label == "." || label == ".." ||
                         label.find_first_of("/ \t\n\r") != std::string::npos))
    throw Error(ErrorKind::BadInput, "label '" + label + "' must be a plain folder name (no '/' or spaces)");
  MethodSpec spec = resolve_method_command(method, tools_dir);
  spec.label = label.empty() ? spec.name : label;
  spec.args = args;
  return spec;
}

namespace {

// The candidate's command line: <command> in map out [method args]; built-ins also get --json and
// (mappers) --refined-input, and a --time-limit of 0.8 x the runner's timeout unless the method
// arguments set their own, so they stop by themselves before the deadline, keeping their best map.
std::vector<std::string> candidate_argv(const BenchmarkCase& c, const MethodSpec& method, const RunOptions& options,
                                        const fs::path& output, const fs::path& refined) {
  std::vector<std::string> argv = method.command;
  argv.insert(argv.end(), {c.mesh_path, c.map_path, output.string()});
  argv.insert(argv.end(), method.args.begin(), method.args.end());
  const auto given = [&](const char* flag) {
    return std::find(method.args.begin(), method.args.end(), flag) != method.args.end();
  };
  if (method.builtin && !given("--json")) argv.push_back("--json");
  if (method.builtin && method.name != "tutte3d") {
    argv.insert(argv.end(), {"--refined-input", refined.string()});
    if (options.timeout_s > 0 && !given("--time-limit"))
      argv.insert(argv.end(), {"--time-limit", std::to_string(0.8 * options.timeout_s)});
  }
  return argv;
}

// Why the candidate's run gave nothing to check (empty when it wrote an output).
std::string candidate_failure(const ProcessResult& run, const RunOptions& options, const fs::path& output, const fs::path& work) {
  std::error_code ec;
  if (!run.started) return run.spawn_error;
  if (run.timed_out) return "timed out after " + std::to_string(options.timeout_s) + " s";
  if (run.term_signal != 0)
    return std::string("killed by signal ") + std::to_string(run.term_signal) + " (" + strsignal(run.term_signal) + ")";
  if (!fs::is_regular_file(output, ec)) {
    std::string failure = "no output written (exit " + std::to_string(run.exit_code) + ")";
    const std::string reason = first_line(work / "candidate.err");
    if (!reason.empty()) failure += ": " + reason;
    return failure;
  }
  return {};
}

constexpr double kCheckerTimeout = 600;

// The exact check (volmap-map-check --absolute --boundary) of what the candidate wrote, in its own
// process. Certified = the checker ran, exited 0 and says certified, with consistent counts.
void record_exact_check(CaseRecord& r, const BenchmarkCase& c, const fs::path& tools, const fs::path& source,
                        const fs::path& output, const fs::path& work, std::atomic<int>* child_pid) {
  const ProcessResult check = run_process({(tools / "volmap-map-check").string(), source.string(), output.string(),
                                           "--boundary", c.map_path, "--absolute", "--json"},
                                          kCheckerTimeout, (work / "check.json").string(), (work / "check.err").string(),
                                          child_pid);
  const auto check_json = parse_tool_json(work / "check.json");
  // volmap-map-check --json: {"certified":..,"num_tets":..,"output":{"positive","zero","negative"},..}
  bool checker_certified = false;
  if (check_json) {
    r.positive = count_at(*check_json, {"output", "positive"});
    r.zero = count_at(*check_json, {"output", "zero"});
    r.negative = count_at(*check_json, {"output", "negative"});
    r.tets_out = count_at(*check_json, {"num_tets"});
    checker_certified = check_json->value("certified", false);
  }
  r.certified = check.started && !check.timed_out && check.term_signal == 0 && check.exit_code == 0 &&
                checker_certified && r.zero == 0 && r.negative == 0 && r.positive == r.tets_out;
  if (!check.started || check.term_signal != 0 || check.timed_out || check.exit_code == 2) {
    const std::string reason = first_line(work / "check.err");
    r.failure = "check failed to run" + (reason.empty() ? std::string() : ": " + reason);
  }
}

// VOLMAP's energies (volmap-metrics, its own process); left unset when it fails.
void record_metrics(CaseRecord& r, const fs::path& tools, const fs::path& source, const fs::path& output,
                    const fs::path& work, std::atomic<int>* child_pid) {
  const ProcessResult metrics = run_process({(tools / "volmap-metrics").string(), source.string(), output.string(), "--json"},
                                            kCheckerTimeout, (work / "metrics.json").string(),
                                            (work / "metrics.err").string(), child_pid);
  if (!metrics.started || metrics.exit_code != 0) return;
  if (const auto m = parse_tool_json(work / "metrics.json")) {
    r.conformal = energy_mean(*m, "conformal");
    r.dirichlet = energy_mean(*m, "dirichlet");
    r.symmetric_dirichlet = energy_mean(*m, "symmetric_dirichlet");
    r.arap = energy_mean(*m, "arap");
    r.mips3d = energy_mean(*m, "mips3d");
    if (r.tets_out < 0) r.tets_out = count_at(*m, {"num_tets"});
  }
}

}  // namespace

CaseRecord run_case(const BenchmarkCase& c, const MethodSpec& method, const RunOptions& options,
                    std::atomic<int>* child_pid) {
  CaseRecord r;
  r.case_id = c.id();
  r.group = c.group;
  r.name = c.name;
  r.domain = c.domain;
  r.method = method.name;
  r.label = run_label(method);
  for (const auto& a : method.args) r.method_args += (r.method_args.empty() ? "" : " ") + a;
  const fs::path work = fs::path(options.out_dir) / "cases" / r.label / c.group / (c.name + "_" + c.domain);
  fs::create_directories(work);
  const fs::path output = work / "output.mesh";
  const fs::path refined = work / "input.mesh";
  fs::remove(output);
  fs::remove(refined);

  const ProcessResult run = run_process(candidate_argv(c, method, options, output, refined), options.timeout_s,
                                        (work / "candidate.out").string(), (work / "candidate.err").string(), child_pid,
                                        {"VOLMAP_REFINED_INPUT=" + refined.string()});  // for external candidates
  r.exit_code = run.started && run.term_signal == 0 && !run.timed_out ? run.exit_code : -1;
  r.term_signal = run.term_signal;
  r.timed_out = run.timed_out;
  r.time_s = run.seconds;
  r.peak_rss_mb = run.peak_rss_mb;
  r.cpu_s = run.cpu_seconds;
  r.failure = candidate_failure(run, options, output, work);
  if (!r.failure.empty()) return r;

  // The exact check and the metrics run on what the candidate wrote (against its refined source
  // when it wrote one).
  std::error_code ec;
  const bool wrote_refined = fs::is_regular_file(refined, ec);
  const fs::path source = wrote_refined ? refined : fs::path(c.mesh_path);
  // What the candidate said about itself (built-ins with --json; anything else may print nothing).
  bool said_refined = false;
  if (const auto said = parse_tool_json(work / "candidate.out"); said && said->is_object()) {
    if (auto it = said->find("refined"); it != said->end() && it->is_boolean()) said_refined = it->get<bool>();
    if (auto it = said->find("certified_by"); it != said->end() && it->is_string()) r.certified_by = it->get<std::string>();
  }
  const fs::path tools(options.tools_dir);
  record_exact_check(r, c, tools, source, output, work, child_pid);
  record_metrics(r, tools, source, output, work, child_pid);
  // Growth is measured against the original (unrefined) input's tet count.
  try {
    r.tets_in = static_cast<long long>(read_tet_mesh(c.mesh_path).num_tets());
  } catch (const Error&) {
    r.tets_in = -1;
  }
  if (r.tets_in > 0 && r.tets_out > 0) r.growth = static_cast<double>(r.tets_out) / static_cast<double>(r.tets_in);
  r.refined = said_refined || wrote_refined || (r.tets_in > 0 && r.tets_out > 0 && r.tets_out != r.tets_in);

  if (!options.keep_outputs) {
    fs::remove(output, ec);
    fs::remove(refined, ec);
  }
  return r;
}

std::vector<CaseRecord> run_benchmark(const std::vector<BenchmarkCase>& cases, const MethodSpec& method,
                                      const RunOptions& options,
                                      const std::function<void(const RunProgress&)>& on_progress,
                                      std::atomic<int>* child_pids) {
  fs::create_directories(options.out_dir);
  const std::string results = (fs::path(options.out_dir) / "results.jsonl").string();
  // A runner killed mid-write leaves a torn last line without newline: terminate it, so the next
  // record starts on a line of its own (the torn one is skipped by readers and its case redone).
  {
    std::ifstream in(results, std::ios::binary | std::ios::ate);
    if (in && in.tellg() > 0) {
      in.seekg(-1, std::ios::end);
      if (in.get() != '\n') append_line_atomically(results, "");
    }
  }
  const std::string label = run_label(method);
  std::set<std::string> done;
  for (const auto& r : read_results(results))
    if (r.label == label) done.insert(r.case_id);
  if (!done.empty() && !options.resume)
    throw Error(ErrorKind::BadInput, results, 0,
                std::to_string(done.size()) + " cases of label '" + label +
                    "' are already recorded: pass --resume to continue, use another --label or another --out");

  std::vector<const BenchmarkCase*> todo;
  for (const auto& c : cases)
    if (!done.count(c.id())) todo.push_back(&c);

  RunProgress progress;
  progress.total = cases.size();
  progress.skipped = cases.size() - todo.size();
  progress.done = progress.skipped;
  std::vector<CaseRecord> records;
  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  const int jobs = std::max(1, options.jobs);
  auto stopped = [&] { return options.stop_requested && options.stop_requested->load(); };
  auto worker = [&](int slot) {
    for (;;) {
      const std::size_t i = next++;
      if (i >= todo.size() || stopped()) return;
      CaseRecord r = run_case(*todo[i], method, options, child_pids ? &child_pids[slot] : nullptr);
      if (stopped()) return;
      std::lock_guard<std::mutex> lock(mutex);
      append_line_atomically(results, record_to_json_line(r));
      records.push_back(std::move(r));
      ++progress.done;
      if (!records.back().certified) ++progress.failures;
      progress.last = &records.back();
      if (on_progress) on_progress(progress);
    }
  };
  std::vector<std::thread> threads;
  for (int s = 0; s < jobs; ++s) threads.emplace_back(worker, s);
  for (auto& t : threads) t.join();
  return records;
}

}  // namespace volmap
