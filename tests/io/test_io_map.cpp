// Boundary maps and rationals files: all 100 G1 maps read and validate against their meshes
// (the README's oracle: vid set = boundary vertex set, line count = boundary vertex count);
// broken maps (missing, extra, interior, duplicate, out-of-range, garbage) throw with the right line.
#include <doctest/doctest.h>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>

#include "test_support.hpp"

#include <cstring>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <sstream>

using namespace volmap;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir() { return volmap_test::scratch_dir("io_map"); }
std::string write_text(const std::string& name, const std::string& text) {
  return volmap_test::write_bytes(scratch_dir() / name, text);
}
std::string read_text(const std::string& p) { return volmap_test::read_bytes(p); }

// Two tets sharing a face plus one interior vertex would need more; here: a tet split at an
// interior vertex 4 (4 tets), boundary vertices 0..3.
TetMeshData star_mesh() {
  TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, 0.2};
  m.tets = {4, 1, 2, 3, 0, 4, 2, 3, 0, 1, 4, 3, 0, 1, 2, 4};
  return m;
}

Error map_error(const std::string& text, const TetMeshData* mesh = nullptr) {
  const std::string p = write_text("broken.txt", text);
  try {
    const BoundaryMap map = read_boundary_map(p);
    if (mesh) validate_boundary_map(map, *mesh, p);
  } catch (const Error& e) {
    return e;
  }
  FAIL("no error for map text: " << text);
  return Error(ErrorKind::Failed, "");
}

const char* kG1[] = {"bimba", "bird", "blade", "bone", "bumpy_sphere", "bunny", "buste", "camile_hand", "devil", "duck",
                     "foot", "gargoyle", "hand", "homer", "moai", "mouse", "octa_flower", "pig", "ramses", "sphinx"};
const char* kDomains[] = {"cube", "tet", "pyr", "octa", "star"};

}  // namespace

TEST_CASE("map: read any whitespace, file order kept, lines recorded") {
  const std::string p = write_text("ok.txt", "3 1 2 3\r\n\n0\t0.5  -0 +1e2\n  2 1 1 1\n1 0 0 0");
  const BoundaryMap m = read_boundary_map(p);
  REQUIRE(m.size() == 4);
  CHECK(m.vids == std::vector<std::uint32_t>{3, 0, 2, 1});
  CHECK(m.source_lines == std::vector<std::uint32_t>{1, 3, 4, 5});
  CHECK(m.xyz[3] == 0.5);
  CHECK(m.xyz[5] == 100.0);
  validate_boundary_map(m, star_mesh(), p);  // vids {0,1,2,3} = boundary of the star mesh
}

TEST_CASE("map: malformed lines") {
  struct Case {
    const char* text;
    std::size_t line;
    const char* part;
  };
  const Case cases[] = {
      {"0 1 2 3\n1 1 2\n", 2, "4 values"},
      {"0 1 2 3\n1 1 2 3 4\n", 2, "4 values"},
      {"0 1 2 3\n-1 1 2 3\n", 2, "negative"},
      {"0 1 2 3\nx 1 2 3\n", 2, "integer"},
      {"0 1 2 3\n1.5 1 2 3\n", 2, "integer"},
      {"0 1 2 3\n1 1 nan 3\n", 2, "finite"},
      {"0 1 2 3\n1 1 2 inf\n", 2, "finite"},
      {"0 1 2 3\n\n1 1 2 3\n0 4 5 6\n", 4, "duplicate vertex id 0"},
      {"", 0, "empty"},
      {"\n\n  \n", 0, "empty"},
  };
  for (const Case& c : cases) {
    const std::string text = c.text;
    CAPTURE(text);
    const Error e = map_error(c.text);
    CHECK(e.kind() == ErrorKind::BadInput);
    CHECK(e.line() == c.line);
    CHECK(e.reason().find(c.part) != std::string::npos);
  }
}

TEST_CASE("map: validation against a mesh names the offending vid and line") {
  const TetMeshData mesh = star_mesh();
  struct Case {
    const char* text;
    std::size_t line;
    const char* part;
  };
  const Case cases[] = {
      {"0 0 0 0\n1 1 0 0\n2 0 1 0\n", 0, "boundary vertex 3 is missing"},            // missing id
      {"0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 0 0 0\n", 5, "vertex id 4 is an interior"},  // interior id
      {"0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n9 0 0 0\n", 5, "vertex id 9 out of range"},   // extra id
      {"0 0 0 0\n1 1 0 0\n2 0 1 0\n1 0 0 1\n", 4, "duplicate vertex id 1"},          // duplicate
  };
  for (const Case& c : cases) {
    const std::string text = c.text;
    CAPTURE(text);
    const Error e = map_error(c.text, &mesh);
    CHECK(e.kind() == ErrorKind::BadInput);
    CHECK(e.line() == c.line);
    CHECK(e.reason().find(c.part) != std::string::npos);
    CHECK(e.file().find("broken.txt") != std::string::npos);
  }
  // In-memory maps without lines name the entry instead.
  BoundaryMap m;
  m.vids = {0, 1, 2, 4};
  m.xyz.assign(12, 0.0);
  try {
    validate_boundary_map(m, mesh, "mem");
    FAIL("interior vid accepted");
  } catch (const Error& e) {
    CHECK(e.reason().find("entry 3") != std::string::npos);
  }
}

