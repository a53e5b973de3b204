// Regression tests, through the real executables, for the defects an outside tester found in the
// tools' handling of inputs and outputs (certificates for invalid meshes, outputs over inputs,
// devices replaced, partial outputs, temporary files left by signals, extensions ignored, option
// ranges, unbounded inputs, messages that named no file). Every case checks the exit code, that
// stderr is one line naming the file and the reason, that no output (and no temporary file) is left
// behind, and that the inputs are unchanged.
#include <doctest/doctest.h>

#include <volmap/io/io.hpp>
#include <volmap/testing/generate.hpp>

#include "tool_run.hpp"

#include <nlohmann/json.hpp>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>

namespace fs = std::filesystem;
using volmap_test::RunResult;

namespace {

// A scratch workspace: inputs in in/, outputs in out/, captures in scratch/.
struct Workspace : volmap_test::ToolTree {
  volmap_test::GridFixture grid = volmap_test::kuhn_grid_fixture(2);
  std::string mesh, map;  // good inputs: the 2x2x2 Kuhn grid and its identity boundary map

  Workspace() : ToolTree("tool_defects") {
    mesh = write("good.mesh", volmap_test::medit_text(grid.mesh));
    map = write("good_map.txt", volmap_test::identity_map_text(grid));
  }

  std::string write(const std::string& name, const std::string& text) const {
    return volmap_test::write_bytes(in / name, text);
  }
  std::string mesh_file(const std::string& name, const volmap::TetMeshData& m) const {
    return write(name, volmap_test::medit_text(m));
  }
  // Identity boundary map of any mesh (every boundary vertex at its own position).
  std::string identity_map(const std::string& name, const volmap::TetMeshData& m) const {
    return write(name, volmap_test::boundary_identity_map_text(m));
  }
  std::string o(const std::string& name) const { return (out / name).string(); }

  RunResult run(const std::string& tool, const std::vector<std::string>& args) const {
    std::vector<std::string> argv{volmap_test::tool(tool).string()};
    argv.insert(argv.end(), args.begin(), args.end());
    return volmap_test::run_tool_process(argv, scratch, 120);
  }
};

bool built(const std::string& tool) {
  if (fs::exists(volmap_test::tool(tool))) return true;
  MESSAGE("skipped: " << tool << " is not built");
  return false;
}

std::string last_line(std::string s) {
  while (!s.empty() && s.back() == '\n') s.pop_back();
  return s;
}

// A refusal: `code`, one stderr line naming every '|'-free item of `names`, no file in out/.
void check_refused(const Workspace& w, const RunResult& r, int code, const std::vector<std::string>& names) {
  const std::string err = last_line(r.err);
  CHECK_FALSE(r.signaled);
  CHECK(r.exit_code == code);
  CHECK(err.find('\n') == std::string::npos);
  for (const auto& n : names) CHECK_MESSAGE(volmap_test::names_one_of(err, n), "stderr '" << err << "' lacks " << n);
  CHECK_MESSAGE(volmap_test::listing(w.out).empty(), "left behind: " << volmap_test::listing(w.out).front());
}

// Kuhn grid meshes that volmap-tetmesh-check rejects, each with its identity map.
volmap::TetMeshData coincident_copy(const volmap::TetMeshData& g) {
  // A copy of the grid's first cube (its 6 tets) over 8 new vertices at the same 8 points.
  volmap::TetMeshData m = g;
  std::vector<std::uint32_t> copy_of(g.num_vertices(), 0xFFFFFFFFu);
  for (std::size_t k = 0; k < 24; ++k) {
    const std::uint32_t v = g.tets[k];
    if (copy_of[v] == 0xFFFFFFFFu) {
      copy_of[v] = static_cast<std::uint32_t>(m.num_vertices());
      m.xyz.insert(m.xyz.end(), &g.xyz[3 * v], &g.xyz[3 * v] + 3);
    }
    m.tets.push_back(copy_of[v]);
  }
  return m;
}
volmap::TetMeshData duplicate_tet(const volmap::TetMeshData& g) {
  volmap::TetMeshData m = g;
  m.tets.insert(m.tets.end(), g.tets.begin(), g.tets.begin() + 4);
  return m;
}
volmap::TetMeshData all_flipped(volmap::TetMeshData m) {
  for (std::size_t t = 0; t < m.num_tets(); ++t) std::swap(m.tets[4 * t], m.tets[4 * t + 1]);
  return m;
}

}  // namespace

