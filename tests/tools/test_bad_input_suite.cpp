// The bad-input suite: every volmap-* tool × every input and output argument × the classes of bad
// input an outside tester tries, generated here and run through the real executables.
//   input files   missing, directory, empty, /dev/zero and /dev/null (through a link with the right
//                 extension), symlink loop, path through a file, binary garbage, UTF-16, truncated,
//                 huge declared counts, NaN, the wrong format behind an extension, and per kind:
//                 invalid meshes (duplicate tet, coincident copy, inverted, mixed, flat, unused or
//                 repeated vertex, two pieces, pinched, genus 1, no tets), bad maps, rationals,
//                 domains, surfaces, results logs, viewer bundles;
//   accepted      UTF-8 byte-order mark, CRLF, the mesh in .vtk/.vtu (the format dispatcher);
//   output paths  an input, another output, a FIFO, /dev/null, a directory, a missing folder, a path
//                 through a file, a wrong extension — with every other output of the run valid, so a
//                 partial write shows;
//   options       NaN, infinity, negative, not a number;
//   signals       SIGTERM/SIGINT during the run.
// Every refused run must: exit with the expected code (never a signal), print one stderr line that
// names the offending file or option, leave no output and no temporary file, change no input, stay
// under 1 GiB and 20 s, and print no certificate. Accepted runs must behave like the control run.
// The suite records its counts (tried / clean / defects) in <build>/bad_input_suite.txt and prints
// them.
#include <doctest/doctest.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/io/io.hpp>
#include <volmap/testing/generate.hpp>

#include "tool_run.hpp"

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sys/stat.h>
#include <thread>

namespace fs = std::filesystem;
using volmap_test::RunResult;

namespace {

// ---- what the tools take -------------------------------------------------------------------------
enum class Kind {
  Mesh,        // a source tet mesh the tool must validate
  ViewMesh,    // a tet mesh a format tool or viewer reads without judging it
  Mapped,      // a mapped tet mesh (the output of a mapper), read as an input
  Map,         // boundary map
  Rationals,   // rationals file
  Domain,      // custom domain file
  Surface,     // triangle surface
  Results,     // volmap-run results folder (holding results.jsonl)
  Bundle,      // viewer bundle
  OutMesh,     // tet mesh output (.mesh/.vtk/.vtu by extension)
  OutVtu,      // .vtu-only output
  OutFile,     // any other file output (map, CSV, HTML, rationals)
  OutDir,      // an output folder (created when missing)
};
bool is_output(Kind k) { return k == Kind::OutMesh || k == Kind::OutVtu || k == Kind::OutFile || k == Kind::OutDir; }

struct Slot {
  std::string key;     // option text ("--fix") or a positional's name
  Kind kind;
  bool positional;
  std::string good;    // good value: an input path, or an output file name (in the out folder)
  bool vary = true;    // false: the slot keeps its good value (it is varied in another invocation)
};

struct Invocation {
  std::string label;   // "volmap-map", "volmap-map (--initial)"
  std::string tool;
  std::vector<std::string> head;   // literal arguments before the slots (subcommands, domains)
  std::vector<Slot> slots;
  std::vector<std::string> tail;   // literal arguments after the slots
  std::vector<std::string> numeric_options;  // options taking a number
};

// ---- the cases -------------------------------------------------------------------------------------
struct Variant {
  std::string cls;        // class name for the counts: "validity", "paths", ...
  std::string what;       // short description
  std::string value;      // the bad value put into the slot
  std::string must_name;  // '|' alternatives, one of which stderr must contain
  std::vector<int> codes; // acceptable exit codes
  bool accepted = false;  // the run must succeed like the control run
};

struct Counts {
  int tried = 0, clean = 0, defects = 0;
};

class Suite : public volmap_test::ToolTree {
 public:
  fs::path dev;  // FIFOs, device links and folders as output targets
  std::map<std::string, Counts> by_class;
  std::vector<std::string> failures;

  Suite() : ToolTree("bad_input_suite"), dev(root / "dev") { fs::create_directories(dev); }

  std::string file(const std::string& name, const std::string& bytes) const {
    return volmap_test::write_bytes(in / name, bytes);
  }
  std::string link(const std::string& name, const std::string& target) const {
    fs::create_symlink(target, in / name);
    return (in / name).string();
  }

