// Bad-input corpus: every volmap-* tool run on broken inputs generated here (truncated files, wrong
// counts, out-of-range / negative / zero ids, NaN / Inf / overflowing numbers, mismatched mesh/map
// pairs, empty files, directories given as files, missing files, huge declared counts in tiny files,
// output paths in missing folders) and on ../shared/data/negative (skipped when absent).
// Expected of every run: exit 2 (or 1 where a check legitimately fails), never a signal or an
// abort; exactly one line on stderr that names the offending file (with ":<line>:" where the case
// is about a line); no output file left behind, no ".tmp." file anywhere; a small peak memory
// (giant allocations before validation are caught: RLIMIT_AS in normal builds, ASan's
// max_allocation_size_mb in sanitizer builds, plus peak RSS from wait4).
// A control run per tool on good inputs must succeed (it proves the argument shapes are right).
// Tools that are not built (e.g. volmap-view on a branch without it) are skipped with a message.
#include <doctest/doctest.h>

#include "tool_run.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

using volmap_test::listing;
using volmap_test::names_one_of;
using volmap_test::RunResult;

void spit(const fs::path& p, const std::string& text) { volmap_test::write_bytes(p, text); }

RunResult run(const std::vector<std::string>& argv, const fs::path& scratch) {
  return volmap_test::run_tool_process(argv, scratch);
}

// Good inputs: the library's n³ Kuhn grid of [0,n]³ (6 VOLMAP-positive tets per cube) and its identity
// boundary map.
struct Grid {
  std::vector<double> xyz;
  std::vector<std::uint32_t> tets;  // 0-based
  volmap_test::GridFixture fixture;
};

Grid kuhn_grid(int n) {
  Grid g{{}, {}, volmap_test::kuhn_grid_fixture(n)};
  g.xyz = g.fixture.mesh.xyz;
  g.tets = g.fixture.mesh.tets;
  return g;
}

std::string medit(const Grid& g) {
  volmap::TetMeshData m = g.fixture.mesh;
  m.xyz = g.xyz;
  m.tets = g.tets;
  return volmap_test::medit_text(m);
}

std::string identity_map(const Grid& g) { return volmap_test::identity_map_text(g.fixture); }

std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// ---------------------------------------------------------------------------------------------
struct Corpus {
  fs::path dir;      // inputs (never written by a tool)
  fs::path scratch;  // stdout/stderr captures
  int cases = 0, skipped_tools = 0;
  std::vector<std::string> failures;
  std::vector<std::string> disabled;  // tools whose control run could not work here (e.g. no viewer bundle)

  bool usable(const std::string& tool_name) const {
    return fs::exists(volmap_test::tool(tool_name)) &&
           std::find(disabled.begin(), disabled.end(), tool_name) == disabled.end();
  }

  fs::path in(const std::string& name) const { return dir / name; }

