// Gmsh .msh and OpenVolumeMesh .ovm through the tools: volmap-convert round-trips .mesh -> .msh ->
// .mesh byte for byte (ASCII and binary), reports skipped elements and dropped nodes (stderr, or
// "input_notes" with --json) and says in words which orientation convention the tets are in;
// volmap-tetmesh-check does the same and --fix flips Gmsh/OVM meshes; meshio (a third-party reader
// and writer) reads what we write and writes what we read, bit-exactly.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <volmap/io/io.hpp>

#include "mesh_compare.hpp"
#include "meshio_support.hpp"
#include "msh_fixtures.hpp"
#include "test_support.hpp"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

using namespace volmap;
namespace fs = std::filesystem;

namespace {

fs::path scratch() { return volmap_test::scratch_dir("formats_tools"); }
std::string shell_quote(const fs::path& p) { return "'" + p.string() + "'"; }
struct Run {
  int code = -1;
  std::string out, err;
};
Run run(const std::string& command) {
  const fs::path out = scratch() / "stdout.txt", err = scratch() / "stderr.txt";
  const int status = std::system((command + " > " + shell_quote(out) + " 2> " + shell_quote(err)).c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, volmap_test::read_bytes(out), volmap_test::read_bytes(err)};
}
bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }
using volmap_test::same_bits;

const char* const kOppositeTwo =
    "all 2 tets are in the opposite orientation convention (orient3d < 0, as Gmsh and OpenVolumeMesh order them)";

}  // namespace

TEST_CASE("volmap-convert: .mesh -> .msh -> .mesh is byte-identical (ASCII and --binary)") {
  const fs::path tool = volmap_test::tool("volmap-convert");
  VOLMAP_REQUIRE_DATA(bone, "volmap/G1/bone.mesh");
  const fs::path d = scratch();
  write_medit((d / "bone_ref.mesh").string(), read_medit(bone.string()));
  for (const char* flag : {"", " --binary"}) {
    CAPTURE(flag);
    Run r = run(shell_quote(tool) + " " + shell_quote(bone) + " " + shell_quote(d / "b.msh") + flag + " --json");
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["output_format"] == "msh");
    CHECK(j["orientation"]["class"] == "positive");
    CHECK(j["orientation"]["summary"] == "all 8,629 tets are in the VOLMAP orientation convention (orient3d > 0)");
    CHECK_FALSE(j.contains("input_notes"));
    CHECK(volmap_test::read_bytes(d / "b.msh").rfind(std::strlen(flag) ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n4.1 0 8\n", 0) == 0);
    r = run(shell_quote(tool) + " " + shell_quote(d / "b.msh") + " " + shell_quote(d / "b.mesh"));
    REQUIRE(r.code == 0);
    CHECK(volmap_test::read_bytes(d / "b.mesh") == volmap_test::read_bytes(d / "bone_ref.mesh"));
  }
}

TEST_CASE("volmap-convert: Gmsh notes and the orientation sentence, on stderr/stdout and in --json") {
  const fs::path tool = volmap_test::tool("volmap-convert");
  const fs::path d = scratch();
  const std::string in = volmap_test::write_bytes(d / "mixed.msh", volmap_test::msh_fixture({}));
  Run r = run(shell_quote(tool) + " " + shell_quote(in) + " " + shell_quote(d / "mixed.mesh") + " --json");
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["input_format"] == "msh");
  CHECK(j["vertices"] == 5);
  CHECK(j["tets"] == 2);
  CHECK(j["orientation"]["class"] == "coherently_opposite");
  CHECK(j["orientation"]["summary"] == std::string(kOppositeTwo) + "; volmap-tetmesh-check --fix flips them");
  const auto& notes = j["input_notes"][in];
  CHECK(notes["format"] == "msh");
  CHECK(notes["ignored_elements"] == nlohmann::json{{"point", 1}, {"line", 1}, {"triangle", 2}});
  CHECK(notes["dropped_vertices"] == 1);
  CHECK(notes["renumbered"] == true);
  CHECK(notes["messages"].size() == 2);
  // Without --json: the notes on stderr, naming the tool and the file; the sentence on stdout.
  r = run(shell_quote(tool) + " " + shell_quote(in) + " " + shell_quote(d / "mixed2.msh"));
  REQUIRE(r.code == 0);
  CHECK(contains(r.err, "volmap-convert: note: " + in + ": skipped 1 point, 1 line and 2 triangles (only tetrahedra are read)"));
  CHECK(contains(r.err, "volmap-convert: note: " + in + ": dropped 1 node that no tetrahedron uses"));
  CHECK(contains(r.out, kOppositeTwo));
  // What we wrote holds only what was kept: reading it back notes nothing.
  TetMeshReadNotes again;
  read_tet_mesh((d / "mixed2.msh").string(), again);
  CHECK(again.empty());
  // .ovm is read-only; a truncated .msh is refused naming file and line; nothing is written.
  CHECK(run(shell_quote(tool) + " " + shell_quote(in) + " " + shell_quote(d / "x.ovm")).code == 2);
  CHECK_FALSE(fs::exists(d / "x.ovm"));
  const std::string cut = volmap_test::msh_fixture({});
  volmap_test::write_bytes(d / "cut.msh", cut.substr(0, cut.find("$EndNodes") - 3));
  r = run(shell_quote(tool) + " " + shell_quote(d / "cut.msh") + " " + shell_quote(d / "cut.mesh"));
  CHECK(r.code == 2);
  CHECK(contains(r.err, (d / "cut.msh").string() + ":"));
  CHECK_FALSE(fs::exists(d / "cut.mesh"));
}