  std::vector<std::string> render(const Invocation& inv, const std::map<std::string, std::string>& overrides,
                                  const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> argv{volmap_test::tool(inv.tool).string()};
    argv.insert(argv.end(), inv.head.begin(), inv.head.end());
    for (const Slot& s : inv.slots) {
      auto it = overrides.find(s.key);
      std::string v = it != overrides.end() ? it->second : is_output(s.kind) ? (out / s.good).string() : s.good;
      if (!s.positional) argv.push_back(s.key);
      argv.push_back(v);
    }
    argv.insert(argv.end(), inv.tail.begin(), inv.tail.end());
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
  }

  // The control run: exit 0, or the invocation is not usable here (tool not built, no bundle).
  bool control(const Invocation& inv) {
    if (!fs::exists(volmap_test::tool(inv.tool))) {
      MESSAGE("skipped: " << inv.tool << " is not built");
      return false;
    }
    const RunResult r = volmap_test::run_tool_process(render(inv, {}), scratch, 120);
    clear_out();
    if (!r.signaled && r.exit_code == 2 && r.err.find("viewer bundle not found") != std::string::npos) {
      MESSAGE("skipped " << inv.label << ": " << r.err);
      return false;
    }
    if (r.signaled || r.exit_code != 0) {
      failures.push_back("control " + inv.label + " failed: exit " + std::to_string(r.exit_code) + " | " + r.err.substr(0, 300));
      return false;
    }
    return true;
  }

  // One case: slot `key` (or, with key "", extra arguments) gets `v.value`.
  void run_case(const Invocation& inv, const std::string& key, const Variant& v, const std::vector<std::string>& extra = {}) {
    std::map<std::string, std::string> overrides;
    if (!key.empty()) overrides[key] = v.value;
    const std::vector<std::string> argv = render(inv, overrides, extra);
    const std::string before_in = volmap_test::fingerprint(in), before_dev = volmap_test::fingerprint(dev);
    const RunResult r = volmap_test::run_tool_process(argv, scratch, 60);
    std::string err = r.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    std::vector<std::string> problems;
    if (r.signaled) problems.push_back("killed by signal " + std::to_string(r.signal));
    if (!r.signaled && std::find(v.codes.begin(), v.codes.end(), r.exit_code) == v.codes.end())
      problems.push_back("exit " + std::to_string(r.exit_code));
    if (!v.accepted && !r.signaled && r.exit_code != 0) {
      const bool quiet_check_failure = r.exit_code == 1 && err.empty();
      if (!quiet_check_failure) {
        if (err.empty() || err.find('\n') != std::string::npos) problems.push_back("stderr is not one line");
        else if (!volmap_test::names_one_of(err, v.must_name)) problems.push_back("stderr does not name " + v.must_name);
        if (err.find("out of memory") != std::string::npos) problems.push_back("allocated before validating");
      }
      if (!volmap_test::listing(out).empty()) problems.push_back("left an output: " + volmap_test::listing(out).front());
    }
    for (const std::string phrase : {"certified injective", "The map is valid (certified", "Check result: SUCCESS"})
      if (!v.accepted && r.out.find(phrase) != std::string::npos) problems.push_back("printed a certificate");
    for (const auto& dir : {in, out, dev})
      for (const auto& name : volmap_test::listing(dir))
        if (name.find(".tmp.") != std::string::npos) problems.push_back("temporary file left: " + name);
    if (inv.tool == "volmap-tetmesh-check" && r.exit_code != 0 && fs::exists(out / "fixed.mesh"))
      problems.push_back("wrote the --fix output of a mesh that fails a check");
    if (volmap_test::fingerprint(in) != before_in) problems.push_back("changed an input");
    if (volmap_test::fingerprint(dev) != before_dev) problems.push_back("replaced a FIFO/device/link");
    if (r.peak_rss_kb > (1l << 20)) problems.push_back("peak RSS " + std::to_string(r.peak_rss_kb / 1024) + " MiB");
    if (r.seconds > 20) problems.push_back("took " + std::to_string(int(r.seconds)) + " s");
    record(v.cls, inv.label + " " + (key.empty() ? std::string("options") : key) + " <- " + v.what, problems, err);
    clear_out();
  }