TEST_CASE("defect 1: no certificate for a mesh volmap-tetmesh-check rejects (coincident copy, duplicate tet)") {
  Workspace w;
  struct Bad {
    std::string name;
    volmap::TetMeshData mesh;
    const char* reason;  // a word of the expected sentence
  };
  const Bad bads[] = {{"coincident_copy.mesh", coincident_copy(w.grid.mesh), "separate pieces"},
                      {"duplicate_tet.mesh", duplicate_tet(w.grid.mesh), "repeat"}};
  for (const Bad& b : bads) {
    CAPTURE(b.name);
    const std::string mesh = w.mesh_file(b.name, b.mesh);
    const std::string map = w.identity_map(b.name + ".map.txt", b.mesh);
    const std::string before = volmap_test::fingerprint(w.in);
    if (built("volmap-tetmesh-check")) CHECK(w.run("volmap-tetmesh-check", {mesh}).exit_code == 1);
    const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
        {"volmap-tutte3d", {mesh, map, w.o("t.mesh")}},
        {"volmap-map", {mesh, map, w.o("m.mesh")}},
        {"volmap-map-check", {mesh, mesh, "--absolute", "--boundary", map}},
        {"volmap-metrics", {mesh, mesh}},
        {"volmap-surface-map", {"cube", mesh, w.o("s.txt")}},
        {"volmap-surface-map-check", {mesh, map}},
    };
    for (const auto& [tool, args] : runs) {
      if (!built(tool)) continue;
      CAPTURE(tool);
      const RunResult r = w.run(tool, args);
      check_refused(w, r, 2, {b.name, "not a valid input tet mesh", b.reason});
      CHECK(r.out.find("certified injective") == std::string::npos);
    }
    CHECK(volmap_test::fingerprint(w.in) == before);
  }
}

TEST_CASE("defect 2: an output that is an input or another output is refused") {
  Workspace w;
  const std::string before = volmap_test::fingerprint(w.in);
  if (built("volmap-tutte3d")) {
    check_refused(w, w.run("volmap-tutte3d", {w.mesh, w.map, w.mesh}), 2, {"good.mesh", "same file as the input mesh"});
    // The same file under another name: a hard link and a symbolic link to the input.
    fs::create_hard_link(w.mesh, w.in / "hard.mesh");
    fs::create_symlink(w.mesh, w.in / "soft.mesh");
    const std::string linked = volmap_test::fingerprint(w.in);
    check_refused(w, w.run("volmap-tutte3d", {w.mesh, w.map, (w.in / "hard.mesh").string()}), 2, {"hard.mesh", "same file"});
    check_refused(w, w.run("volmap-tutte3d", {w.mesh, w.map, (w.in / "soft.mesh").string()}), 2, {"soft.mesh", "same file"});
    CHECK(volmap_test::fingerprint(w.in) == linked);
    fs::remove(w.in / "hard.mesh");
    fs::remove(w.in / "soft.mesh");
  }
  if (built("volmap-map")) {
    check_refused(w, w.run("volmap-map", {w.mesh, w.map, w.map}), 2, {"good_map.txt", "same file as the boundary map"});
    check_refused(w, w.run("volmap-map", {w.mesh, w.map, w.o("m.mesh"), "--refined-input", w.o("m.mesh")}), 2,
                  {"m.mesh", "same file as the output map"});
    check_refused(w, w.run("volmap-map", {w.mesh, w.map, w.o("m.mesh"), "--rationals", w.mesh}), 2,
                  {"good.mesh", "same file as the input mesh"});
  }
  if (built("volmap-surface-map")) {
    check_refused(w, w.run("volmap-surface-map", {"cube", w.mesh, w.mesh}), 2, {"good.mesh", "same file as the input mesh"});
    check_refused(w, w.run("volmap-surface-map", {"cube", w.mesh, w.o("s.txt"), "--refined", w.o("s.txt")}), 2,
                  {"s.txt", "same file as the output map"});
  }
  if (built("volmap-tetmesh-check"))
    check_refused(w, w.run("volmap-tetmesh-check", {w.mesh, "--fix", w.o("f.mesh"), "--log", w.o("f.mesh")}), 2,
                  {"f.mesh", "same file as the --fix output"});
  if (built("volmap-metrics"))
    check_refused(w, w.run("volmap-metrics", {w.mesh, w.mesh, "--csv", w.mesh}), 2, {"good.mesh", "same file as the input mesh"});
  CHECK(volmap_test::fingerprint(w.in) == before);
}