  // One run: `args` may contain "@OUT/<name>" for an output inside a fresh, initially empty folder
  // (that folder must still be empty afterwards). One of the '|'-separated `must_name` alternatives
  // must appear in the one stderr line; `codes` are the acceptable exit codes. Exit 1 (a check that
  // failed) may instead report on stdout with an empty stderr.
  void expect(const std::string& tool_name, std::vector<std::string> args, const std::string& must_name,
              std::vector<int> codes = {2}) {
    const fs::path exe = volmap_test::tool(tool_name);
    if (!usable(tool_name)) return;
    const fs::path out_dir = dir.parent_path() / ("out_" + std::to_string(cases++));
    fs::create_directories(out_dir);
    for (auto& a : args)
      if (a.rfind("@OUT/", 0) == 0) a = (out_dir / a.substr(5)).string();
    std::vector<std::string> argv{exe.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    const auto before = listing(dir);
    const RunResult r = run(argv, scratch);
    std::string what = tool_name;
    for (const auto& a : args) what += " " + fs::path(a).filename().string();
    auto fail = [&](const std::string& why) {
      failures.push_back(what + ": " + why + " | stderr: " + r.err.substr(0, 400));
    };
    std::string err = r.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    if (r.signaled) {
      fail("killed by signal " + std::to_string(r.signal));
    } else if (std::find(codes.begin(), codes.end(), r.exit_code) == codes.end()) {
      fail("exit " + std::to_string(r.exit_code));
    } else if (r.exit_code == 1 && err.empty() && !r.out.empty()) {
      // a failed check reported on stdout
    } else if (err.empty() || err.find('\n') != std::string::npos) {
      fail("stderr is not exactly one line");
    } else if (!names_one_of(err, must_name)) {
      fail("stderr does not name " + must_name);
    } else if (err.find("usage:") != std::string::npos) {
      fail("refused as a usage error (argument shape wrong?)");
    } else if (err.find("out of memory") != std::string::npos) {
      fail("a giant allocation was attempted before validation");
    } else if (r.peak_rss_kb > (1l << 20)) {
      fail("peak RSS " + std::to_string(r.peak_rss_kb / 1024) + " MiB");
    }
    if (!listing(out_dir).empty()) fail("left files behind in the output folder: " + listing(out_dir).front());
    if (listing(dir) != before) fail("changed the input folder");
    fs::remove_all(out_dir);
  }

  // A run that must succeed (exit 0, no signal).
  void control(const std::string& tool_name, std::vector<std::string> args) {
    const fs::path exe = volmap_test::tool(tool_name);
    if (!fs::exists(exe)) {
      MESSAGE("skipped: " << exe.string() << " is not built");
      ++skipped_tools;
      return;
    }
    const fs::path out_dir = dir.parent_path() / "control_out";
    fs::create_directories(out_dir);
    for (auto& a : args)
      if (a.rfind("@OUT/", 0) == 0) a = (out_dir / a.substr(5)).string();
    std::vector<std::string> argv{exe.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    const RunResult r = run(argv, scratch);
    if (!r.signaled && r.exit_code == 2 && r.err.find("viewer bundle not found") != std::string::npos) {
      MESSAGE("skipped " << tool_name << ": " << r.err);
      disabled.push_back(tool_name);
    } else if (r.signaled || r.exit_code != 0)
      failures.push_back("control " + tool_name + " failed: exit " + std::to_string(r.exit_code) + " signal " +
                         std::to_string(r.signal) + " | " + r.err.substr(0, 400));
    fs::remove_all(out_dir);
  }
};

struct Fixture {
  fs::path root;
  Corpus corpus;
  Grid grid = kuhn_grid(2);
  std::string good_mesh, good_map;
  std::vector<std::string> bad_meshes;  // file names in corpus.dir
  std::vector<std::string> bad_maps;

  Fixture() {
    root = fs::temp_directory_path() / ("volmap_bad_inputs_" + std::to_string(getpid()));
    fs::remove_all(root);
    corpus.dir = root / "in";
    corpus.scratch = root / "scratch";
    fs::create_directories(corpus.dir);
    fs::create_directories(corpus.scratch);
    good_mesh = medit(grid);
    good_map = identity_map(grid);
    spit(corpus.in("good.mesh"), good_mesh);
    spit(corpus.in("good_map.txt"), good_map);
    spit(corpus.in("one_cube.mesh"), medit(kuhn_grid(1)));
    spit(corpus.in("one_cube_map.txt"), identity_map(kuhn_grid(1)));

    auto bad_mesh = [&](const std::string& name, const std::string& text) {
      spit(corpus.in(name), text);
      bad_meshes.push_back(name);
    };
    bad_mesh("m_empty.mesh", "");
    bad_mesh("m_truncated.mesh", good_mesh.substr(0, good_mesh.size() * 3 / 5));
    bad_mesh("m_wrong_count.mesh", replace_once(good_mesh, "Tetrahedra\n48", "Tetrahedra\n49"));
    bad_mesh("m_id_range.mesh", replace_once(good_mesh, "Tetrahedra\n48\n", "Tetrahedra\n48\n999 "));
    bad_mesh("m_id_negative.mesh", replace_once(good_mesh, "Tetrahedra\n48\n", "Tetrahedra\n48\n-3 "));
    bad_mesh("m_id_zero.mesh", replace_once(good_mesh, "Tetrahedra\n48\n", "Tetrahedra\n48\n0 "));
    bad_mesh("m_id_overflow.mesh", replace_once(good_mesh, "Tetrahedra\n48\n", "Tetrahedra\n48\n99999999999999999999 "));
    bad_mesh("m_nan.mesh", replace_once(good_mesh, "Vertices\n27\n0 ", "Vertices\n27\nnan "));
    bad_mesh("m_inf.mesh", replace_once(good_mesh, "Vertices\n27\n0 ", "Vertices\n27\n-inf "));
    bad_mesh("m_overflow.mesh", replace_once(good_mesh, "Vertices\n27\n0 ", "Vertices\n27\n1e99999 "));
    bad_mesh("m_huge_vertices.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n4000000000\n0 0 0 0\n");
    bad_mesh("m_huge_tets.mesh", replace_once(good_mesh, "Tetrahedra\n48", "Tetrahedra\n2000000000"));
    bad_mesh("m_binary.mesh", std::string("\x7f\x45\x4c\x46\x00\xff\xfe\x01garbage\x00\n\x01", 18));
    bad_mesh("m_bowtie.mesh",  // two tets sharing one vertex: not a manifold ball
             "MeshVersionFormatted 1\nDimension 3\nVertices\n7\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
             "-1 0 0 0\n0 -1 0 0\n0 0 -1 0\nTetrahedra\n2\n1 2 3 4 0\n1 5 7 6 0\nEnd\n");
    bad_mesh("m_huge.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4000000000 double\n0 0 0\n");
    bad_mesh("m_truncated.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0\n1 0");
    bad_mesh("m_huge.vtu",
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
             "<UnstructuredGrid>\n<Piece NumberOfPoints=\"4000000000\" NumberOfCells=\"4000000000\">\n<Points>\n"
             "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0</DataArray>\n</Points>\n");
    bad_mesh("m_truncated.vtu", "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n<Unstru");
    fs::create_directories(corpus.in("m_directory.mesh"));
    bad_meshes.push_back("m_directory.mesh");
    bad_meshes.push_back("m_missing.mesh");

    auto bad_map = [&](const std::string& name, const std::string& text) {
      spit(corpus.in(name), text);
      bad_maps.push_back(name);
    };
    const std::string first = good_map.substr(0, good_map.find('\n') + 1);  // "0 0 0 0\n"
    bad_map("b_empty.txt", "");
    std::string first14;  // the first 14 lines, then a line cut after its y coordinate (line 15)
    for (std::size_t at = 0, lines = 0; lines < 14; ++lines) {
      const std::size_t end = good_map.find('\n', at) + 1;
      first14 += good_map.substr(at, end - at);
      at = end;
    }
    bad_map("b_truncated.txt", first14 + "17 0.5\n");
    bad_map("b_id_range.txt", good_map + "999 0 0 0\n");
    bad_map("b_id_negative.txt", good_map + "-1 0 0 0\n");
    bad_map("b_id_overflow.txt", good_map + "4294967296 0 0 0\n");
    bad_map("b_nan.txt", replace_once(good_map, first, "0 nan 0 0\n"));
    bad_map("b_inf.txt", replace_once(good_map, first, "0 0 inf 0\n"));
    bad_map("b_overflow.txt", replace_once(good_map, first, "0 0 0 1e99999\n"));
    bad_map("b_duplicate.txt", good_map + first);
    bad_map("b_interior.txt", good_map + "13 1 1 1\n");  // vertex 13 is the grid's centre
    bad_map("b_missing_vertex.txt", good_map.substr(first.size()));
    bad_map("b_binary.txt", std::string("\x00\x01\x02\xff\n\x80", 6));
    fs::create_directories(corpus.in("b_directory.txt"));
    bad_maps.push_back("b_directory.txt");
    bad_maps.push_back("b_missing.txt");
  }
  ~Fixture() { fs::remove_all(root); }

  void report() {
    MESSAGE(corpus.cases << " bad-input runs, " << corpus.failures.size() << " failures, " << corpus.skipped_tools
                         << " tools not built");
    for (const auto& f : corpus.failures) MESSAGE(f);
    CHECK(corpus.failures.empty());
  }
};

std::string line_of(const std::string& name, int line) { return name + ":" + std::to_string(line) + ":"; }

}  // namespace

TEST_CASE("bad inputs: tet mesh readers and the mesh tools") {
  Fixture fx;
  auto& c = fx.corpus;
  const std::string good = c.in("good.mesh").string(), map = c.in("good_map.txt").string();
  c.control("volmap-convert", {good, "@OUT/copy.vtu"});
  c.control("volmap-tetmesh-check", {good});
  c.control("volmap-tutte3d", {good, map, "@OUT/t.mesh"});
  c.control("volmap-map-check", {good, good});
  c.control("volmap-metrics", {good, good});
  c.control("volmap-map", {good, map, "@OUT/m.mesh"});
  c.control("volmap-surface-map", {"cube", good, "@OUT/map.txt"});
  c.control("volmap-view", {good, "-o", "@OUT/v.html"});
  for (const auto& name : fx.bad_meshes) {
    const std::string bad = c.in(name).string();
    const std::vector<int> check_codes = {1, 2};  // bowtie / orientation problems may be "check failed"
    if (name != "m_bowtie.mesh") c.expect("volmap-convert", {bad, "@OUT/copy.mesh"}, name);  // bowtie: a valid file
    c.expect("volmap-tetmesh-check", {bad}, name, check_codes);
    c.expect("volmap-tutte3d", {bad, map, "@OUT/t.mesh"}, name + "|good_map.txt", check_codes);
    c.expect("volmap-map-check", {bad, good}, name, check_codes);
    c.expect("volmap-map-check", {good, bad}, name, check_codes);
    c.expect("volmap-metrics", {good, bad}, name, check_codes);
    c.expect("volmap-map", {bad, map, "@OUT/m.mesh"}, name + "|good_map.txt", check_codes);
    c.expect("volmap-surface-map", {"cube", bad, "@OUT/map.txt"}, name, check_codes);
    c.expect("volmap-surface-map-check", {bad, map, "--domain", "cube"}, name + "|good_map.txt", check_codes);
    // bowtie: a valid file with bad topology, which a viewer may show (like volmap-convert copies it)
    if (name != "m_bowtie.mesh") c.expect("volmap-view", {bad, "-o", "@OUT/v.html"}, name);
  }
  // Line numbers where the case is about a line.
  c.expect("volmap-convert", {c.in("m_id_range.mesh").string(), "@OUT/x.vtk"}, line_of("m_id_range.mesh", 34));
  c.expect("volmap-convert", {c.in("m_nan.mesh").string(), "@OUT/x.vtk"}, line_of("m_nan.mesh", 5));
  // Mismatched mesh pairs: different vertex counts, same counts but other connectivity.
  const std::string one = c.in("one_cube.mesh").string();
  c.expect("volmap-map-check", {good, one}, "", {1, 2});
  c.expect("volmap-metrics", {good, one}, "", {1, 2});
  {
    Grid other = kuhn_grid(2);
    other.tets[3] = 26;  // tet 0 gets the far corner: same vertex count, other connectivity
    spit(c.in("other_tets.mesh"), medit(other));
    c.expect("volmap-map-check", {good, c.in("other_tets.mesh").string()}, "", {1, 2});
  }
  // Outputs in missing folders (and an output path that is a folder).
  const std::string nowhere = (fx.root / "no" / "such" / "dir").string();
  c.expect("volmap-convert", {good, nowhere + "/x.vtu"}, "no/such/dir");
  c.expect("volmap-tutte3d", {good, map, nowhere + "/t.mesh"}, "no/such/dir");
  c.expect("volmap-metrics", {good, good, "--csv", nowhere + "/m.csv"}, "no/such/dir");
  c.expect("volmap-tetmesh-check", {good, "--log", nowhere + "/log.txt"}, "no/such/dir", {1, 2});
  c.expect("volmap-map", {good, map, nowhere + "/m.mesh"}, "no/such/dir");
  c.expect("volmap-surface-map", {"cube", good, nowhere + "/map.txt"}, "no/such/dir");
  c.expect("volmap-view", {good, "-o", nowhere + "/v.html"}, "no/such/dir");
  c.expect("volmap-convert", {good, c.dir.string()}, c.dir.filename().string());
  fx.report();
}

TEST_CASE("bad inputs: boundary maps, domains and surfaces") {
  Fixture fx;
  auto& c = fx.corpus;
  const std::string good = c.in("good.mesh").string();
  c.control("volmap-view", {good, "-o", "@OUT/v.html"});
  for (const auto& name : fx.bad_maps) {
    const std::string bad = c.in(name).string();
    c.expect("volmap-tutte3d", {good, bad, "@OUT/t.mesh"}, name, {1, 2});
    c.expect("volmap-map-check", {good, good, "--boundary", bad}, name, {1, 2});
    c.expect("volmap-map", {good, bad, "@OUT/m.mesh"}, name, {1, 2});
    c.expect("volmap-surface-map-check", {good, bad, "--domain", "cube"}, name, {1, 2});
    c.expect("volmap-view", {good, "--map", bad, "-o", "@OUT/v.html"}, name, {1, 2});
  }
  c.expect("volmap-tutte3d", {good, c.in("b_truncated.txt").string(), "@OUT/t.mesh"},
           line_of("b_truncated.txt", 15));
  // A map that belongs to another mesh.
  c.expect("volmap-tutte3d", {good, c.in("one_cube_map.txt").string(), "@OUT/t.mesh"}, "one_cube_map.txt", {1, 2});

  // Custom domains.
  auto domain = [&](const std::string& name, const std::string& text) {
    spit(c.in(name), text);
    c.expect("volmap-surface-map", {"custom", good, "@OUT/map.txt", "--domain", c.in(name).string()}, name, {1, 2});
  };
  const std::string tet = "n 0\nn 1\nn 2\nn 4\nnm 0 0 0\nnm 0 0 100\nnm 100 0 50\nnm 30 100 30\n"
                          "a 0 1\na 1 2\na 2 0\na 3 0\na 3 1\na 3 2\n";
  domain("d_empty.txt", "");
  domain("d_arc_range.txt", tet + "a 0 7\n");
  domain("d_arc_negative.txt", tet + "a -1 2\n");
  domain("d_nan.txt", replace_once(tet, "nm 0 0 0", "nm nan 0 0"));
  domain("d_inf.txt", replace_once(tet, "nm 0 0 0", "nm inf 0 0"));
  domain("d_overflow.txt", replace_once(tet, "nm 0 0 0", "nm 1e99999 0 0"));
  domain("d_corner_range.txt", replace_once(tet, "n 4", "n 9"));
  domain("d_truncated.txt", tet.substr(0, tet.size() / 2));
  domain("d_binary.txt", std::string("\x00\xff\x01\n", 4));
  fs::create_directories(c.in("d_directory.txt"));
  c.expect("volmap-surface-map", {"custom", good, "@OUT/map.txt", "--domain", c.in("d_directory.txt").string()},
           "d_directory.txt", {1, 2});
  c.expect("volmap-surface-map", {"custom", good, "@OUT/map.txt", "--domain", c.in("d_missing.txt").string()},
           "d_missing.txt", {1, 2});

  // Surfaces (volmap-tetrahedralize).
  auto surface = [&](const std::string& name, const std::string& text) {
    spit(c.in(name), text);
    c.expect("volmap-tetrahedralize", {c.in(name).string(), "@OUT/t.mesh"}, name, {1, 2});
  };
  surface("s_empty.off", "");
  surface("s_empty.obj", "");
  surface("s_empty.ply", "");
  surface("s_empty.stl", "");
  const std::string off = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  spit(c.in("tet.off"), off);
  c.control("volmap-tetrahedralize", {c.in("tet.off").string(), "@OUT/t.mesh"});
  surface("s_truncated.off", off.substr(0, off.size() / 2));
  surface("s_id_range.off", replace_once(off, "3 1 2 3", "3 1 2 9"));
  surface("s_id_negative.off", replace_once(off, "3 1 2 3", "3 1 2 -1"));
  surface("s_nan.off", replace_once(off, "0 0 1\n", "0 0 nan\n"));
  surface("s_overflow.off", replace_once(off, "0 0 1\n", "0 0 1e99999\n"));
  surface("s_huge.off", "OFF\n2000000000 2000000000 0\n0 0 0\n");
  surface("s_huge_polygon.off", replace_once(off, "3 1 2 3", "2000000000 1 2 3"));
  surface("s_id_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  surface("s_nan.obj", "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  surface("s_huge.ply",
          "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
          "property float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n\x01\x02");
  surface("s_truncated.ply",
          "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
          "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0");
  surface("s_huge.stl", std::string(80, ' ') + std::string("\xff\xff\xff\x7f", 4) + std::string(50, '\0'));
  surface("s_truncated.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0");
  fs::create_directories(c.in("s_directory.off"));
  c.expect("volmap-tetrahedralize", {c.in("s_directory.off").string(), "@OUT/t.mesh"}, "s_directory.off", {1, 2});
  c.expect("volmap-tetrahedralize", {c.in("s_missing.off").string(), "@OUT/t.mesh"}, "s_missing.off", {1, 2});
  c.expect("volmap-tetrahedralize", {c.in("tet.off").string(), (fx.root / "no/such/dir/t.mesh").string()}, "no/such/dir");

  // Folders given to the dataset tools: a file instead of a folder, an empty folder, a missing one.
  fs::create_directories(c.dir / "empty_dir");
  c.expect("volmap-run", {good, "--method", "tutte3d", "--out", "@OUT/results"}, "good.mesh", {1, 2});
  c.expect("volmap-run", {(c.dir / "missing_dir").string(), "--method", "tutte3d", "--out", "@OUT/results"},
           "missing_dir", {1, 2});
  c.expect("volmap-run", {"report", good}, "good.mesh", {1, 2});
  c.expect("volmap-run", {"report", (c.dir / "empty_dir").string(), "-o", "@OUT/r.md"}, "empty_dir", {1, 2});
  c.expect("volmap-dataset", {good, "@OUT/ds", "--group", "G9"}, "good.mesh", {1, 2});
  c.expect("volmap-dataset", {(c.dir / "missing_dir").string(), "@OUT/ds", "--group", "G9"}, "missing_dir", {1, 2});
  c.expect("volmap-shapes", {good}, "good.mesh", {1, 2});
  fx.report();
}

TEST_CASE("bad inputs: ../shared/data/negative (open, non-genus-0, self-intersecting)") {
  const auto root = volmap_test::data_root();
  if (root.empty() || !fs::is_directory(root / "negative")) {
    MESSAGE("skipped: ../shared/data/negative is absent");
    return;
  }
  Fixture fx;
  auto& c = fx.corpus;
  for (const auto& entry : fs::directory_iterator(root / "negative")) {
    const std::string path = entry.path().string(), name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    if (ext == ".mesh") {
      // Every .mesh here is refused by the mesh check and cannot be surface-mapped.
      c.expect("volmap-tetmesh-check", {path}, name, {1, 2});
      c.expect("volmap-surface-map", {"cube", path, "@OUT/map.txt"}, name, {1, 2});
    } else if (ext == ".off" || ext == ".obj") {
      if (entry.file_size() > 300 * 1024) continue;  // keep the default run short (TetGen in the ASan build)
      c.expect("volmap-tetrahedralize", {path, "@OUT/t.mesh"}, name, {1, 2});
    }
  }
  fx.report();
}

TEST_CASE("bad inputs: rationals files and unreadable paths and the remaining options of every tool") {
  Fixture fx;
  auto& c = fx.corpus;
  const std::string good = c.in("good.mesh").string(), map = c.in("good_map.txt").string();
  // Exact coordinates of good.mesh: one rational per line, x y z per vertex (27 vertices = 81 lines).
  std::string rat;
  for (double x : fx.grid.xyz) rat += std::to_string(int(x)) + "\n";
  spit(c.in("good.rat"), rat);
  c.control("volmap-map-check", {good, good, "--rationals-in", c.in("good.rat").string()});
  c.control("volmap-view", {good, "-o", "@OUT/v.html"});
  auto rationals = [&](const std::string& name, const std::string& text) {
    spit(c.in(name), text);
    c.expect("volmap-map-check", {good, good, "--rationals-in", c.in(name).string()}, name, {1, 2});
    c.expect("volmap-map-check", {good, good, "--rationals-out", c.in(name).string()}, name, {1, 2});
  };
  rationals("r_empty.rat", "");
  rationals("r_truncated.rat", rat.substr(0, rat.size() / 2));
  rationals("r_too_many.rat", rat + "1\n");
  rationals("r_zero_den.rat", replace_once(rat, "0\n", "1/0\n"));
  rationals("r_garbage.rat", replace_once(rat, "0\n", "1/x\n"));
  rationals("r_float.rat", replace_once(rat, "0\n", "0.5\n"));
  rationals("r_nan.rat", replace_once(rat, "0\n", "nan\n"));
  rationals("r_binary.rat", std::string("\x00\xff/\x01\n", 5));
  rationals("r_overlong.rat", replace_once(rat, "0\n", std::string(200000, '9') + "/" + std::string(200000, '7') + "\n"));
  fs::create_directories(c.in("r_directory.rat"));
  c.expect("volmap-map-check", {good, good, "--rationals-in", c.in("r_directory.rat").string()}, "r_directory.rat",
           {1, 2});
  c.expect("volmap-map-check", {good, good, "--rationals-in", c.in("r_missing.rat").string()}, "r_missing.rat",
           {1, 2});

  // Unreadable paths that stay unreadable for root too: a symlink loop and a path through a file.
  fs::create_symlink("loop.mesh", c.in("loop.mesh"));
  const std::string loop = c.in("loop.mesh").string(), through = good + "/x.mesh";
  for (const std::string& bad : {loop, through}) {
    const std::string name = fs::path(bad).filename().string();
    c.expect("volmap-convert", {bad, "@OUT/x.vtu"}, name);
    c.expect("volmap-tetmesh-check", {bad}, name, {1, 2});
    c.expect("volmap-tutte3d", {bad, map, "@OUT/t.mesh"}, name, {1, 2});
    c.expect("volmap-map", {good, bad, "@OUT/m.mesh"}, name, {1, 2});
    c.expect("volmap-map-check", {good, bad}, name, {1, 2});
    c.expect("volmap-metrics", {bad, good}, name, {1, 2});
    c.expect("volmap-surface-map", {"cube", bad, "@OUT/map.txt"}, name, {1, 2});
    c.expect("volmap-surface-map-check", {good, bad, "--domain", "cube"}, name, {1, 2});
    c.expect("volmap-tetrahedralize", {bad, "@OUT/t.mesh"}, name, {1, 2});
    c.expect("volmap-view", {bad, "-o", "@OUT/v.html"}, name, {1, 2});
  }
  // chmod 000 only bites without root (CI may run as root: then it is a readable file, not a case).
  if (geteuid() != 0) {
    spit(c.in("no_read.mesh"), fx.good_mesh);
    fs::permissions(c.in("no_read.mesh"), fs::perms::none);
    c.expect("volmap-convert", {c.in("no_read.mesh").string(), "@OUT/x.vtu"}, "no_read.mesh");
    c.expect("volmap-tetmesh-check", {c.in("no_read.mesh").string()}, "no_read.mesh", {1, 2});
    fs::permissions(c.in("no_read.mesh"), fs::perms::owner_all);
  }

  // Secondary inputs and outputs not covered above.
  const std::string nowhere = (fx.root / "no" / "such" / "dir").string();
  c.expect("volmap-metrics", {good, good, "--original", c.in("m_truncated.mesh").string()}, "m_truncated.mesh", {1, 2});
  c.expect("volmap-metrics", {good, good, "--vtu", nowhere + "/m.vtu"}, "no/such/dir");
  // volmap-map once wrote m.mesh and then failed on the missing rationals folder (partial output);
  // with --refined-input it succeeded when no refinement was needed: all output folders are now
  // checked before the run.
  c.expect("volmap-map", {good, map, "@OUT/m.mesh", "--rationals", nowhere + "/m.rat"}, "no/such/dir", {1, 2});
  c.expect("volmap-map", {good, map, "@OUT/m.mesh", "--refined-input", nowhere + "/r.mesh"}, "no/such/dir", {1, 2});
  c.expect("volmap-map-check", {good, good, "--boundary", c.in("one_cube_map.txt").string()}, "one_cube_map.txt",
           {1, 2});
  c.expect("volmap-surface-map", {"cube", good, "@OUT/map.txt", "--refined", nowhere + "/r.mesh"}, "no/such/dir",
           {1, 2});
  c.expect("volmap-tetmesh-check", {good, "--fix", nowhere + "/f.mesh"}, "no/such/dir", {1, 2});
  c.expect("volmap-view", {good, "--bundle", c.in("missing_bundle.js").string(), "-o", "@OUT/v.html"},
           "missing_bundle.js", {1, 2});
  c.expect("volmap-shapes", {(fs::path(good) / "shapes").string()}, "good.mesh", {1, 2});
  c.expect("volmap-run", {"list", (c.dir / "missing_dir").string()}, "missing_dir", {1, 2});
  c.expect("volmap-run", {"case", (c.dir / "missing_dir").string(), "G1/bone_cube", "--method", "tutte3d"}, "missing_dir|bone_cube", {1, 2});
  fx.report();
}
