// volmap-run end to end: the Tutte 3D oracle of VOLMAP's G1 log.csv, kill + resume, the Snakemake
// workflow on a tiny dataset, and the HTML report rendered by headless Chromium.
#include <doctest/doctest.h>
#include <test_support.hpp>
#include <tiny_dataset.hpp>
#include "support/benchmark_runner.hpp"
#include "support/process.hpp"

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) { return volmap_test::fresh_scratch_dir(name); }

// log.csv: "<path>/<mesh>_<dom>_tutte; #tets; #inverted; ..." -> {"mesh_dom": inverted}
std::map<std::string, long long> log_inverted(const fs::path& log) {
  std::map<std::string, long long> out;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);) {
    std::stringstream ss(line);
    std::string path, tets, inverted;
    std::getline(ss, path, ';');
    std::getline(ss, tets, ';');
    std::getline(ss, inverted, ';');
    std::string stem = path.substr(path.find_last_of('/') + 1);
    stem = stem.substr(0, stem.size() - std::string("_tutte").size());
    out[stem] = std::stoll(inverted);
  }
  return out;
}

void check_tutte_against_log(const std::string& meshes, std::size_t expected_rows) {
  VOLMAP_REQUIRE_DATA(root, "volmap/G1/log.csv");
  const auto dataset = root.parent_path().parent_path();
  const auto out = fresh_dir("run_tutte");
  std::vector<std::string> argv = {volmap_test::tool("volmap-run").string(), dataset.string(), "--groups", "G1",
                                   "--domains", "cube,tet,pyr,octa", "--method", "tutte3d", "--jobs", "2",
                                   "--out", (out / "r").string()};
  if (!meshes.empty()) argv.insert(argv.end(), {"--meshes", meshes});
  const auto run = volmap::run_process(argv, 3000, "", (out / "err").string());
  REQUIRE(run.exit_code == 0);
  const auto expected = log_inverted(root);
  const auto records = volmap::read_results((out / "r" / "results.jsonl").string());
  std::size_t compared = 0;
  for (const auto& r : records) {
    CAPTURE(r.case_id);
    CHECK_FALSE(r.certified);  // Tutte 3D: 0 % on VOLMAP
    const auto it = expected.find(r.name + "_" + r.domain);
    REQUIRE(it != expected.end());
    CHECK(r.negative + r.zero == it->second);
    ++compared;
  }
  CHECK(compared == expected_rows);
  fs::remove_all(out);
}

}  // namespace

TEST_CASE("volmap-run --method tutte3d reproduces log.csv's inverted counts (bone, duck)") {
  check_tutte_against_log("bone,duck", 8);
}

TEST_SUITE("long") {
  TEST_CASE("volmap-run --method tutte3d reproduces log.csv's inverted counts for all 80 G1 rows") {
    check_tutte_against_log("", 80);
  }
}

TEST_CASE("killing volmap-run mid-way and resuming completes every case exactly once") {
  const auto root = fresh_dir("run_kill");
  for (int i = 0; i < 6; ++i) volmap_test::write_cube_case(root / "data", "G1", "c" + std::to_string(i), "cube");
  const auto slow = root / "slow.sh";
  volmap_test::write_file(slow, "#!/bin/sh\nsleep 0.4\ncp \"$1\" \"$3\"\n", true);
  const std::string runner = volmap_test::tool("volmap-run").string();
  const std::vector<std::string> args = {runner, (root / "data").string(), "--method", slow.string(), "--jobs", "1",
                                         "--out", (root / "out").string()};
  // SIGTERM as soon as the first result is on disk (not after a fixed delay: under a sanitizer the
  // first case can take longer than any delay): the runner kills its running candidate and leaves.
  const std::string results = (root / "out" / "results.jsonl").string();
  std::vector<std::string> killed = {
      "sh", "-c",
      "r=$1; shift; \"$@\" & p=$!; i=0; while [ ! -s \"$r\" ] && [ $i -lt 1200 ]; do sleep 0.05; i=$((i+1)); done; "
      "kill -TERM $p; wait $p",
      "sh", results};
  killed.insert(killed.end(), args.begin(), args.end());
  const auto first = volmap::run_process(killed, 90);
  CHECK(first.exit_code != 0);
  const auto partial = volmap::read_results(results);
  CHECK(partial.size() >= 1);
  CHECK(partial.size() < 6);
  std::vector<std::string> resume = args;
  resume.push_back("--resume");
  const auto second = volmap::run_process(resume, 120);
  CHECK(second.exit_code == 0);
  const auto all = volmap::read_results((root / "out" / "results.jsonl").string());
  std::set<std::string> ids;
  for (const auto& r : all) {
    ids.insert(r.case_id);
    CHECK(r.certified);
  }
  CHECK(all.size() == 6);
  CHECK(ids.size() == 6);
  fs::remove_all(root);
}

