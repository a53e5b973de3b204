// Gmsh .msh: generated fixtures (msh_fixtures.hpp) of every version/encoding/byte order read to the
// same mesh, with skipped elements, dropped nodes and labels reported; write_msh round-trips bit
// exactly (labels, order, doubles) and .mesh -> .msh -> .mesh is byte-identical on a G1 mesh;
// truncated and corrupt files throw volmap::Error naming file and line (never crash, never allocate
// what the file cannot hold); the orientation sentence says Gmsh's tets are in the opposite convention.
#include <doctest/doctest.h>
#include <volmap/check/orientation.hpp>
#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>

#include "msh_fixtures.hpp"
#include "mesh_compare.hpp"
#include "test_support.hpp"

#include <cstring>
#include <filesystem>

using namespace volmap;
namespace fs = std::filesystem;
using volmap_test::MshFixture;

namespace {

fs::path scratch() { return volmap_test::scratch_dir("io_msh"); }
std::string put(const std::string& name, const std::string& bytes) { return volmap_test::write_bytes(scratch() / name, bytes); }

using volmap_test::same_bits;
void check_same(const TetMeshData& a, const TetMeshData& b) { volmap_test::check_same_mesh(a, b); }

// The error read_msh throws on `bytes` (kind and message), or fails the test when none is thrown.
Error msh_error(const std::string& bytes, const std::string& name = "bad.msh") {
  const std::string path = put(name, bytes);
  try {
    read_msh(path);
  } catch (const Error& e) {
    return e;
  }
  FAIL("accepted: " << name);
  return Error(ErrorKind::BadInput, "", 0, "");
}
bool mentions(const Error& e, const std::string& what) { return std::string(e.what()).find(what) != std::string::npos; }

const MshFixture kAllFixtures[] = {
    {22, false, false, 8, true}, {22, true, false, 8, true}, {22, true, true, 8, true},  {41, false, false, 8, true},
    {41, true, false, 8, true},  {41, true, true, 8, true},  {41, true, false, 4, true}, {41, true, true, 4, true}};

std::string fixture_name(const MshFixture& f) {
  return "v" + std::to_string(f.version) + (f.binary ? (f.big_endian ? "_be" : "_le") : "_ascii") +
         (f.version == 41 ? "_ds" + std::to_string(f.size_bytes) : "") + (f.physicals ? "" : "_nophys") + ".msh";
}

TetMeshData small_labelled_mesh() {
  // Two cubes' worth of tets would do; five tets over seven vertices are enough to exercise runs of
  // labels (0 5 5 0 -3), negative labels, vertex labels and doubles that need 17 digits.
  TetMeshData m;
  m.xyz = {0.1, 0.2, 0.3, 1.0 / 3.0, 0, 0, 0, 2.0 / 3.0, 0, 0, 0, 1e-300, 1, 1, 1, -7.5e12, 3, 4, 0.5, 0.5, 0.5};
  m.vertex_labels = {0, 4, 0, -2, 0, 9, 1};
  m.tets = {0, 1, 2, 3, 1, 2, 3, 4, 2, 3, 4, 5, 3, 4, 5, 6, 0, 2, 4, 6};
  m.tet_labels = {0, 5, 5, 0, -3};
  return m;
}

}  // namespace

TEST_CASE("msh: every version, encoding and byte order reads the same mixed mesh") {
  const TetMeshData expected = volmap_test::msh_fixture_expected();
  for (const MshFixture& f : kAllFixtures) {
    const std::string name = fixture_name(f);
    CAPTURE(name);
    TetMeshReadNotes notes;
    const TetMeshData m = read_tet_mesh(put(name, volmap_test::msh_fixture(f)), notes);
    check_same(m, expected);
    CHECK(notes.format == "msh");
    REQUIRE(notes.ignored_elements.size() == 3);
    CHECK(notes.ignored_elements[0].type == "point");
    CHECK(notes.ignored_elements[0].count == 1);
    CHECK(notes.ignored_elements[1].type == "line");
    CHECK(notes.ignored_elements[1].count == 1);
    CHECK(notes.ignored_elements[2].type == "triangle");
    CHECK(notes.ignored_elements[2].code == 2);
    CHECK(notes.ignored_elements[2].count == 2);
    CHECK(notes.dropped_vertices == 1);  // node 7 is used by a line only
    CHECK(notes.source_vertex_ids == std::vector<std::uint64_t>{3, 1, 2, 5, 9});
    REQUIRE(notes.messages.size() == 2);
    CHECK(notes.messages[0] == "skipped 1 point, 1 line and 2 triangles (only tetrahedra are read)");
    CHECK(notes.messages[1].find("dropped 1 node that no tetrahedron uses") == 0);
  }
}