TEST_CASE("volmap-tetmesh-check: .msh and .ovm inputs, the orientation in words, --fix to the VOLMAP convention") {
  const fs::path tool = volmap_test::tool("volmap-tetmesh-check");
  const fs::path d = scratch();
  const std::string in = volmap_test::write_bytes(d / "check.msh", volmap_test::msh_fixture({41, true, true, 8, true}));
  Run r = run(shell_quote(tool) + " " + shell_quote(in));
  CHECK(r.code == 1);
  CHECK(contains(r.out, std::string("orientation         FAILED  ") + kOppositeTwo + "; --fix flips them"));
  CHECK(contains(r.err, "volmap-tetmesh-check: note: " + in + ": skipped"));
  r = run(shell_quote(tool) + " " + shell_quote(in) + " --json --fix " + shell_quote(d / "fixed.msh"));
  CHECK(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["report"]["orientation"]["class"] == "coherently_opposite");
  CHECK(j["report"]["orientation"]["summary"] == std::string(kOppositeTwo) + "; --fix flips them");
  CHECK(j["input_notes"][in]["dropped_vertices"] == 1);
  CHECK(j["fix"]["written"] == true);
  CHECK(j["fix"]["report"]["orientation"]["class"] == "positive");
  const TetMeshData fixed = read_msh((d / "fixed.msh").string());
  CHECK(fixed.tets == std::vector<std::uint32_t>{1, 0, 2, 3, 2, 1, 3, 4});
  CHECK(fixed.tet_labels == std::vector<std::int32_t>{11, 12});

  VOLMAP_REQUIRE_DATA(ovm, "maps/expansion_cones/prism_domain.ovm");
  r = run(shell_quote(tool) + " " + shell_quote(ovm));
  CHECK(r.code == 1);
  CHECK(contains(r.out, "all 619 tets are in the opposite orientation convention"));
  CHECK(r.err.empty());
  CHECK(run(shell_quote(tool) + " " + shell_quote(ovm) + " --fix " + shell_quote(d / "prism.mesh")).code == 0);
}

TEST_CASE("third-party: meshio reads our .msh (ASCII and binary) with labels; we read meshio's .msh bit-exactly") {
  const std::string py = volmap_test::meshio_python();
  if (py.empty()) {
    MESSAGE("skipped: Python meshio not available");
    return;
  }
  VOLMAP_REQUIRE_DATA(bone, "volmap/G1/bone.mesh");
  TetMeshData m = read_medit(bone.string());
  for (std::size_t t = 0; t < m.num_tets(); ++t) m.tet_labels[t] = t < m.num_tets() / 2 ? 4 : 7;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) m.vertex_labels[v] = static_cast<std::int32_t>(v % 5);
  const fs::path d = scratch();
  write_msh((d / "ours_a.msh").string(), m, MshEncoding::Ascii);
  write_msh((d / "ours_b.msh").string(), m, MshEncoding::Binary);
  long long expected_sum = 0;
  for (std::int32_t l : m.vertex_labels) expected_sum += l;
  for (const char* name : {"ours_a.msh", "ours_b.msh"}) {
    CAPTURE(name);
    volmap_test::MeshioSummary s;
    REQUIRE(volmap_test::meshio_summary(py, d.string(), (d / name).string(), s));
    volmap_test::check_meshio_summary(s, m);
    CHECK(s.first_physical == 4);
    CHECK(s.last_physical == 7);
    CHECK(s.label_sum == expected_sum);
  }
  // meshio writes MSH 2.2 and 4.1, ASCII and binary (17 significant digits in ASCII): read exactly.
  write_vtu((d / "src.vtu").string(), m);
  const std::string writer =
      "import sys, meshio\n"
      "m = meshio.read(sys.argv[1])\n"
      "d = sys.argv[2]\n"
      "for fmt, name in (('gmsh22', 'mio22'), ('gmsh', 'mio41')):\n"
      "    meshio.write(d + '/' + name + 'a.msh', m, file_format=fmt, binary=False)\n"
      "    meshio.write(d + '/' + name + 'b.msh', m, file_format=fmt, binary=True)\n";
  { std::ofstream(d / "write.py") << writer; }
  REQUIRE(run(py + " " + shell_quote(d / "write.py") + " " + shell_quote(d / "src.vtu") + " " + shell_quote(d)).code == 0);
  for (const char* name : {"mio22a.msh", "mio22b.msh", "mio41a.msh", "mio41b.msh"}) {
    CAPTURE(name);
    TetMeshReadNotes notes;
    const TetMeshData r = read_tet_mesh((d / name).string(), notes);
    CHECK(same_bits(r.xyz, m.xyz));
    CHECK(r.tets == m.tets);
    CHECK(notes.dropped_vertices == 0);
    CHECK(notes.ignored_elements.empty());
  }
}
