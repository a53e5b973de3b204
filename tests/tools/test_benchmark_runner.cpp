// The benchmark runner: case discovery in the VOLMAP layout, child processes with timeouts,
// crash/hang recording, atomic append + resume, and the self-contained report.
#include <doctest/doctest.h>
#include <test_support.hpp>
#include <tiny_dataset.hpp>
#include "support/benchmark_report.hpp"
#include "support/benchmark_runner.hpp"
#include "support/dataset.hpp"
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include "support/process.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>
#include <csignal>
#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) { return volmap_test::fresh_scratch_dir(name); }

}  // namespace

// Skips the test case with a message when a tool it runs is not built.
#define REQUIRE_BUILT_TOOL(path_var, name)              \
  const auto path_var = volmap_test::tool(name);        \
  if (!fs::exists(path_var)) {                          \
    MESSAGE("skipped: " << (name) << " is not built");  \
    return;                                             \
  }

TEST_CASE("discover_cases follows the VOLMAP layout deterministically") {
  const auto root = fresh_dir("discover");
  volmap_test::write_cube_case(root, "G2", "b", "tet");
  volmap_test::write_cube_case(root, "G1", "b", "cube");
  volmap_test::write_cube_case(root, "G1", "a", "star");
  volmap_test::write_cube_case(root, "G1", "a", "cube");
  volmap_test::write_file(root / "G1" / "c.mesh", "");          // a mesh without maps: no case
  volmap_test::write_file(root / "G1_cube" / "zz_cube.txt", "");  // a map without mesh: no case
  volmap_test::write_file(root / "notes" / "x.mesh", "");         // not a group folder
  const auto all = volmap::discover_cases(root.string());
  REQUIRE(all.size() == 4);
  CHECK(all[0].id() == "G1/a_cube");
  CHECK(all[1].id() == "G1/a_star");
  CHECK(all[2].id() == "G1/b_cube");
  CHECK(all[3].id() == "G2/b_tet");
  CHECK(volmap::discover_cases(root.string(), {"G2"}).size() == 1);
  CHECK(volmap::discover_cases(root.string(), {}, {"cube"}).size() == 2);
  CHECK_THROWS_AS(volmap::discover_cases(root.string(), {}, {"hexagon"}), volmap::Error);
  CHECK_THROWS_AS(volmap::discover_cases((root / "missing").string()), volmap::Error);
  fs::remove_all(root);
}

TEST_CASE("discover_cases on the real G1 group finds its 100 cases") {
  VOLMAP_REQUIRE_DATA(root, "volmap");
  const auto cases = volmap::discover_cases(root.string(), {"G1"});
  CHECK(cases.size() == 100);
  CHECK(volmap::discover_cases(root.string(), {"G1"}, {"star"}).size() == 20);
}

TEST_CASE("run_process: exit codes, signals, timeouts, environment") {
  const auto dir = fresh_dir("process");
  auto r = volmap::run_process({"/bin/sh", "-c", "echo hi; echo $VOLMAP_X >&2; exit 3"}, 10, (dir / "o").string(),
                               (dir / "e").string(), nullptr, {"VOLMAP_X=42"});
  CHECK(r.started);
  CHECK(r.exit_code == 3);
  CHECK_FALSE(r.timed_out);
  std::string line;
  std::ifstream(dir / "e") >> line;
  CHECK(line == "42");

  r = volmap::run_process({"/bin/sh", "-c", "kill -SEGV $$"}, 10);
  CHECK(r.term_signal == SIGSEGV);

  r = volmap::run_process({"/bin/sh", "-c", "sleep 30"}, 0.3);
  CHECK(r.timed_out);
  CHECK(r.seconds < 10);

  r = volmap::run_process({(dir / "does-not-exist").string()}, 10);
  CHECK((!r.started || r.exit_code == 127));
  fs::remove_all(dir);
}