TEST_CASE("defect 3: FIFOs and devices are never replaced by an output") {
  Workspace w;
  if (!built("volmap-tutte3d") || !built("volmap-metrics")) return;
  const fs::path dev = w.root / "dev";
  fs::create_directories(dev);
  REQUIRE(mkfifo((dev / "fifo.mesh").c_str(), 0644) == 0);
  volmap_test::output_device_target(dev / "null.mesh");
  volmap_test::output_device_target(dev / "null.csv");
  const RunResult fifo = w.run("volmap-tutte3d", {w.mesh, w.map, (dev / "fifo.mesh").string()});
  check_refused(w, fifo, 2, {"fifo.mesh", "FIFO"});
  CHECK(fs::is_fifo(dev / "fifo.mesh"));
  const RunResult null = w.run("volmap-tutte3d", {w.mesh, w.map, (dev / "null.mesh").string()});
  check_refused(w, null, 2, {"null.mesh", "character device"});
  CHECK(fs::is_character_file(dev / "null.mesh"));
  check_refused(w, w.run("volmap-metrics", {w.mesh, w.mesh, "--csv", (dev / "null.csv").string()}), 2,
                {"null.csv", "character device"});
  CHECK(fs::is_character_file(dev / "null.csv"));
  CHECK(volmap_test::listing(dev) == std::vector<std::string>{"fifo.mesh", "null.csv", "null.mesh"});
}

TEST_CASE("defect 4: the outputs of a run are written together or not at all") {
  Workspace w;
  const std::string missing = (w.root / "no" / "such").string();
  const std::string through_file = w.mesh + "/x";  // a path through a regular file: never writable
  if (built("volmap-map")) {
    check_refused(w, w.run("volmap-map", {w.mesh, w.map, w.o("m.mesh"), "--rationals", through_file + ".rat"}), 2,
                  {"good.mesh/x.rat"});
    check_refused(w, w.run("volmap-map", {w.mesh, w.map, w.o("m.mesh"), "--refined-input", missing + "/r.mesh"}), 2,
                  {"no/such/r.mesh", "folder does not exist"});
  }
  if (built("volmap-surface-map"))
    check_refused(w, w.run("volmap-surface-map", {"cube", w.mesh, w.o("s.txt"), "--refined", missing + "/r.mesh"}), 2,
                  {"no/such/r.mesh"});
  if (built("volmap-metrics"))
    check_refused(w, w.run("volmap-metrics", {w.mesh, w.mesh, "--csv", w.o("ok.csv"), "--vtu", missing + "/m.vtu"}), 2,
                  {"no/such/m.vtu"});
  if (built("volmap-tetmesh-check"))
    check_refused(w, w.run("volmap-tetmesh-check", {w.mesh, "--fix", missing + "/f.mesh", "--log", w.o("ok.csv")}), 2,
                  {"no/such/f.mesh"});
  if (built("volmap-run")) {
    // report writes an HTML page and a CSV summary: both or neither.
    const fs::path results = w.root / "results";
    fs::create_directories(results);
    volmap_test::write_bytes(results / "results.jsonl",
                             "{\"case\":\"G1/a_cube\",\"group\":\"G1\",\"mesh\":\"a\",\"domain\":\"cube\",\"method\":\"m\","
                             "\"certified\":true,\"time_s\":1}\n");
    check_refused(w, w.run("volmap-run", {"report", results.string(), "-o", w.o("r.html"), "--csv", missing + "/s.csv"}), 2,
                  {"no/such/s.csv"});
  }
}