  // A run interrupted by `sig` after `delay`: no temporary file, no changed input.
  void signal_case(const Invocation& inv, int sig, int delay_ms) {
    const std::string before_in = volmap_test::fingerprint(in);
    const RunResult r = volmap_test::run_tool_process(render(inv, {}), scratch, 60, [&](pid_t pid) {
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      kill(pid, sig);
    });
    std::vector<std::string> problems;
    if (r.signaled && r.signal != sig) problems.push_back("died of signal " + std::to_string(r.signal));
    if (!r.signaled && r.exit_code != 0) problems.push_back("exit " + std::to_string(r.exit_code));
    for (const auto& dir : {in, out, dev})
      for (const auto& name : volmap_test::listing(dir))
        if (name.find(".tmp.") != std::string::npos) problems.push_back("temporary file left: " + name);
    if (volmap_test::fingerprint(in) != before_in) problems.push_back("changed an input");
    record("signals", inv.label + " <- " + std::string(sig == SIGINT ? "SIGINT" : "SIGTERM") + " after " +
                          std::to_string(delay_ms) + " ms",
           problems, r.err);
    clear_out();
  }

  void record(const std::string& cls, const std::string& what, const std::vector<std::string>& problems,
              const std::string& err) {
    Counts& c = by_class[cls];
    ++c.tried;
    if (problems.empty()) {
      ++c.clean;
    } else {
      ++c.defects;
      std::string line = what + ": ";
      for (const auto& p : problems) line += p + "; ";
      failures.push_back(line + "| stderr: " + err.substr(0, 300));
    }
  }

};

// ---- fixtures ---------------------------------------------------------------------------------------
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

std::string crlf(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
  return out;
}

// Meshes volmap-tetmesh-check rejects, built from the 2x2x2 Kuhn grid (and a 3x3x1 one).
std::vector<std::pair<std::string, volmap::TetMeshData>> invalid_meshes(const volmap::TetMeshData& g) {
  std::vector<std::pair<std::string, volmap::TetMeshData>> out;
  auto flip = [](volmap::TetMeshData m, std::size_t t) {
    std::swap(m.tets[4 * t], m.tets[4 * t + 1]);
    return m;
  };
  {
    volmap::TetMeshData m = g;
    m.tets.insert(m.tets.end(), g.tets.begin() + 20, g.tets.begin() + 24);
    out.emplace_back("v_duplicate_tet", m);
  }
  {
    volmap::TetMeshData m = g;  // a copy of the first cube over 8 coincident vertices
    std::map<std::uint32_t, std::uint32_t> copy;
    for (std::size_t k = 0; k < 24; ++k) {
      const std::uint32_t v = g.tets[k];
      if (!copy.count(v)) {
        copy[v] = static_cast<std::uint32_t>(m.num_vertices());
        m.xyz.insert(m.xyz.end(), &g.xyz[3 * v], &g.xyz[3 * v] + 3);
      }
      m.tets.push_back(copy[v]);
    }
    out.emplace_back("v_coincident_copy", m);
  }
  {
    volmap::TetMeshData m = g;
    for (std::size_t t = 0; t < m.num_tets(); ++t) m = flip(m, t);
    out.emplace_back("v_all_inverted", m);
  }
  out.emplace_back("v_one_inverted", flip(g, 7));
  {
    volmap::TetMeshData m = g;  // the centre vertex (1,1,1) moved far out: flat and inverted tets
    m.xyz[3 * 13] = 1, m.xyz[3 * 13 + 1] = 1, m.xyz[3 * 13 + 2] = 0;
    out.emplace_back("v_flat", m);
  }
  {
    volmap::TetMeshData m = g;
    m.xyz.insert(m.xyz.end(), {7, 7, 7});
    out.emplace_back("v_unused_vertex", m);
  }
  {
    volmap::TetMeshData m = g;
    m.tets[2] = m.tets[1];
    out.emplace_back("v_repeated_vertex", m);
  }
  {
    volmap::TetMeshData m = g;  // a second grid beside the first
    const std::uint32_t nv = static_cast<std::uint32_t>(g.num_vertices());
    for (std::size_t v = 0; v < nv; ++v) m.xyz.insert(m.xyz.end(), {g.xyz[3 * v] + 10, g.xyz[3 * v + 1], g.xyz[3 * v + 2]});
    for (std::uint32_t id : g.tets) m.tets.push_back(id + nv);
    out.emplace_back("v_two_pieces", m);
  }
  {
    volmap::TetMeshData m;  // two tets sharing one vertex
    m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
    m.tets = {0, 1, 2, 3, 0, 4, 6, 5};
    out.emplace_back("v_pinched", m);
  }
  {
    volmap::TetMeshData m = volmap::generate_kuhn_grid(3, 3, 1);  // the centre cube removed: a torus
    m.tets.erase(m.tets.begin() + 4 * 24, m.tets.begin() + 4 * 30);
    out.emplace_back("v_genus_one", m);
  }
  {
    volmap::TetMeshData m = g;
    m.tets.clear();
    out.emplace_back("v_no_tets", m);
  }
  return out;
}

// ---- the invocations of every tool --------------------------------------------------------------------
struct Inputs {
  std::string mesh, map, rat, domain, surface, results, bundle, init;
};

std::vector<Invocation> invocations(const Inputs& g) {
  return {
      {"volmap-convert", "volmap-convert", {}, {{"input", Kind::ViewMesh, true, g.mesh}, {"output", Kind::OutMesh, true, "c.vtu"}}, {}, {}},
      {"volmap-tetmesh-check", "volmap-tetmesh-check", {},
       {{"input", Kind::Mesh, true, g.mesh}, {"--fix", Kind::OutMesh, false, "fixed.mesh"}, {"--log", Kind::OutFile, false, "log.csv"}},
       {}, {}},
      {"volmap-tetmesh-check (surface)", "volmap-tetmesh-check", {}, {{"input", Kind::Surface, true, g.surface}}, {}, {}},
      {"volmap-tutte3d", "volmap-tutte3d", {},
       {{"in.mesh", Kind::Mesh, true, g.mesh}, {"map.txt", Kind::Map, true, g.map}, {"out.mesh", Kind::OutMesh, true, "t.mesh"}},
       {}, {}},
      {"volmap-map", "volmap-map", {},
       {{"input", Kind::Mesh, true, g.mesh}, {"map", Kind::Map, true, g.map}, {"output", Kind::OutMesh, true, "m.mesh"},
        {"--refined-input", Kind::OutMesh, false, "r.mesh"}, {"--rationals", Kind::OutFile, false, "m.rat"}},
       {},
       {"--max-growth", "--max-growth-last-resort", "--time-limit", "--threads", "--tlc-share", "--ffm-inner"}},
      {"volmap-map (--initial)", "volmap-map", {},
       {{"input", Kind::Mesh, true, g.mesh}, {"map", Kind::Map, true, "-"}, {"output", Kind::OutMesh, true, "m.vtk"},
        {"--initial", Kind::Mapped, false, g.init}},
       {}, {}},
      {"volmap-map-check", "volmap-map-check", {},
       {{"in.mesh", Kind::Mesh, true, g.mesh}, {"out.mesh", Kind::Mapped, true, g.mesh}, {"--boundary", Kind::Map, false, g.map},
        {"--rationals-in", Kind::Rationals, false, g.rat}, {"--rationals-out", Kind::Rationals, false, g.rat}},
       {"--absolute"}, {"--max-bad"}},
      {"volmap-metrics", "volmap-metrics", {},
       {{"in.mesh", Kind::Mesh, true, g.mesh}, {"out.mesh", Kind::Mapped, true, g.mesh}, {"--original", Kind::Mesh, false, g.mesh},
        {"--csv", Kind::OutFile, false, "m.csv"}, {"--vtu", Kind::OutVtu, false, "m.vtu"}},
       {}, {"--upper"}},
      {"volmap-surface-map", "volmap-surface-map", {"custom"},
       {{"mesh", Kind::Mesh, true, g.mesh}, {"map", Kind::OutFile, true, "s.txt"},
        {"--refined", Kind::OutMesh, false, "s_refined.mesh"}, {"--domain", Kind::Domain, false, g.domain}},
       {}, {}},
      {"volmap-surface-map-check", "volmap-surface-map-check", {},
       {{"mesh", Kind::Mesh, true, g.mesh}, {"map", Kind::Map, true, g.map}},
       {}, {"--tolerance"}},
      {"volmap-tetrahedralize", "volmap-tetrahedralize", {},
       {{"surface", Kind::Surface, true, g.surface}, {"out", Kind::OutMesh, true, "tet.mesh"}},
       {}, {"--quality", "--max-volume"}},
      {"volmap-view", "volmap-view", {},
       {{"meshes", Kind::ViewMesh, true, g.mesh}, {"--bundle", Kind::Bundle, false, g.bundle},
        {"-o", Kind::OutFile, false, "v.html"}},
       {}, {"--upper"}},
      {"volmap-view (--map)", "volmap-view", {},
       {{"meshes", Kind::ViewMesh, true, g.mesh, false}, {"--map", Kind::Map, false, g.map},
        {"--bundle", Kind::Bundle, false, g.bundle, false}, {"-o", Kind::OutFile, false, "v.html", false}},
       {}, {}},
      {"volmap-run report", "volmap-run", {"report"},
       {{"results_dir", Kind::Results, true, g.results}, {"-o", Kind::OutFile, false, "r.html"}, {"--csv", Kind::OutFile, false, "s.csv"}},
       {}, {}},
      {"volmap-shapes", "volmap-shapes", {}, {{"out_dir", Kind::OutDir, true, "shapes"}},
       {"--names", "ellipsoid", "--subdivisions", "1"}, {"--subdivisions"}},
  };
}

// The variants of one input kind: what every file input gets, then what its kind gets.
std::vector<Variant> input_variants(Suite& s, Kind kind, const std::string& ext, const Inputs& g,
                                    const std::map<std::string, std::string>& kind_files) {
  std::vector<Variant> v;
  auto refuse = [&](const std::string& cls, const std::string& what, const std::string& path, std::vector<int> codes = {2}) {
    v.push_back({cls, what, path, fs::path(path).filename().string(), std::move(codes)});
  };
  const std::string tag = std::to_string(static_cast<int>(kind));
  if (kind != Kind::Results) {
    refuse("paths", "missing file", (s.in / ("missing" + tag + ext)).string());
    fs::create_directories(s.in / ("dir" + tag + ext));
    refuse("paths", "a directory", (s.in / ("dir" + tag + ext)).string());
    refuse("empty/huge/unbounded", "empty file", s.file("empty" + tag + ext, ""));
    refuse("devices", "/dev/zero", s.link("zero" + tag + ext, "/dev/zero"));
    refuse("devices", "/dev/null", s.link("null" + tag + ext, "/dev/null"));
    refuse("paths", "symlink loop", s.link("loop" + tag + ext, "loop" + tag + ext));
    refuse("paths", "path through a file", g.mesh + "/x" + ext);
    refuse("encodings", "binary garbage", s.file("garbage" + tag + ext, std::string("\x7f" "ELF\x02\x01\x01\0\0\xff\xfe", 12)));
    refuse("encodings", "UTF-16", s.file("utf16" + tag + ext, std::string("\xff\xfe" "1\0 \0" "2\0", 8)));
  }
  for (const auto& [name, cls] : kind_files) {
    const auto dot = name.find('|');
    const std::string file = name.substr(0, dot), codes = name.substr(dot + 1);
    std::vector<int> c;
    for (char ch : codes) c.push_back(ch - '0');
    if (cls == "accepted")
      v.push_back({"encodings", "accepted " + file, (s.in / file).string(), "", {0}, true});
    else
      refuse(cls, file, (s.in / file).string(), c);
  }
  return v;
}

}  // namespace

