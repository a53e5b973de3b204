// The benchmark runner: case discovery in the VOLMAP layout, child processes with timeouts,
// crash/hang recording, atomic append + resume, and the self-contained report.
#include <doctest/doctest.h>
#include <test_support.hpp>
#include <tiny_dataset.hpp>
#include <volmap/benchmark_report.hpp>
#include <volmap/benchmark_runner.hpp>
#include <volmap/dataset.hpp>
#include <volmap/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/process.hpp>

#include <filesystem>
#include <fstream>
#include <csignal>
#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("volmap_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

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
  const auto check_tool = volmap_test::tool("volmap-map-check");
  if (!fs::exists(check_tool)) {
    MESSAGE("skipped: volmap-map-check is not built");
    return;
  }
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