TEST_CASE("map: writer sorts by vid; full precision round-trips, Volmap6 prints 6 decimals") {
  BoundaryMap m;
  m.vids = {5, 1, 3};
  m.xyz = {0.1, 2.0 / 3.0, -1e-20, 25.581395, 100.0, 100.0, 1.0 / 3.0, -0.0, 7.0};
  const std::string full = (scratch_dir() / "full.txt").string();
  write_boundary_map(full, m);
  const BoundaryMap r = read_boundary_map(full);
  CHECK(r.vids == std::vector<std::uint32_t>{1, 3, 5});
  const double expect[] = {25.581395, 100.0, 100.0, 1.0 / 3.0, -0.0, 7.0, 0.1, 2.0 / 3.0, -1e-20};
  CHECK(std::memcmp(r.xyz.data(), expect, sizeof expect) == 0);
  const std::string six = (scratch_dir() / "six.txt").string();
  write_boundary_map(six, m, MapPrecision::Volmap6);
  CHECK(read_text(six) ==
        "1 25.581395 100.000000 100.000000\n3 0.333333 -0.000000 7.000000\n5 0.100000 0.666667 -0.000000\n");
}

TEST_CASE("map: all 100 G1 maps read and validate; line count = boundary vertex count") {
  if (volmap_test::data_root().empty()) {
    MESSAGE("skipped: ../shared/data is absent");
    return;
  }
  int validated = 0;
  for (const char* name : kG1) {
    const auto mesh_path = volmap_test::data_file(std::string("volmap/G1/") + name + ".mesh");
    if (mesh_path.empty()) continue;
    const TetMeshData mesh = read_medit(mesh_path.string());
    const std::size_t nb = boundary_vertex_ids(mesh).size();
    for (const char* dom : kDomains) {
      const std::string rel = std::string("volmap/G1_") + dom + "/" + name + "_" + dom + ".txt";
      const auto map_path = volmap_test::data_file(rel);
      if (map_path.empty()) continue;
      CAPTURE(rel);
      const BoundaryMap map = read_boundary_map(map_path.string());
      CHECK(map.size() == nb);
      CHECK_NOTHROW(validate_boundary_map(map, mesh, map_path.string()));
      ++validated;
    }
  }
  MESSAGE("validated " << validated << " G1 maps");
  CHECK(validated == 100);
}

TEST_CASE("map: expansion-cones exact decimal maps parse to the nearest double") {
  VOLMAP_REQUIRE_DATA(p, "maps/expansion_cones/prism_ball_boundary.txt");
  const BoundaryMap m = read_boundary_map(p.string());
  CHECK(m.size() == 84);
  // Line 2: "1 0.94280904158206346732384872666443698108196258544921875 0 -0.3333333333333333148..."
  CHECK(m.vids[1] == 1);
  CHECK(m.xyz[3] == 0.94280904158206346732384872666443698108196258544921875);
  CHECK(m.xyz[5] == -0.333333333333333314829616256247390992939472198486328125);
}

TEST_CASE("rationals: exact round-trip, canonicalisation, rejects") {
  std::vector<Rational> v = {Rational(6064708513608651LL) / Rational(140737488355328LL), Rational(-3), Rational(0),
                             Rational(1) / Rational(3), Rational("123456789012345678901234567890/7"), Rational(5) / Rational(-10)};
  const std::string p = (scratch_dir() / "r.txt").string();
  write_rationals(p, v);
  CHECK(read_text(p) ==
        "6064708513608651/140737488355328\n-3\n0\n1/3\n123456789012345678901234567890/7\n-1/2\n");
  const std::vector<Rational> r = read_rationals(p, 2);
  CHECK(r == v);
  // 2/4 is legal and canonicalised; '+', blank lines and CRLF accepted.
  const std::vector<Rational> c = read_rationals(write_text("c.txt", "2/4\r\n+6\n\n-10/20\n"), 1);
  REQUIRE(c.size() == 3);
  CHECK(c[0] == Rational(1) / Rational(2));
  CHECK(c[1] == Rational(6));
  CHECK(c[2] == Rational(-1) / Rational(2));
  struct Case {
    const char* text;
    std::size_t vertices;
    std::size_t line;
    const char* part;
  };
  const Case cases[] = {
      {"1\n2\n3/0\n", 1, 3, "zero denominator"},
      {"1\n2\n", 1, 2, "expected 3 values"},
      {"1\n2\n3\n4\n", 1, 4, "more than"},
      {"1\n2.5\n3\n", 1, 2, "rational"},
      {"1\n2/\n3\n", 1, 2, "rational"},
      {"1\n/2\n3\n", 1, 2, "rational"},
      {"1\n1/2/3\n3\n", 1, 2, "rational"},
      {"1\n2\n3\n", 1000000000, 0, "too small"},
      {"", 1, 0, "too small"},
  };
  for (const Case& k : cases) {
    const std::string text = k.text;
    CAPTURE(text);
    try {
      read_rationals(write_text("bad_r.txt", k.text), k.vertices);
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::BadInput);
      CHECK(e.line() == k.line);
      CHECK(e.reason().find(k.part) != std::string::npos);
    }
  }
}
