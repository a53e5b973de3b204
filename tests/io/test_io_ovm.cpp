// OpenVolumeMesh .ovm: a hand-built tet whose half-faces all point into the cell reads in
// OpenVolumeMesh's vertex order (first half-face, then the apex; reversed half-faces included) and
// comes out orient3d < 0; polyhedral cells are refused naming the cell; broken topology, truncations
// and binary headers throw volmap::Error. On the Expansion Cones inputs: the README's counts, every
// tet in the opposite convention, all seven checks pass after a flip, and every *_boundary.txt lists
// exactly the boundary vertices of its .ovm (vertex ids = .ovm vertex indices).
#include <doctest/doctest.h>
#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>

#include "test_support.hpp"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

using namespace volmap;
namespace fs = std::filesystem;

namespace {

fs::path scratch() { return volmap_test::scratch_dir("io_ovm"); }
std::string put(const std::string& name, const std::string& text) { return volmap_test::write_bytes(scratch() / name, text); }

// The unit tet (0,0,0) (1,0,0) (0,1,0) (0,0,1); edges listed once; each face given as a vertex loop,
// written either as listed (half-face 2f) or reversed in the file (then the cell uses 2f+1).
struct OvmTet {
  std::vector<std::array<std::uint32_t, 2>> edges{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  std::uint32_t half_edge(std::uint32_t a, std::uint32_t b) const {
    for (std::uint32_t e = 0; e < edges.size(); ++e) {
      if (edges[e][0] == a && edges[e][1] == b) return 2 * e;
      if (edges[e][0] == b && edges[e][1] == a) return 2 * e + 1;
    }
    return 999;
  }
  // faces: inward loops; `reversed[f]` stores face f reversed in the file.
  std::string text(const std::vector<std::array<std::uint32_t, 3>>& inward, const std::vector<bool>& reversed,
                   const std::string& cell_line = "", const std::string& after = "") const {
    std::string s = "OVM ASCII\n# a comment\nVertices\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nEdges\n6\n";
    for (const auto& e : edges) s += std::to_string(e[0]) + " " + std::to_string(e[1]) + "\n";
    s += "Faces\n" + std::to_string(inward.size()) + "\n";
    std::string cell = "4";
    for (std::size_t f = 0; f < inward.size(); ++f) {
      auto loop = inward[f];
      if (reversed[f]) std::swap(loop[1], loop[2]);
      s += "3";
      for (int i = 0; i < 3; ++i) s += " " + std::to_string(half_edge(loop[i], loop[(i + 1) % 3]));
      s += "\n";
      cell += " " + std::to_string(2 * f + (reversed[f] ? 1 : 0));
    }
    s += "Polyhedra\n1\n" + (cell_line.empty() ? cell : cell_line) + "\n" + after;
    return s;
  }
};
// Inward loops of the unit tet (right-hand normals pointing into the cell).
const std::vector<std::array<std::uint32_t, 3>> kInward{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};

Error ovm_error(const std::string& text) {
  try {
    read_ovm(put("bad.ovm", text));
  } catch (const Error& e) {
    return e;
  }
  FAIL("accepted");
  return Error(ErrorKind::BadInput, "", 0, "");
}
bool mentions(const Error& e, const std::string& what) { return std::string(e.what()).find(what) != std::string::npos; }

}  // namespace

TEST_CASE("ovm: a tet cell reads in OpenVolumeMesh order (first half-face, then apex) and is orient3d < 0") {
  const OvmTet tet;
  // As listed: first half-face 0 = loop (0 1 2), apex 3.
  const TetMeshData a = read_tet_mesh(put("a.ovm", tet.text(kInward, {false, false, false, false}, "", "VProp int \"x\"\n0\n0\n0\n0\n")));
  CHECK(a.num_vertices() == 4);
  CHECK(a.xyz == std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
  CHECK(a.tets == std::vector<std::uint32_t>{0, 1, 2, 3});
  CHECK(a.tet_labels == std::vector<std::int32_t>{0});
  CHECK(orient3d(&a.xyz[0], &a.xyz[3], &a.xyz[6], &a.xyz[9]) < 0);
  // Face 0 stored reversed (0 2 1): the cell's half-face 1 runs it backwards, from the file's first
  // vertex: (0 1 2) again. Face 3 stored reversed too (the cell order only depends on the first face).
  const TetMeshData b = read_ovm(put("b.ovm", tet.text(kInward, {true, false, false, true})));
  CHECK(b.tets == std::vector<std::uint32_t>{0, 1, 2, 3});
  // Cell listing another face first: (0 3 1) then apex 2.
  const std::vector<std::array<std::uint32_t, 3>> rotated{{0, 3, 1}, {0, 1, 2}, {0, 2, 3}, {1, 3, 2}};
  const TetMeshData c = read_ovm(put("c.ovm", tet.text(rotated, {false, false, false, false})));
  CHECK(c.tets == std::vector<std::uint32_t>{0, 3, 1, 2});
  CHECK(orient3d(&c.xyz[0], &c.xyz[9], &c.xyz[3], &c.xyz[6]) < 0);
  const TetMeshCheckReport r = check_tet_mesh(c);
  CHECK(r.orientation == OrientationClass::CoherentlyOpposite);
  CHECK(r.check("orientation").detail.find("the one tet is in the opposite orientation convention") == 0);
}

TEST_CASE("ovm: polyhedral cells are refused naming the cell; broken cells and files throw volmap::Error") {
  const OvmTet tet;
  const std::vector<bool> plain{false, false, false, false};
  const Error five = ovm_error(tet.text(kInward, plain, "5 0 2 4 6 1"));
  CHECK(five.kind() == ErrorKind::Unsupported);
  CHECK(mentions(five, "cell 0 has 5 faces: only tetrahedral cells are supported"));
  // A quad face (0 1 3 2 is not planar here, but topology is what the reader judges).
  OvmTet quad;
  std::string text = quad.text(kInward, plain);
  text.replace(text.find("Faces\n4\n"), 8, "Faces\n5\n");
  text.replace(text.find("Polyhedra"), 9, "4 0 8 11 5\nPolyhedra");
  text.replace(text.find("Polyhedra\n1\n4 0 2 4 6"), 21, "Polyhedra\n1\n4 8 2 4 6");
  const Error q = ovm_error(text);
  CHECK(q.kind() == ErrorKind::Unsupported);
  CHECK(mentions(q, "cell 0 has a face with 4 edges (face 4)"));
  // The same half-face twice: not a closed tet.
  const Error open = ovm_error(tet.text(kInward, plain, "4 0 0 4 6"));
  CHECK(open.kind() == ErrorKind::BadInput);
  CHECK(mentions(open, "cell 0 is not a tetrahedron"));
  // Face 1 used backwards: its edges run the same way as face 0's.
  CHECK(mentions(ovm_error(tet.text(kInward, plain, "4 0 3 4 6")), "consistently oriented"));
  // Half-edges that do not chain.
  std::string chain = tet.text(kInward, plain);
  chain.replace(chain.find("Faces\n4\n3 0 2 5"), 15, "Faces\n4\n3 0 5 2");
  CHECK(mentions(ovm_error(chain), "face 0: its half-edges do not form a closed loop"));
  CHECK(mentions(ovm_error(tet.text(kInward, plain, "4 0 2 4 99")), "half-face id 99 outside [0,8)"));
  CHECK(ovm_error("OVM BINARY\n").kind() == ErrorKind::Unsupported);
  CHECK(mentions(ovm_error("ply\n"), "expected the header `OVM ASCII`"));
  CHECK(mentions(ovm_error(tet.text(kInward, plain, "", "garbage\n")), "unexpected 'garbage' after the Polyhedra"));
  const Error big = ovm_error("OVM ASCII\nVertices\n999999999\n0 0 0\n");
  CHECK(mentions(big, "cannot fit"));
  CHECK(big.line() == 3);
  // Every truncation throws.
  const std::string whole = tet.text(kInward, plain);
  std::size_t thrown = 0;
  for (std::size_t n = 0; n + 1 < whole.size(); ++n) {
    try {
      read_ovm(put("cut.ovm", whole.substr(0, n)));
    } catch (const Error&) {
      ++thrown;
    }
  }
  CHECK(thrown == whole.size() - 1);
}

TEST_CASE("ovm: the Expansion Cones inputs read, are coherently opposite, pass after a flip, match their maps") {
  struct Case {
    const char* mesh;
    const char* map;
    std::size_t vertices, tets, boundary_vertices;
  };
  const Case cases[] = {{"notch_domain.ovm", "notch_stiff_tet_boundary.txt", 502, 1850, 290},
                        {"prism_domain.ovm", "prism_ball_boundary.txt", 169, 619, 84},
                        {"thingi10k_81152_domain.ovm", "thingi10k_81152_random_star_boundary.txt", 1212, 3867, 973},
                        {"thingi10k_83715_domain.ovm", "thingi10k_83715_tet_boundary.txt", 303, 607, 298}};
  for (const Case& c : cases) {
    CAPTURE(c.mesh);
    VOLMAP_REQUIRE_DATA(mesh_path, std::string("maps/expansion_cones/") + c.mesh);
    VOLMAP_REQUIRE_DATA(map_path, std::string("maps/expansion_cones/") + c.map);
    TetMeshReadNotes notes;
    TetMeshData m = read_tet_mesh(mesh_path.string(), notes);
    CHECK(notes.format == "ovm");
    CHECK(notes.messages.empty());
    CHECK(m.num_vertices() == c.vertices);
    CHECK(m.num_tets() == c.tets);
    const TetMeshCheckReport before = check_tet_mesh(m);
    CHECK(before.orientation == OrientationClass::CoherentlyOpposite);
    CHECK(before.signs.negative == c.tets);
    flip_all_tets(m);
    const TetMeshCheckReport after = check_tet_mesh(m);
    CHECK(after.all_passed());
    // The map's ids are .ovm vertex indices: exactly the boundary vertices, each once.
    const BoundaryMap map = read_boundary_map(map_path.string());
    CHECK(map.size() == c.boundary_vertices);
    CHECK(boundary_vertex_ids(m).size() == c.boundary_vertices);
    CHECK_NOTHROW(validate_boundary_map(map, m, map_path.string()));
  }
}