TEST_CASE("defect 5: SIGINT and SIGTERM leave no temporary file") {
  Workspace w;
  if (!built("volmap-convert")) return;
  // A mesh large enough that writing it takes a while (~10 MB of Medit text).
  const auto big = volmap::generate_kuhn_grid(24, 24, 24);
  const std::string big_mesh = w.mesh_file("big.mesh", big);
  // True once the tool has ended (peeked at, not reaped: run_tool_process waits for it).
  auto ended = [](pid_t pid) {
    siginfo_t info{};
    return waitid(P_PID, pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
  };
  auto temp_exists = [&] {
    for (const auto& name : volmap_test::listing(w.out))
      if (name.find(".tmp.") != std::string::npos) return true;
    return false;
  };
  // Even runs: the signal after a short delay (reading, validating or writing). Odd runs: as soon as
  // the temporary output exists, i.e. mid-write (the tool writes it in milliseconds, so a fixed delay
  // alone mostly arrives after the end on a fast machine).
  int interrupted_mid_write = 0;
  for (int k = 0; k < 12; ++k) {
    const int sig = k % 4 < 2 ? SIGTERM : SIGINT;
    const bool at_temp = k % 2 == 1;
    const auto r = volmap_test::run_tool_process(
        {volmap_test::tool("volmap-convert").string(), big_mesh, w.o("big" + std::to_string(k) + ".vtk")}, w.scratch, 60,
        [&](pid_t pid) {
          if (at_temp) {
            while (!temp_exists() && !ended(pid)) {
            }
          } else {
            std::this_thread::sleep_for(std::chrono::milliseconds(2 * k));
          }
          kill(pid, sig);
        });
    if (r.signaled) CHECK(r.signal == sig);  // died of the signal after cleaning up
    if (r.signaled && at_temp) ++interrupted_mid_write;
    for (const auto& name : volmap_test::listing(w.out))
      CHECK_MESSAGE(name.find(".tmp.") == std::string::npos, "temporary file left: " << name);
  }
  MESSAGE(interrupted_mid_write << " of 6 runs were interrupted while their temporary output existed");
  CHECK(interrupted_mid_write > 0);
}

TEST_CASE("defect 6: every mesh output is written in the format of its extension, or refused") {
  Workspace w;
  auto head = [](const std::string& path) { return volmap_test::read_bytes(path).substr(0, 40); };
  if (built("volmap-tutte3d")) {
    CHECK(w.run("volmap-tutte3d", {w.mesh, w.map, w.o("t.vtu")}).exit_code == 0);
    CHECK(head(w.o("t.vtu")).find("<?xml") == 0);
    CHECK(w.run("volmap-tutte3d", {w.mesh, w.map, w.o("t.vtk")}).exit_code == 0);
    CHECK(head(w.o("t.vtk")).find("# vtk DataFile") == 0);
    w.clear_out();
    check_refused(w, w.run("volmap-tutte3d", {w.mesh, w.map, w.o("t.txt")}), 2, {"t.txt", "extension"});
  }
  if (built("volmap-map")) {
    CHECK(w.run("volmap-map", {w.mesh, w.map, w.o("m.vtk")}).exit_code == 0);
    CHECK(head(w.o("m.vtk")).find("# vtk DataFile") == 0);
    fs::remove(w.o("m.vtk"));
    check_refused(w, w.run("volmap-map", {w.mesh, w.map, w.o("m.off")}), 2, {"m.off", "extension"});
  }
  if (built("volmap-tetrahedralize")) {
    const std::string off = w.write("tet.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    CHECK(w.run("volmap-tetrahedralize", {off, w.o("t.vtu")}).exit_code == 0);
    CHECK(head(w.o("t.vtu")).find("<?xml") == 0);
    fs::remove(w.o("t.vtu"));
    check_refused(w, w.run("volmap-tetrahedralize", {off, w.o("t.stl")}), 2, {"t.stl", "extension"});
  }
}

TEST_CASE("defect 7: option values out of range (NaN, negative) are usage errors") {
  Workspace w;
  const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      {"volmap-map", {w.mesh, w.map, w.o("m.mesh"), "--max-growth", "nan"}},
      {"volmap-map", {w.mesh, w.map, w.o("m.mesh"), "--time-limit", "-5"}},
      {"volmap-map", {w.mesh, w.map, w.o("m.mesh"), "--threads", "-4"}},
      {"volmap-map", {w.mesh, w.map, w.o("m.mesh"), "--tlc-share", "nan"}},
      {"volmap-surface-map-check", {w.mesh, w.map, "--tolerance", "-1"}},
      {"volmap-surface-map-check", {w.mesh, w.map, "--tolerance", "nan"}},
      {"volmap-metrics", {w.mesh, w.mesh, "--upper", "nan"}},
      {"volmap-view", {w.mesh, "-o", w.o("v.html"), "--upper", "inf"}},
      {"volmap-tetrahedralize", {w.mesh, w.o("t.mesh"), "--quality", "nan"}},
      {"volmap-tetrahedralize", {w.mesh, w.o("t.mesh"), "--max-volume", "-1"}},
      {"volmap-run", {w.in.string(), "--method", "tutte3d", "--timeout", "nan", "--out", w.o("r")}},
  };
  for (const auto& [tool, args] : runs) {
    if (!built(tool)) continue;
    CAPTURE(tool);
    CAPTURE(args[args.size() - 2] + " " + args.back());
    const RunResult r = w.run(tool, args);
    const std::string option = args[args.size() - 2] == "--out" ? "--timeout" : args[args.size() - 2];
    check_refused(w, r, 2, {"usage:", option});
  }
}

TEST_CASE("defect 8: empty meshes, garbage results and unbounded inputs are refused quickly") {
  Workspace w;
  const std::string no_tets = w.write("no_tets.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
                                                      "0 0 1 0\nTetrahedra\n0\nEnd\n");
  if (built("volmap-metrics")) check_refused(w, w.run("volmap-metrics", {no_tets, no_tets}), 2, {"no_tets.mesh", "no tets"});
  if (built("volmap-run")) {
    const fs::path results = w.root / "garbage";
    fs::create_directories(results);
    volmap_test::write_bytes(results / "results.jsonl", "{\"case\":\"G1/a_cube\",\"method\":\"m\"}\nhello world\n");
    check_refused(w, w.run("volmap-run", {"report", results.string(), "-o", w.o("r.html"), "--csv", w.o("s.csv")}), 2,
                  {"results.jsonl:2:", "not a volmap-run record"});
    CHECK(volmap_test::listing(results) == std::vector<std::string>{"results.jsonl"});
  }
  if (built("volmap-tutte3d")) {
    const RunResult r = w.run("volmap-tutte3d", {w.mesh, "/dev/zero", w.o("t.mesh")});
    check_refused(w, r, 2, {"/dev/zero", "NUL"});
    CHECK(r.seconds < 5);
    CHECK(r.peak_rss_kb < 200 * 1024);
  }
  if (built("volmap-tetmesh-check")) {  // a binary format: its text header is vetted as it arrives
    fs::create_symlink("/dev/zero", w.in / "zero.vtk");
    const RunResult r = w.run("volmap-tetmesh-check", {(w.in / "zero.vtk").string()});
    check_refused(w, r, 2, {"zero.vtk", "NUL"});
    CHECK(r.seconds < 5);
  }
}

TEST_CASE("defect 9: messages name the file and the real reason") {
  Workspace w;
  // An inverted (Gmsh-oriented) mesh: said in words, with the fix.
  const std::string gmsh = w.mesh_file("gmsh.mesh", all_flipped(w.grid.mesh));
  if (built("volmap-map"))
    check_refused(w, w.run("volmap-map", {gmsh, w.map, w.o("m.mesh")}), 2, {"gmsh.mesh", "opposite orientation convention"});
  if (built("volmap-tetmesh-check")) {
    const RunResult r = w.run("volmap-tetmesh-check", {gmsh});
    CHECK(r.exit_code == 1);
    CHECK(r.out.find("all 48 tets are in the opposite orientation convention (orient3d < 0, as Gmsh and OpenVolumeMesh "
                     "order them); --fix flips them") != std::string::npos);
  }
  // An isolated vertex (the Laplacian would be singular): exit 2 naming the vertex and the file.
  volmap::TetMeshData isolated = w.grid.mesh;
  isolated.xyz.insert(isolated.xyz.end(), {5, 5, 5});
  const std::string iso = w.mesh_file("isolated.mesh", isolated);
  if (built("volmap-tutte3d"))
    check_refused(w, w.run("volmap-tutte3d", {iso, w.map, w.o("t.mesh")}), 2, {"isolated.mesh", "vertex 27"});
  // A tet using one vertex twice: the mesh is named, not the map.
  volmap::TetMeshData twice = w.grid.mesh;
  twice.tets[1] = twice.tets[0];
  const std::string tw = w.mesh_file("twice.mesh", twice);
  if (built("volmap-map"))
    check_refused(w, w.run("volmap-map", {tw, w.map, w.o("m.mesh")}), 2, {"twice.mesh", "vertex twice"});
  // A 1e308-scale map: the map file is named, not the output.
  {
    std::string huge_map;
    std::istringstream lines(volmap_test::read_bytes(w.map));
    for (std::string l; std::getline(lines, l);) {
      std::istringstream f(l);
      long v;
      double x, y, z;
      f >> v >> x >> y >> z;
      huge_map += std::to_string(v) + " " + std::to_string(x) + "e306 " + std::to_string(y) + "e306 " + std::to_string(z) + "e306\n";
    }
    const std::string hm = w.write("huge_map.txt", huge_map);
    if (built("volmap-tutte3d"))
      check_refused(w, w.run("volmap-tutte3d", {w.mesh, hm, w.o("t.mesh")}), 2, {"huge_map.txt", "1e100"});
  }
  // volmap-view: a mesh without tets, an empty bundle.
  const std::string no_tets = w.write("no_tets.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n"
                                                      "0 1 0 0\n0 0 1 0\nTetrahedra\n0\nEnd\n");
  const std::string empty_bundle = w.write("empty.js", "");
  if (built("volmap-view")) {
    check_refused(w, w.run("volmap-view", {no_tets, "-o", w.o("v.html"), "--bundle", empty_bundle}), 2, {"empty.js", "empty"});
    const std::string bundle = w.write("bundle.js", "console.log(1);");
    check_refused(w, w.run("volmap-view", {no_tets, "-o", w.o("v.html"), "--bundle", bundle}), 2, {"no_tets.mesh", "no tets"});
  }
  // A valid tet at 1e-300 scale: the scale is named, not a self-intersection.
  const std::string tiny = w.write("tiny.off", "OFF\n4 4 0\n0 0 0\n1e-300 0 0\n0 1e-300 0\n0 0 1e-300\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  if (built("volmap-tetrahedralize"))
    check_refused(w, w.run("volmap-tetrahedralize", {tiny, w.o("t.mesh")}), 2, {"tiny.off", "rescale"});
  // Binary STL: a NaN corner, a count that disagrees with the size.
  auto stl = [](std::uint32_t count, std::size_t records, float poison) {
    std::string b(80, ' ');
    b.append(reinterpret_cast<const char*>(&count), 4);
    for (std::size_t t = 0; t < records; ++t) {
      float f[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
      if (t == 0) f[4] = poison;
      b.append(reinterpret_cast<const char*>(f), sizeof f);
      b.append(2, '\0');
    }
    return b;
  };
  const std::string nan_stl = w.write("nan.stl", stl(2, 2, std::nanf("")));
  const std::string short_stl = w.write("short.stl", stl(3, 2, 0));
  if (built("volmap-tetmesh-check")) {
    check_refused(w, w.run("volmap-tetmesh-check", {nan_stl}), 2, {"nan.stl", "non-finite"});
    check_refused(w, w.run("volmap-tetmesh-check", {short_stl}), 2, {"short.stl", "announces 3 triangles"});
  }
  // A .vtk where Medit used to be assumed: read through the format dispatcher.
  const std::string vtk = (w.in / "good.vtk").string();
  volmap::write_vtk(vtk, w.grid.mesh);
  for (const std::string tool : {"volmap-metrics", "volmap-tutte3d"}) {
    if (!built(tool)) continue;
    const RunResult r = tool == "volmap-metrics" ? w.run(tool, {vtk, vtk}) : w.run(tool, {vtk, w.map, w.o("t.mesh")});
    CHECK_MESSAGE(r.exit_code == 0, tool << ": " << r.err);
    w.clear_out();
  }
  // A UTF-8 byte-order mark is accepted (Medit, OFF, map).
  const std::string bom_mesh = w.write("bom.mesh", "\xEF\xBB\xBF" + volmap_test::read_bytes(w.mesh));
  const std::string bom_map = w.write("bom_map.txt", "\xEF\xBB\xBF" + volmap_test::read_bytes(w.map));
  const std::string bom_off = w.write("bom.off", "\xEF\xBB\xBFOFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  if (built("volmap-tutte3d")) CHECK(w.run("volmap-tutte3d", {bom_mesh, bom_map, w.o("b.mesh")}).exit_code == 0);
  fs::remove(w.o("b.mesh"));
  if (built("volmap-tetmesh-check")) CHECK(w.run("volmap-tetmesh-check", {bom_off}).exit_code == 0);
  // UTF-16 is not UTF-8: named as binary data, not as a wrong element count.
  const std::string utf16 = w.write("utf16.mesh", std::string("\xFF\xFEM\0e\0s\0h\0", 10));
  if (built("volmap-tetmesh-check")) check_refused(w, w.run("volmap-tetmesh-check", {utf16}), 2, {"utf16.mesh", "NUL"});
}

TEST_CASE("one JSON contract: \"ok\" is the verdict (exit 0) and \"exit_code\" is always there") {
  Workspace w;
  const std::string gmsh = w.mesh_file("gmsh.mesh", all_flipped(w.grid.mesh));
  const std::string off = w.write("tet.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const std::string bundle = w.write("bundle.js", "console.log(1);");
  const fs::path results = w.root / "results";
  fs::create_directories(results);
  volmap_test::write_bytes(results / "results.jsonl",
                           "{\"case\":\"G1/a_cube\",\"group\":\"G1\",\"mesh\":\"a\",\"domain\":\"cube\",\"method\":\"m\","
                           "\"certified\":true,\"time_s\":1}\n");
  struct Run {
    std::string tool;
    std::vector<std::string> args;
  };
  const std::vector<Run> runs = {
      {"volmap-convert", {w.mesh, w.o("c.vtu")}},
      {"volmap-convert", {w.mesh, w.o("c.txt")}},
      {"volmap-tetmesh-check", {w.mesh}},
      {"volmap-tetmesh-check", {gmsh}},
      {"volmap-tutte3d", {w.mesh, w.map, w.o("t.mesh")}},
      {"volmap-tutte3d", {gmsh, w.map, w.o("t2.mesh")}},
      {"volmap-map", {w.mesh, w.map, w.o("m.mesh")}},
      {"volmap-map-check", {w.mesh, w.mesh}},
      {"volmap-map-check", {gmsh, w.mesh}},
      {"volmap-metrics", {w.mesh, w.mesh}},
      {"volmap-surface-map", {"cube", w.mesh, w.o("s.txt")}},
      {"volmap-surface-map-check", {w.mesh, w.map}},
      {"volmap-surface-map-check", {w.mesh, w.map, "--domain", "tet"}},
      {"volmap-shapes", {w.o("shapes"), "--names", "ellipsoid", "--subdivisions", "1"}},
      {"volmap-shapes", {w.o("shapes2"), "--names", "nonsense"}},
      {"volmap-predicates-selftest", {}},
      {"volmap-tetrahedralize", {off, w.o("t.vtu")}},
      {"volmap-tetrahedralize", {off, w.o("t.txt")}},
      {"volmap-view", {w.mesh, "-o", w.o("v.html"), "--bundle", bundle}},
      {"volmap-view", {gmsh, "-o", w.o("v.txt"), "--bundle", (w.in / "missing.js").string()}},
      {"volmap-run", {"report", results.string(), "-o", w.o("r.html"), "--csv", w.o("s.csv")}},
      {"volmap-run", {"table", results.string(), "-o", w.o("table.txt")}},
      {"volmap-run", {"list", w.in.string()}},
      {"volmap-run", {"report", (w.root / "no_results").string(), "-o", w.o("r2.html")}},
      {"volmap-dataset", {(w.root / "no_surfaces").string(), w.o("ds"), "--group", "G9"}},
  };
  for (const Run& run : runs) {
    if (!built(run.tool)) continue;
    // --json last, and for volmap-run's subcommands also before the subcommand.
    std::vector<std::vector<std::string>> placements{run.args};
    placements.front().push_back("--json");
    if (run.tool == "volmap-run") {
      placements.push_back(run.args);
      placements.back().insert(placements.back().begin(), "--json");
    }
    for (const auto& args : placements) {
      const RunResult r = w.run(run.tool, args);
      CAPTURE(run.tool);
      CAPTURE(args.front());
      CAPTURE(r.err);
      REQUIRE_FALSE(r.signaled);
      nlohmann::json j;
      REQUIRE_NOTHROW(j = nlohmann::json::parse(r.out));
      REQUIRE(j.is_object());
      CHECK(j.at("ok") == (r.exit_code == 0));
      CHECK(j.at("exit_code") == r.exit_code);
      w.clear_out();
    }
  }
}