TEST_CASE("bad-input suite: every tool x every argument x every class") {
  Suite s;
  const volmap::TetMeshData grid = volmap::generate_kuhn_grid(2, 2, 2);
  const std::string mesh_text = volmap_test::medit_text(grid), map_text = volmap_test::boundary_identity_map_text(grid);
  Inputs g;
  g.mesh = s.file("good.mesh", mesh_text);
  g.map = s.file("good_map.txt", map_text);
  g.init = s.file("init.mesh", mesh_text);
  std::string rat;
  for (double x : grid.xyz) rat += std::to_string(static_cast<int>(x)) + "\n";
  g.rat = s.file("good.rat", rat);
  const std::string tet_domain = "n 0\nn 1\nn 2\nn 4\nnm 0 0 0\nnm 0 0 100\nnm 100 0 50\nnm 30 100 30\n"
                                 "a 0 1\na 1 2\na 2 0\na 3 0\na 3 1\na 3 2\n";
  g.domain = s.file("tet_domain.txt", tet_domain);
  const std::string off = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  g.surface = s.file("tet.off", off);
  fs::create_directories(s.in / "results");
  g.results = (s.in / "results").string();
  volmap_test::write_bytes(s.in / "results" / "results.jsonl",
                           "{\"case\":\"G1/a_cube\",\"group\":\"G1\",\"mesh\":\"a\",\"domain\":\"cube\",\"method\":\"m\","
                           "\"certified\":true,\"time_s\":1}\n");
  g.bundle = s.file("bundle.js", "console.log('volmap');\n");
  volmap::write_vtk((s.in / "good.vtk").string(), grid);
  volmap::write_vtu((s.in / "good.vtu").string(), grid);

  // Per-kind files: "name|codes" -> class ("accepted" = must succeed).
  std::map<std::string, std::string> mesh_files, mapped_files, map_files, rat_files, domain_files, surface_files,
      results_files, bundle_files;
  for (const auto& [name, m] : invalid_meshes(grid)) {
    s.file(name + ".mesh", volmap_test::medit_text(m));
    mesh_files[name + ".mesh|2"] = "validity";
  }
  s.file("bom.mesh", "\xEF\xBB\xBF" + mesh_text);
  s.file("crlf.mesh", crlf(mesh_text));
  mesh_files["bom.mesh|0"] = mapped_files["bom.mesh|0"] = "accepted";
  mesh_files["crlf.mesh|0"] = mapped_files["crlf.mesh|0"] = "accepted";
  mesh_files["good.vtk|0"] = mapped_files["good.vtk|0"] = "accepted";
  mesh_files["good.vtu|0"] = mapped_files["good.vtu|0"] = "accepted";
  s.file("truncated.mesh", mesh_text.substr(0, mesh_text.size() / 2));
  s.file("huge_count.mesh", replace_once(mesh_text, "Tetrahedra\n48", "Tetrahedra\n2000000000"));
  s.file("nan.mesh", replace_once(mesh_text, "Vertices\n27\n0 ", "Vertices\n27\nnan "));
  s.file("medit_in.vtk", mesh_text);
  s.file("vtk_in.mesh", volmap_test::read_bytes(s.in / "good.vtk"));
  for (const char* f : {"truncated.mesh|2", "huge_count.mesh|2", "nan.mesh|2", "medit_in.vtk|2", "vtk_in.mesh|2"})
    mesh_files[f] = mapped_files[f] = "empty/huge/unbounded";
  {
    volmap::TetMeshData other = grid;
    other.tets[3] = 26;  // the same counts, other connectivity
    s.file("other_tets.mesh", volmap_test::medit_text(other));
    mapped_files["other_tets.mesh|12"] = "validity";
    s.file("one_cube.mesh", volmap_test::medit_text(volmap::generate_kuhn_grid(1, 1, 1)));
    mapped_files["one_cube.mesh|12"] = "validity";
  }
  s.file("bom_map.txt", "\xEF\xBB\xBF" + map_text);
  s.file("crlf_map.txt", crlf(map_text));
  map_files["bom_map.txt|0"] = map_files["crlf_map.txt|0"] = "accepted";
  const std::string first = map_text.substr(0, map_text.find('\n') + 1);
  s.file("m_range.txt", map_text + "999 0 0 0\n");
  s.file("m_interior.txt", map_text + "13 1 1 1\n");
  s.file("m_duplicate.txt", map_text + first);
  s.file("m_missing_vertex.txt", map_text.substr(first.size()));
  s.file("m_nan.txt", replace_once(map_text, first, "0 nan 0 0\n"));
  s.file("m_long_line.txt", std::string(200000, ' ') + map_text);
  s.file("m_huge_coords.txt", replace_once(map_text, first, "0 1e308 1e308 1e308\n"));
  for (const char* f : {"m_range.txt|2", "m_interior.txt|2", "m_duplicate.txt|2", "m_missing_vertex.txt|2", "m_nan.txt|2",
                        "m_long_line.txt|2"})
    map_files[f] = "validity";
  map_files["m_huge_coords.txt|12"] = "empty/huge/unbounded";
  s.file("r_short.rat", rat.substr(0, rat.size() / 2));
  s.file("r_zero_den.rat", replace_once(rat, "0\n", "1/0\n"));
  s.file("r_float.rat", replace_once(rat, "0\n", "0.5\n"));
  for (const char* f : {"r_short.rat|2", "r_zero_den.rat|2", "r_float.rat|2"}) rat_files[f] = "validity";
  s.file("d_arc_range.txt", tet_domain + "a 0 7\n");
  s.file("d_nan.txt", replace_once(tet_domain, "nm 0 0 0", "nm nan 0 0"));
  s.file("d_bom.txt", "\xEF\xBB\xBF" + tet_domain);
  domain_files["d_arc_range.txt|2"] = domain_files["d_nan.txt|2"] = "validity";
  domain_files["d_bom.txt|0"] = "accepted";
  s.file("s_bom.off", "\xEF\xBB\xBF" + off);
  s.file("s_hole.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n");
  s.file("s_huge.off", "OFF\n2000000000 2000000000 0\n0 0 0\n");
  {
    std::string stl(80, ' ');
    const std::uint32_t count = 3;
    stl.append(reinterpret_cast<const char*>(&count), 4);
    stl.append(100, '\0');  // two records for three announced
    s.file("s_short.stl", stl);
  }
  surface_files["s_bom.off|0"] = "accepted";
  surface_files["s_hole.off|12"] = "validity";
  surface_files["s_huge.off|2"] = surface_files["s_short.stl|2"] = "empty/huge/unbounded";
  for (const auto& [dir, content] : std::vector<std::pair<std::string, std::string>>{
           {"garbage_results", "hello world\n"}, {"empty_results", ""}, {"binary_results", std::string("\0\1\2", 3)}}) {
    fs::create_directories(s.in / dir);
    volmap_test::write_bytes(s.in / dir / "results.jsonl", content);
    results_files[dir + "|2"] = "validity";
  }
  fs::create_directories(s.in / "no_results");
  results_files["no_results|2"] = "paths";
  s.file("empty_bundle.js", "");
  bundle_files["empty_bundle.js|2"] = "empty/huge/unbounded";

  const std::map<Kind, std::pair<std::string, std::map<std::string, std::string>*>> kinds = {
      {Kind::Mesh, {".mesh", &mesh_files}},     {Kind::ViewMesh, {".mesh", &mesh_files}},
      {Kind::Mapped, {".mesh", &mapped_files}}, {Kind::Map, {".txt", &map_files}},
      {Kind::Rationals, {".rat", &rat_files}},  {Kind::Domain, {".txt", &domain_files}},
      {Kind::Surface, {".off", &surface_files}}, {Kind::Results, {"", &results_files}},
      {Kind::Bundle, {".js", &bundle_files}}};
  std::map<Kind, std::vector<Variant>> variants;
  for (const auto& [kind, spec] : kinds) variants[kind] = input_variants(s, kind, spec.first, g, *spec.second);

  // FIFOs, device links and a read-only folder as output targets live in dev/ (checked unchanged).
  REQUIRE(mkfifo((s.dev / "fifo.mesh").c_str(), 0644) == 0);
  REQUIRE(mkfifo((s.dev / "fifo.txt").c_str(), 0644) == 0);
  volmap_test::output_device_target(s.dev / "null.mesh");
  volmap_test::output_device_target(s.dev / "null.txt");
  fs::create_directories(s.dev / "dir.mesh");
  fs::create_directories(s.dev / "dir.txt");
  volmap_test::write_bytes(s.dev / "file.txt", "a regular file\n");

  for (const Invocation& inv : invocations(g)) {
    if (!s.control(inv)) continue;
    std::vector<std::string> input_paths, output_keys;
    for (const Slot& slot : inv.slots)
      if (is_output(slot.kind)) output_keys.push_back(slot.key);
      else if (slot.good != "-" && fs::exists(slot.good)) input_paths.push_back(slot.good);
    for (const Slot& slot : inv.slots) {
      if (slot.good == "-" || !slot.vary) continue;
      if (!is_output(slot.kind)) {
        for (Variant v : variants[slot.kind]) {
          // A format tool or a viewer copies or shows invalid meshes (volmap-tetmesh-check judges them).
          if (slot.kind == Kind::ViewMesh && v.cls == "validity") v.codes = {0}, v.accepted = true;
          // volmap-tetmesh-check reports (exit 1, the --log line written); --fix repairs the inverted mesh.
          if (inv.tool == "volmap-tetmesh-check" && v.cls == "validity")
            v.codes = {v.what.find("all_inverted") != std::string::npos ? 0 : 1}, v.accepted = true;
          if (inv.tool == "volmap-surface-map-check" && v.what.rfind("m_", 0) == 0) v.codes = {1, 2};
          if (inv.tool == "volmap-view" && slot.kind == Kind::ViewMesh && v.what.find("v_no_tets") != std::string::npos)
            v.codes = {2}, v.accepted = false;
          s.run_case(inv, slot.key, v);
        }
        continue;
      }
      // Output paths.
      if (slot.kind == Kind::OutDir) {  // a folder output: never a FIFO, a device or a file
        for (const char* target : {"fifo.txt", "null.txt", "file.txt"})
          s.run_case(inv, slot.key, {"devices", std::string("a folder output that is ") + target, (s.dev / target).string(), target, {2}});
        s.run_case(inv, slot.key, {"paths", "a folder through a file", g.mesh + "/x", "good.mesh/x", {2}});
        continue;
      }
      const std::string ext = slot.kind == Kind::OutMesh ? ".mesh" : slot.kind == Kind::OutVtu ? ".vtu" : ".txt";
      std::vector<Variant> outs;
      for (const std::string& input : input_paths)
        outs.push_back({"paths", "an input (" + fs::path(input).filename().string() + ")", input,
                        fs::path(input).filename().string(), {2}});
      for (const Slot& other : inv.slots)
        if (is_output(other.kind) && other.key != slot.key)
          outs.push_back({"partial multi-output", "the same file as " + other.key, (s.out / other.good).string(), other.good, {2}});
      const std::string dev_ext = slot.kind == Kind::OutFile ? ".txt" : ".mesh";
      outs.push_back({"devices", "a FIFO", (s.dev / ("fifo" + dev_ext)).string(), "fifo" + dev_ext, {2}});
      outs.push_back({"devices", "/dev/null", (s.dev / ("null" + dev_ext)).string(), "null" + dev_ext, {2}});
      outs.push_back({"paths", "a directory", (s.dev / ("dir" + dev_ext)).string(), "dir" + dev_ext, {2}});
      outs.push_back({"partial multi-output", "a missing folder", (s.root / "no" / "such" / ("x" + ext)).string(), "no/such", {2}});
      outs.push_back({"partial multi-output", "a path through a file", g.mesh + "/x" + ext, "good.mesh/x", {2}});
      if (slot.kind != Kind::OutFile) {
        outs.push_back({"extensions", "extension .txt", (s.out / "x.txt").string(), "x.txt", {2}});
        outs.push_back({"extensions", "no extension", (s.out / "x").string(), "x", {2}});
      }
      if (slot.kind == Kind::OutMesh)
        for (const char* e : {".vtk", ".vtu", ".MESH"})
          outs.push_back({"extensions", std::string("extension ") + e, (s.out / (std::string("x") + e)).string(), "", {0}, true});
      for (const Variant& v : outs) s.run_case(inv, slot.key, v);
    }
    // Options.
    for (const std::string& option : inv.numeric_options)
      for (const std::string bad : {"nan", "inf", "-1", "abc"})
        s.run_case(inv, "", {"options", option + " " + bad, "", option, {2}}, {option, bad});
    // Signals (tools that write).
    if (!output_keys.empty())
      for (const auto& [sig, delay] : std::vector<std::pair<int, int>>{{SIGTERM, 5}, {SIGINT, 30}, {SIGTERM, 80}})
        s.signal_case(inv, sig, delay);
  }

  // Counts: printed and recorded for the closing note.
  std::ostringstream summary;
  Counts total;
  for (const auto& [cls, c] : s.by_class) {
    summary << cls << ": tried " << c.tried << ", clean " << c.clean << ", defects " << c.defects << "\n";
    total.tried += c.tried, total.clean += c.clean, total.defects += c.defects;
  }
  summary << "total: tried " << total.tried << ", clean " << total.clean << ", defects " << total.defects << "\n";
  std::ofstream((fs::path(VOLMAP_BIN_DIR).parent_path() / "bad_input_suite.txt").string()) << summary.str();
  std::cout << "bad-input suite\n" << summary.str();
  MESSAGE(summary.str());
  for (const auto& f : s.failures) MESSAGE(f);
  CHECK(s.failures.empty());
  CHECK(total.tried > 500);
}