TEST_CASE("msh: without physical tags, the volume entity tags become labels (and the reader says so)") {
  for (int version : {22, 41}) {
    CAPTURE(version);
    MshFixture f;
    f.version = version;
    f.physicals = false;
    TetMeshReadNotes notes;
    const TetMeshData m = read_tet_mesh(put(fixture_name(f), volmap_test::msh_fixture(f)), notes);
    check_same(m, volmap_test::msh_fixture_expected(false));
    CHECK(notes.messages.back() == "no tet has a physical tag: labels are the 2 volume entity tags");
  }
}

TEST_CASE("msh: the orientation sentence says Gmsh's tets are in the opposite convention; --fix makes them pass") {
  TetMeshData m = read_msh(put("orient.msh", volmap_test::msh_fixture({})));
  const TetMeshCheckReport r = check_tet_mesh(m);
  CHECK(r.orientation == OrientationClass::CoherentlyOpposite);
  CHECK(r.check("orientation").detail ==
        "all 2 tets are in the opposite orientation convention (orient3d < 0, as Gmsh and OpenVolumeMesh order them); "
        "--fix flips them");
  flip_all_tets(m);
  CHECK(check_tet_mesh(m).check("orientation").detail == "all 2 tets are in the VOLMAP orientation convention (orient3d > 0)");
}

TEST_CASE("orientation sentences: every class, grouped digits, zero-volume tets") {
  auto counts = [](std::size_t p, std::size_t z, std::size_t n) {
    TetSignCounts s;
    s.positive = p, s.zero = z, s.negative = n;
    return s;
  };
  CHECK(describe_orientation(counts(0, 0, 6059)) ==
        "all 6,059 tets are in the opposite orientation convention (orient3d < 0, as Gmsh and OpenVolumeMesh order "
        "them); volmap-tetmesh-check --fix flips them");
  CHECK(describe_orientation(counts(0, 9, 6050), "--fix") ==
        "6,050 of 6,059 tets are in the opposite orientation convention (orient3d < 0, as Gmsh and OpenVolumeMesh "
        "order them) and 9 have zero volume; --fix flips them");
  CHECK(describe_orientation(counts(1234567, 0, 0)) == "all 1,234,567 tets are in the VOLMAP orientation convention (orient3d > 0)");
  CHECK(describe_orientation(counts(1, 0, 0)) == "the one tet is in the VOLMAP orientation convention (orient3d > 0)");
  CHECK(describe_orientation(counts(0, 0, 1), "--fix") ==
        "the one tet is in the opposite orientation convention (orient3d < 0, as Gmsh and OpenVolumeMesh order them); "
        "--fix flips it");
  CHECK(describe_orientation(counts(120, 0, 6000)) ==
        "orientation is mixed: 120 of 6,120 tets are in the VOLMAP convention (orient3d > 0) and 6,000 in the opposite "
        "one; no global flip fixes that");
  CHECK(describe_orientation(counts(0, 3, 0)) == "all 3 tets have zero volume");
  CHECK(describe_orientation(counts(0, 0, 0)) == "the mesh has no tets");
  CHECK(classify_orientation(counts(0, 1, 5)) == OrientationClass::CoherentlyOpposite);
  CHECK(classify_orientation(counts(2, 1, 5)) == OrientationClass::Mixed);
}