TEST_CASE("run_benchmark records crashing and hanging candidates, appends, resumes; report is self-contained") {
  REQUIRE_BUILT_TOOL(check_tool, "volmap-map-check");
  const auto root = fresh_dir("runner");
  for (const char* n : {"ok", "crash", "hang"}) volmap_test::write_cube_case(root / "data", "G1", n, "cube");
  // A candidate that copies the input (the identity map is valid for an identity boundary map),
  // crashes on "crash" and hangs on "hang".
  const auto candidate = root / "candidate.sh";
  volmap_test::write_file(candidate,
             "#!/bin/sh\ncase \"$1\" in *crash*) kill -SEGV $$;; *hang*) sleep 60;; esac\ncp \"$1\" \"$3\"\n", true);
  volmap::RunOptions options;
  options.out_dir = (root / "out").string();
  options.tools_dir = check_tool.parent_path().string();
  options.jobs = 2;
  options.timeout_s = 1.0;
  const auto cases = volmap::discover_cases((root / "data").string());
  REQUIRE(cases.size() == 3);
  const auto spec = volmap::resolve_method(candidate.string(), options.tools_dir);
  std::size_t calls = 0;
  auto records = volmap::run_benchmark(cases, spec, options, [&](const volmap::RunProgress&) { ++calls; });
  CHECK(calls == 3);
  const auto file = (root / "out" / "results.jsonl").string();
  auto stored = volmap::read_results(file);
  REQUIRE(stored.size() == 3);
  for (const auto& r : stored) {
    if (r.name == "ok") {
      CHECK(r.certified);
      CHECK(r.exit_code == 0);
      CHECK(r.negative == 0);
      CHECK(r.tets_in == 6);
    } else if (r.name == "crash") {
      CHECK_FALSE(r.certified);
      CHECK(r.term_signal == SIGSEGV);
    } else {
      CHECK_FALSE(r.certified);
      CHECK(r.timed_out);
    }
  }
  // Without --resume a second run refuses; with it nothing is redone.
  CHECK_THROWS_AS(volmap::run_benchmark(cases, spec, options), volmap::Error);
  options.resume = true;
  records = volmap::run_benchmark(cases, spec, options);
  CHECK(records.empty());
  CHECK(volmap::read_results(file).size() == 3);
  // A torn last line (runner killed mid-write) is ignored, and resume redoes only that case.
  {
    auto lines = std::vector<std::string>();
    std::ifstream in(file);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    std::ofstream outf(file, std::ios::trunc);
    outf << lines[0] << "\n" << lines[1] << "\n" << lines[2].substr(0, lines[2].size() / 2);
  }
  CHECK(volmap::read_results(file).size() == 2);
  records = volmap::run_benchmark(cases, spec, options);
  CHECK(records.size() == 1);

  volmap::MethodRun run{"candidate", volmap::read_results(file)};
  const auto rows = volmap::summarize(run);
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].cases == 3);
  CHECK(rows[0].certified == 1);
  const std::string html = volmap::render_report_html({run}, "test");
  CHECK(html.find("<svg") != std::string::npos);
  CHECK(html.find("http://") == html.find("http://www.w3.org/2000/svg"));  // only the SVG namespace
  CHECK(html.find("https://") == std::string::npos);
  CHECK(html.find("<script src") == std::string::npos);
  fs::remove_all(root);
}

