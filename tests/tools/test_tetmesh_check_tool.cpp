// volmap-tetmesh-check end to end: exit codes (0 pass, 1 check failed / fix refused, 2 usage or bad
// input), one JSON object with --json, --fix on coherently opposite meshes (the written file passes
// all checks) and its refusal on mixed ones, and every file of negative/ rejected with the right
// failing check (never a crash).
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

struct Run {
  int code = -1;
  std::string out, err;
};

fs::path scratch() { return volmap_test::scratch_dir("tmcheck"); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Run run(const std::string& args) {
  const fs::path dir = scratch();
  const std::string cmd = volmap_test::tool("volmap-tetmesh-check").string() + " " + args + " >" +
                          (dir / "out.txt").string() + " 2>" + (dir / "err.txt").string();
  const int status = std::system(cmd.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.out = slurp(dir / "out.txt");
  r.err = slurp(dir / "err.txt");
  return r;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// Parses stdout as exactly one JSON object (one line).
Json one_object(const Run& r) {
  REQUIRE_MESSAGE(!r.out.empty(), "no stdout; stderr: " << r.err);
  CHECK(r.out.find('\n') == r.out.size() - 1);
  const Json j = Json::parse(r.out);
  REQUIRE(j.is_object());
  return j;
}

std::set<std::string> failed(const Json& checks) {
  std::set<std::string> out;
  for (auto it = checks.begin(); it != checks.end(); ++it)
    if (!it.value().at("passed").get<bool>()) out.insert(it.key());
  return out;
}

}  // namespace

TEST_CASE("usage and bad input exit 2 with a one-line reason") {
  Run r = run("");
  CHECK(r.code == 2);
  r = run("/nonexistent/x.mesh");
  CHECK(r.code == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  const fs::path dir = scratch();
  std::ofstream(dir / "garbage.mesh") << "MeshVersionFormatted 1\nDimension 3\nVertices\n2\n0 0 0 0\n";
  r = run(q(dir / "garbage.mesh"));
  CHECK(r.code == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  r = run(q(dir / "garbage.mesh") + " --json");
  CHECK(r.code == 2);
  const Json j = one_object(r);
  CHECK(j.at("ok") == false);
  std::ofstream(dir / "x.xyz") << "1 2 3\n";
  CHECK(run(q(dir / "x.xyz")).code == 2);
  CHECK(run("--help").code == 0);
}

TEST_CASE("G1 bone passes: human output and one JSON object") {
  VOLMAP_REQUIRE_DATA(bone, "volmap/G1/bone.mesh");
  Run r = run(q(bone));
  CHECK(r.code == 0);
  CHECK(r.out.find("FAILED") == std::string::npos);
  int passed_lines = 0;
  for (std::size_t at = 0; (at = r.out.find(" PASSED ", at)) != std::string::npos; ++at) ++passed_lines;
  CHECK(passed_lines == 7);
  r = run(q(bone) + " --json");
  CHECK(r.code == 0);
  const Json j = one_object(r);
  CHECK(j.at("ok") == true);
  CHECK(j.at("report").at("tets") == 8629);
  CHECK(j.at("report").at("checks").size() == 7);
  CHECK(failed(j.at("report").at("checks")).empty());
  CHECK(j.at("report").at("orientation").at("positive") == 8629);
  // --fix on a mesh already in the VOLMAP convention writes it unchanged (here as .vtu) and passes.
  const fs::path out = scratch() / "bone_fixed.vtu";
  fs::remove(out);
  r = run(q(bone) + " --json --fix " + q(out));
  CHECK(r.code == 0);
  CHECK(one_object(r).at("fix").at("flipped_tets") == 0);
  CHECK(fs::exists(out));
  CHECK(run(q(out)).code == 0);
  // --log: VOLMAP's CSV line, appended (reference: `bone.mesh; 1; 1; 1; 1; 1; 1; 1`).
  const fs::path log = scratch() / "log.csv";
  fs::remove(log);
  CHECK(run(q(bone) + " --log " + q(log)).code == 0);
  CHECK(run(q(bone) + " --log " + q(log)).code == 0);
  CHECK(slurp(log) == "bone.mesh; 1; 1; 1; 1; 1; 1; 1\nbone.mesh; 1; 1; 1; 1; 1; 1; 1\n");
  // An output folder that does not exist: bad input (2), nothing written.
  CHECK(run(q(bone) + " --fix /nonexistent/dir/x.mesh").code == 2);
}

TEST_CASE("--fix repairs coherently opposite meshes and refuses mixed ones") {
  VOLMAP_REQUIRE_DATA(dir, "volmap/viewer-samples");
  const fs::path out = scratch();
  for (const char* name : {"hand_aigerman", "max"}) {
    INFO(name);
    const fs::path in = dir / (std::string(name) + ".mesh"), fixed = out / (std::string(name) + "_fixed.mesh");
    fs::remove(fixed);
    Run r = run(q(in));
    CHECK(r.code == 1);
    r = run(q(in) + " --json --fix " + q(fixed));
    CHECK(r.code == 0);
    const Json j = one_object(r);
    CHECK(j.at("report").at("orientation").at("class") == "coherently_opposite");
    CHECK(failed(j.at("report").at("checks")) == std::set<std::string>{"orientation"});
    CHECK(j.at("fix").at("written") == true);
    CHECK(j.at("fix").at("flipped_tets") == j.at("report").at("tets"));
    REQUIRE(fs::exists(fixed));
    r = run(q(fixed));  // the written file passes on its own
    CHECK(r.code == 0);
  }
  for (const char* name : {"hand_pc_aigerman", "max_pc"}) {
    INFO(name);
    const fs::path in = dir / (std::string(name) + ".mesh"), fixed = out / (std::string(name) + "_fixed.mesh");
    fs::remove(fixed);
    const Run r = run(q(in) + " --json --fix " + q(fixed));
    CHECK(r.code == 1);
    const Json j = one_object(r);
    CHECK(j.at("report").at("orientation").at("class") == "mixed");
    CHECK(j.at("fix").at("written") == false);
    CHECK_FALSE(fs::exists(fixed));
  }
}

TEST_CASE("every file in negative/ is rejected with the right failing check") {
  VOLMAP_REQUIRE_DATA(dir, "negative");
  struct Expect {
    const char* file;
    std::set<std::string> must_fail;  // at least these checks fail
    bool exact;                       // and only these
  };
  const Expect expected[] = {
      {"cgal_bull.off", {"self_intersections"}, true},
      {"cgal_elephant-with-holes.off", {"closed", "genus", "self_intersections"}, true},
      {"cinolib_torus.obj", {"genus"}, true},
      {"cinolib_two_spheres.obj", {"components", "self_intersections"}, true},
      {"common3d_cow.obj", {"genus", "manifold", "self_intersections"}, true},
      {"common3d_rocker-arm.obj", {"genus"}, true},
      {"libigl_3holes.off", {"genus"}, true},
      {"libigl_cow.off", {"self_intersections"}, true},
      {"libigl_fertility.off", {"genus"}, true},
      {"robustpolycube_NY_2.mesh", {"orientation", "genus"}, true},
  };
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
  CHECK(files == std::size(expected));
  for (const Expect& e : expected) {
    INFO(e.file);
    const Run r = run(q(dir / e.file) + " --json");
    CHECK((r.code == 1 || r.code == 2));
    if (r.code != 1) continue;
    const Json j = one_object(r);
    const Json& checks = j.contains("report") ? j.at("report").at("checks") : j.at("checks");
    const auto f = failed(checks);
    for (const auto& key : e.must_fail) CHECK_MESSAGE(f.count(key) == 1, key << " should fail");
    if (e.exact) CHECK(f == e.must_fail);
  }
}