TEST_CASE("msh: write_msh (ASCII and binary) reads back bit-exactly, labels and order included") {
  const TetMeshData m = small_labelled_mesh();
  for (MshEncoding enc : {MshEncoding::Ascii, MshEncoding::Binary}) {
    const std::string path = (scratch() / (enc == MshEncoding::Ascii ? "rt_ascii.msh" : "rt_binary.msh")).string();
    write_msh(path, m, enc);
    TetMeshReadNotes notes;
    const TetMeshData back = read_tet_mesh(path, notes);
    check_same(back, m);
    CHECK(notes.format == "msh");
    CHECK(notes.empty());  // nothing skipped, dropped or renumbered
  }
  // Layout the docs promise: 3 volume entities (labels 0, 5, -3), 4 element blocks (runs 0 | 5 5 | 0 | -3).
  write_msh((scratch() / "layout.msh").string(), m);
  const std::string text = volmap_test::read_bytes(scratch() / "layout.msh");
  CHECK(text.find("$Entities\n0 0 0 3\n") != std::string::npos);
  CHECK(text.find("$Elements\n4 5 1 5\n") != std::string::npos);
  CHECK(text.find("$NodeData\n1\n\"label\"\n") != std::string::npos);
  // All-zero labels: no physical tags and no $NodeData.
  TetMeshData plain = m;
  plain.vertex_labels.assign(plain.vertex_labels.size(), 0);
  plain.tet_labels.assign(plain.tet_labels.size(), 0);
  write_msh((scratch() / "plain.msh").string(), plain);
  const std::string plain_text = volmap_test::read_bytes(scratch() / "plain.msh");
  CHECK(plain_text.find("$NodeData") == std::string::npos);
  check_same(read_msh((scratch() / "plain.msh").string()), plain);
}

TEST_CASE("msh: .mesh -> .msh -> .mesh is byte-identical on a G1 mesh (ASCII and binary)") {
  VOLMAP_REQUIRE_DATA(bone, "volmap/G1/bone.mesh");
  const TetMeshData m = read_medit(bone.string());
  write_medit((scratch() / "bone_ref.mesh").string(), m);
  for (MshEncoding enc : {MshEncoding::Ascii, MshEncoding::Binary}) {
    write_msh((scratch() / "bone.msh").string(), m, enc);
    write_medit((scratch() / "bone_back.mesh").string(), read_msh((scratch() / "bone.msh").string()));
    CHECK(volmap_test::read_bytes(scratch() / "bone_back.mesh") == volmap_test::read_bytes(scratch() / "bone_ref.mesh"));
  }
}

TEST_CASE("msh: every truncation of every fixture throws volmap::Error, never crashes") {
  for (const MshFixture& f : kAllFixtures) {
    const std::string bytes = volmap_test::msh_fixture(f);
    const std::string name = fixture_name(f);
    CAPTURE(name);
    std::size_t thrown = 0;
    for (std::size_t n = 0; n + 1 < bytes.size(); ++n) {
      try {
        read_msh(put("cut.msh", bytes.substr(0, n)));
      } catch (const Error& e) {
        ++thrown;
        CHECK(e.file().find("cut.msh") != std::string::npos);
      }
    }
    CHECK(thrown == bytes.size() - 1);
  }
}