TEST_CASE("a stop (volmap-run's signal handler) records no case it cut short and starts none") {
  REQUIRE_BUILT_TOOL(check_tool, "volmap-map-check");
  const auto root = fresh_dir("stop");
  for (const char* n : {"a", "b", "c"}) volmap_test::write_cube_case(root / "data", "G1", n, "cube");
  const auto candidate = root / "candidate.sh";
  volmap_test::write_file(candidate, "#!/bin/sh\nsleep 30\ncp \"$1\" \"$3\"\n", true);
  std::atomic<bool> stop{false};
  std::atomic<int> child_pids[1];
  child_pids[0] = 0;
  volmap::RunOptions options;
  options.out_dir = (root / "out").string();
  options.tools_dir = check_tool.parent_path().string();
  options.stop_requested = &stop;
  const auto cases = volmap::discover_cases((root / "data").string());
  REQUIRE(cases.size() == 3);
  // Plays the handler without ending the process: announce, then kill the running candidate. Before
  // the announcement existed, the killed case was appended as a failure ("killed by signal 9"), and
  // --resume then skipped it.
  std::thread handler([&] {
    while (child_pids[0].load() <= 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    stop.store(true);
    ::kill(-child_pids[0].load(), SIGKILL);
  });
  const auto records =
      volmap::run_benchmark(cases, volmap::resolve_method(candidate.string(), options.tools_dir), options, {}, child_pids);
  handler.join();
  CHECK(records.empty());
  CHECK(volmap::read_results((root / "out" / "results.jsonl").string()).empty());
  fs::remove_all(root);
}

TEST_CASE("method arguments reach the candidate after in map out and labels keep runs apart") {
  REQUIRE_BUILT_TOOL(check_tool, "volmap-map-check");
  const auto root = fresh_dir("labels");
  volmap_test::write_cube_case(root / "data", "G1", "a", "cube");
  volmap_test::write_cube_case(root / "data", "G1", "b", "tet");
  // Records its arguments, copies the input (a valid identity map) and, given --refine, also
  // writes the refined source the runner asked for (a copy: same tets, but a file was written).
  const auto candidate = root / "candidate.sh";
  volmap_test::write_file(candidate,
                          "#!/bin/sh\necho \"$@\" > \"$3.args\"\ncp \"$1\" \"$3\"\n"
                          "[ \"$4\" = --refine ] && cp \"$1\" \"$VOLMAP_REFINED_INPUT\"\nexit 0\n",
                          true);
  volmap::RunOptions options;
  options.out_dir = (root / "out").string();
  options.tools_dir = check_tool.parent_path().string();
  options.keep_outputs = true;
  const auto cases = volmap::discover_cases((root / "data").string());
  REQUIRE(cases.size() == 2);

  CHECK(volmap::split_arguments("  --threads 1\t--no-refine ") == std::vector<std::string>{"--threads", "1", "--no-refine"});
  CHECK(volmap::split_arguments("").empty());
  CHECK_THROWS_AS(volmap::resolve_method(candidate.string(), options.tools_dir, "a/b"), volmap::Error);
  CHECK_THROWS_AS(volmap::resolve_method(candidate.string(), options.tools_dir, ".."), volmap::Error);

  const auto plain = volmap::resolve_method(candidate.string(), options.tools_dir);
  CHECK(plain.label == "candidate.sh");
  const auto refining =
      volmap::resolve_method(candidate.string(), options.tools_dir, "refining", volmap::split_arguments("--refine  -x 7"));
  volmap::run_benchmark(cases, plain, options);
  // The same method under another label shares the folder without --resume.
  volmap::run_benchmark(cases, refining, options);
  const auto stored = volmap::read_results((root / "out" / "results.jsonl").string());
  REQUIRE(stored.size() == 4);
  std::size_t plain_count = 0, refining_count = 0;
  for (const auto& r : stored) {
    CHECK(r.method == "candidate.sh");
    CHECK(r.certified);
    CHECK(r.tets_in == r.tets_out);
    const fs::path work = root / "out" / "cases" / r.label / r.group / (r.name + "_" + r.domain);
    std::string args;
    std::getline(std::ifstream(work / "output.mesh.args"), args);
    if (r.label == "candidate.sh") {
      ++plain_count;
      CHECK(r.method_args.empty());
      CHECK_FALSE(r.refined);
    } else {
      ++refining_count;
      CHECK(r.label == "refining");
      CHECK(r.method_args == "--refine -x 7");
      CHECK(r.refined);  // it wrote a refined source, even with the same tet count
    }
    const fs::path data = root / "data";
    const std::string expected_prefix = (data / "G1" / (r.name + ".mesh")).string() + " " +
                                        (data / ("G1_" + r.domain) / (r.name + "_" + r.domain + ".txt")).string() +
                                        " " + (work / "output.mesh").string();
    CHECK(args == (r.label == "refining" ? expected_prefix + " --refine -x 7" : expected_prefix));
  }
  CHECK(plain_count == 2);
  CHECK(refining_count == 2);
  // Resume is per label: the refining label is complete, a third label is not.
  CHECK_THROWS_AS(volmap::run_benchmark(cases, refining, options), volmap::Error);
  options.resume = true;
  CHECK(volmap::run_benchmark(cases, refining, options).empty());
  const auto third = volmap::resolve_method(candidate.string(), options.tools_dir, "third");
  CHECK(volmap::run_benchmark(cases, third, options).size() == 2);

  // The runs separate by label in the report's table.
  std::vector<volmap::MethodRun> runs;
  for (const auto& r : volmap::read_results((root / "out" / "results.jsonl").string())) {
    auto it = std::find_if(runs.begin(), runs.end(), [&](const auto& m) { return m.label == r.label; });
    if (it == runs.end()) it = runs.insert(runs.end(), volmap::MethodRun{r.label, {}});
    it->records.push_back(r);
  }
  REQUIRE(runs.size() == 3);
  const std::string md = volmap::mapping_table_markdown(runs);
  CHECK(md.find("### refining - G1") != std::string::npos);
  CHECK(md.find("arguments `--refine -x 7`") != std::string::npos);
  CHECK(md.find("| G1 | all | 2/2 | 2/2 | 2/2 |") != std::string::npos);
  fs::remove_all(root);
}

TEST_CASE("built-in volmap-map gets --method-args: an unknown flag is a recorded failure") {
  REQUIRE_BUILT_TOOL(map_tool, "volmap-map");
  REQUIRE_BUILT_TOOL(check_tool, "volmap-map-check");
  const auto root = fresh_dir("builtin_args");
  volmap_test::write_cube_case(root / "data", "G1", "a", "cube");
  const auto cases = volmap::discover_cases((root / "data").string());
  volmap::RunOptions options;
  options.out_dir = (root / "out").string();
  options.tools_dir = map_tool.parent_path().string();
  REQUIRE(check_tool.parent_path() == map_tool.parent_path());  // the runner finds both there
  options.timeout_s = 60;
  const auto good = volmap::resolve_method("map", options.tools_dir, "map-fixed",
                                           volmap::split_arguments("--threads 1 --no-refine --time-limit 10"));
  const auto bad = volmap::resolve_method("map", options.tools_dir, "map-bad", {"--no-such-flag"});
  const auto ok = volmap::run_case(cases[0], good, options);
  CHECK(ok.certified);
  CHECK(ok.exit_code == 0);
  CHECK_FALSE(ok.refined);
  CHECK_FALSE(ok.certified_by.empty());  // read from volmap-map --json
  CHECK(ok.label == "map-fixed");
  const auto failed = volmap::run_case(cases[0], bad, options);
  CHECK_FALSE(failed.certified);
  CHECK(failed.exit_code == 2);
  CHECK(failed.failure.find("no output written (exit 2)") != std::string::npos);
  CHECK(failed.failure.find("no-such-flag") != std::string::npos);
  fs::remove_all(root);
}

namespace {

volmap::CaseRecord made_record(const std::string& name, const std::string& domain, bool certified, long long tets_in,
                               long long tets_out, double time_s, std::optional<double> mips3d = std::nullopt,
                               std::optional<double> conformal = std::nullopt) {
  volmap::CaseRecord r;
  r.group = "G1";
  r.name = name;
  r.domain = domain;
  r.case_id = "G1/" + name + "_" + domain;
  r.method = r.label = "map";
  r.certified = certified;
  r.exit_code = certified ? 0 : 1;
  r.tets_in = tets_in;
  r.tets_out = tets_out;
  r.growth = double(tets_out) / double(tets_in);
  r.refined = tets_out != tets_in;
  r.time_s = time_s;
  r.mips3d = mips3d;
  r.conformal = conformal;
  return r;
}

}  // namespace

TEST_CASE("mapping table counts and medians on hand-made records") {
  volmap::MethodRun run{"map", {}};
  // cube: fixed (0 %), refined +4 %, refined exactly +5 % (in budget), refined +10 %, one failure.
  run.records.push_back(made_record("a", "cube", true, 100, 100, 1.0, 3.0, 1.5));
  run.records.push_back(made_record("b", "cube", true, 100, 104, 3.0, 4.0, 2.5));
  run.records.push_back(made_record("c", "cube", true, 100, 105, 2.0));  // no metrics
  run.records.push_back(made_record("d", "cube", true, 100, 110, 5.0, 5.0, 2.0));
  run.records.push_back(made_record("e", "cube", false, 100, 100, 20.0, 100.0, 100.0));
  // star (listed first, shown after cube in VOLMAP order): one failure only.
  run.records.insert(run.records.begin(), made_record("a", "star", false, 100, 100, 7.0));
  // A line written before labels and "refined" existed: label = method, refined inferred from counts.
  const auto old = volmap::record_from_json_line(
      R"({"case":"G1/f_tet","group":"G1","mesh":"f","domain":"tet","method":"map","certified":true,)"
      R"("tets_in":200,"tets_out":230,"growth":1.15,"time_s":4.0,"mips3d":6.0,"conformal":null})");
  REQUIRE(old);
  CHECK(old->label == "map");
  CHECK(old->refined);
  CHECK(old->method_args.empty());
  run.records.push_back(*old);

  const auto rows = volmap::mapping_table(run);
  REQUIRE(rows.size() == 4);
  CHECK(rows[0].domain == "cube");
  CHECK(rows[1].domain == "tet");
  CHECK(rows[2].domain == "star");
  CHECK(rows[3].domain == "all");
  const auto& cube = rows[0];
  CHECK(cube.pairs == 5);
  CHECK(cube.certified == 4);
  CHECK(cube.certified_fixed == 1);
  CHECK(cube.certified_small_growth == 3);  // 0 %, 4 %, 5 % (not 10 %)
  // Growth over certified {0, .04, .05, .10}: median (.04 + .05) / 2, max .10.
  CHECK(cube.growth_median == doctest::Approx(0.045));
  CHECK(cube.growth_max == doctest::Approx(0.10));
  // Time over all five {1, 3, 2, 5, 20}: median 3, max 20.
  CHECK(cube.time_median_s == doctest::Approx(3.0));
  CHECK(cube.time_max_s == doctest::Approx(20.0));
  // Metrics over certified records that have them: MIPS3D {3, 4, 5}, conformal {1.5, 2.5, 2}.
  REQUIRE(cube.mean_mips3d);
  CHECK(*cube.mean_mips3d == doctest::Approx(4.0));
  CHECK(*cube.mean_conformal == doctest::Approx(2.0));
  const auto& star = rows[2];
  CHECK(star.pairs == 1);
  CHECK(star.certified == 0);
  CHECK_FALSE(star.mean_mips3d);
  CHECK(star.growth_max == 0);
  const auto& tet = rows[1];
  CHECK(tet.certified_fixed == 0);
  CHECK(tet.certified_small_growth == 0);
  CHECK(tet.growth_median == doctest::Approx(0.15));
  CHECK(*tet.mean_mips3d == doctest::Approx(6.0));
  CHECK_FALSE(tet.mean_conformal);
  const auto& all = rows[3];
  CHECK(all.pairs == 7);
  CHECK(all.certified == 5);
  CHECK(all.certified_fixed == 1);
  CHECK(all.certified_small_growth == 3);
  // Growth {0, .04, .05, .10, .15}: median .05. Time {7, 1, 3, 2, 5, 20, 4}: median 4.
  CHECK(all.growth_median == doctest::Approx(0.05));
  CHECK(all.growth_max == doctest::Approx(0.15));
  CHECK(all.time_median_s == doctest::Approx(4.0));
  CHECK(*all.mean_mips3d == doctest::Approx(4.5));

  const std::string md = volmap::mapping_table_markdown({run});
  CHECK(md.find("| cube | 5 | 4 | 1 | 3 | 4.50 % / 10.00 % | 3.00 / 20.00 | 4.000 | 2.000 |") != std::string::npos);
  CHECK(md.find("| star | 1 | 0 | 0 | 0 | - | 7.00 / 7.00 | - | - |") != std::string::npos);
  CHECK(md.find("Not certified (2):") != std::string::npos);
  CHECK(md.find("- G1/e_cube (exit 1") != std::string::npos);
  CHECK(md.find("- G1/a_star (exit 1") != std::string::npos);
  CHECK(md.find("side by side") == std::string::npos);  // one run only
}