TEST_CASE("the Snakemake workflow runs a tiny dataset and renders the report") {
  if (volmap::run_process({"snakemake", "--version"}, 60).exit_code != 0) {
    MESSAGE("skipped: snakemake is not installed");
    return;
  }
  const auto root = fresh_dir("snakemake");
  for (const char* n : {"a", "b"}) volmap_test::write_cube_case(root / "data", "G1", n, "cube");
  volmap_test::write_cube_case(root / "data", "G1", "a", "tet");
  const auto copy = root / "copy.sh";
  volmap_test::write_file(copy, "#!/bin/sh\ncp \"$1\" \"$3\"\n", true);
  const auto run = volmap::run_process(
      {"snakemake", "-s", (fs::path(VOLMAP_SOURCE_DIR) / "workflow" / "Snakefile").string(), "--cores", "2",
       "--directory", root.string(), "--config", "dataset=" + (root / "data").string(), "method=" + copy.string(),
       "out=" + (root / "out").string(), "bin=" + std::string(VOLMAP_BIN_DIR)},
      600, (root / "snake.out").string(), (root / "snake.err").string());
  CHECK(run.exit_code == 0);
  const auto records = volmap::read_results((root / "out" / "results.jsonl").string());
  CHECK(records.size() == 3);
  for (const auto& r : records) CHECK(r.certified);
  CHECK(fs::file_size(root / "out" / "report.html") > 1000);
  fs::remove_all(root);
}

TEST_CASE("the HTML report renders in headless Chromium (screenshot artifact)") {
  if (!fs::exists("/usr/bin/chromium")) {
    MESSAGE("skipped: /usr/bin/chromium is not installed");
    return;
  }
  const auto root = fresh_dir("report");
  volmap_test::write_cube_case(root / "data", "G1", "a", "cube");
  const auto copy = root / "copy.sh";
  volmap_test::write_file(copy, "#!/bin/sh\ncp \"$1\" \"$3\"\n", true);
  const std::string runner = volmap_test::tool("volmap-run").string();
  REQUIRE(volmap::run_process({runner, (root / "data").string(), "--method", copy.string(), "--out",
                               (root / "out").string()}, 120).exit_code == 0);
  REQUIRE(volmap::run_process({runner, "report", (root / "out").string()}, 120).exit_code == 0);
  const fs::path artifacts = fs::path(VOLMAP_BIN_DIR).parent_path() / "report-test";
  fs::create_directories(artifacts);
  const auto png = artifacts / "report.png";
  fs::remove(png);
  const auto shot = volmap::run_process(
      {"/usr/bin/chromium", "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
       "--disable-component-update", "--disable-sync", "--no-first-run", "--user-data-dir=" + (root / "chrome").string(),
       "--window-size=1200,1600", "--screenshot=" + png.string(), "file://" + (root / "out" / "report.html").string()},
      120, "", (root / "chrome.err").string());
  CHECK(shot.exit_code == 0);
  REQUIRE(fs::exists(png));
  CHECK(fs::file_size(png) > 20000);  // a rendered page with plots, not a blank image
  fs::remove_all(root);
}