TEST_CASE("msh: corrupt files are refused with a clear reason and line") {
  const std::string v22 = volmap_test::msh_fixture({22, false, false, 8, true});
  SUBCASE("not a msh file, unsupported versions and encodings") {
    CHECK(mentions(msh_error(""), "empty file"));
    CHECK(mentions(msh_error("solid x\n"), "expected $MeshFormat"));
    CHECK(msh_error("$NOD\n1\n1 0 0 0\n$ENDNOD\n").kind() == ErrorKind::Unsupported);
    const Error v40 = msh_error("$MeshFormat\n4 0 8\n$EndMeshFormat\n");
    CHECK(v40.kind() == ErrorKind::Unsupported);
    CHECK(mentions(v40, "MSH version '4'"));
    CHECK(mentions(msh_error("$MeshFormat\n2.2 2 8\n$EndMeshFormat\n"), "file type 2"));
    CHECK(msh_error("$MeshFormat\n2.2 0 4\n$EndMeshFormat\n").kind() == ErrorKind::Unsupported);
    const char marker[] = "$MeshFormat\n2.2 1 8\n\x02\0\0\0\n$EndMeshFormat\n";
    CHECK(mentions(msh_error(std::string(marker, sizeof marker - 1)), "endianness marker"));
  }
  SUBCASE("counts larger than the file are refused before allocating") {
    const Error e = msh_error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n900000000\n1 0 0 0\n$EndNodes\n");
    CHECK(mentions(e, "cannot fit"));
    CHECK(e.line() == 5);
    std::string huge = volmap_test::msh_fixture({41, true, false, 8, true});
    const std::size_t at = huge.find("$Nodes\n") + 7 + 8;  // the total node count, after numEntityBlocks
    for (int k = 0; k < 8; ++k) huge[at + k] = k == 7 ? '\x7f' : '\xff';
    CHECK(mentions(msh_error(huge), "number of nodes"));
    std::string blocks = volmap_test::msh_fixture({41, true, false, 8, true});
    blocks[blocks.find("$Elements\n") + 10 + 3] = '\x40';  // numEntityBlocks = 2^30
    CHECK(mentions(msh_error(blocks), "cannot fit"));
  }
  SUBCASE("wrong counts, bad numbers, unknown nodes, duplicate tags") {
    std::string bad = v22;
    bad.replace(bad.find("$Nodes\n6\n"), 9, "$Nodes\n5\n");
    const Error count = msh_error(bad);
    CHECK(mentions(count, "expected $EndNodes"));
    bad = v22;
    bad.replace(bad.find("\n1 1 0 0\n"), 9, "\n1 1 zero 0\n");
    const Error number = msh_error(bad);
    CHECK(mentions(number, "'zero'"));
    CHECK(number.line() == 15);  // node tag 1's line: after 3 format, 3 comment, 5 names and 3 node lines
    bad = v22;
    bad.replace(bad.find("6 4 2 12 2 1 2 5 9"), 18, "6 4 2 12 2 1 2 5 8");
    const Error unknown = msh_error(bad);
    CHECK(mentions(unknown, "node tag 8, which $Nodes does not define"));
    CHECK(unknown.line() == 28);
    bad = v22;
    bad.replace(bad.find("\n9 "), 3, "\n5 ");
    CHECK(mentions(msh_error(bad), "node tag 5 is defined twice"));
    bad = v22;
    bad.replace(bad.find("$EndElements"), 12, "$EndElemenz");
    CHECK(mentions(msh_error(bad), "expected $EndElements"));
    CHECK(mentions(msh_error(v22 + "$NodeData\n1\n\"x\"\n"), "unexpected end of file: expected number of real tags"));
    CHECK(mentions(msh_error(v22 + "$NodeData\n1\n\"x\"\n1\n0\n3\n0\n1\n1\n1 5\n"), "section $NodeData has no $EndNodeData"));
  }
  SUBCASE("3D elements other than linear tets are refused; surfaces alone are not tet meshes") {
    std::string hex = v22;
    hex.replace(hex.find("5 4 2 11 1 3 1 2 5"), 18, "5 5 2 11 1 3 1 2 5 9 9 9 9");
    const Error h = msh_error(hex);
    CHECK(h.kind() == ErrorKind::Unsupported);
    CHECK(mentions(h, "element type 5 (hexahedron)"));
    std::string tet10 = v22;
    tet10.replace(tet10.find("5 4 2 11 1 3 1 2 5"), 18, "5 11 2 11 1 3 1 2 5 9 9 9 9 9 9");
    CHECK(mentions(msh_error(tet10), "tetrahedron (10-node)"));
    std::string unknown = v22;
    unknown.replace(unknown.find("5 4 2 11 1 3 1 2 5"), 18, "5 999 2 11 1 3 1 2 5");
    CHECK(mentions(msh_error(unknown), "unknown Gmsh element type 999"));
    const std::string surface =
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n";
    const Error s = msh_error(surface);
    CHECK(s.kind() == ErrorKind::Unsupported);
    CHECK(mentions(s, "no linear tetrahedra (element type 4): the file holds 1 triangle only"));
    CHECK(mentions(msh_error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n0\n$EndElements\n"), "$Elements before $Nodes"));
  }
}
