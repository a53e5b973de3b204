// Surface IO: every OBJ/OFF/STL/PLY in ../shared/data/surfaces (and negative/) loads with the
// README's V/F counts (F counted after triangulation for the all-quad files), coordinates are the
// correctly rounded doubles of the text, writers round-trip, malformed files throw.
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/io/io_surface.hpp>

#include "test_support.hpp"

#include <cstring>
#include <filesystem>
#include <unistd.h>
#include <fstream>

using namespace volmap;
namespace fs = std::filesystem;

namespace {
fs::path scratch_dir() { return volmap_test::scratch_dir("io_surface"); }
std::string write_text(const std::string& name, const std::string& text) {
  return volmap_test::write_bytes(scratch_dir() / name, text);
}
struct Expected {
  const char* file;
  std::size_t v, t;
};
// README counts (V, F). Quad files: cubespikes.obj 1,192 quads -> 2,384 triangles; horse_quad.obj
// (README: all-quad) 2,398 quads -> 4,796 triangles. igea.ply: 268,686 strip triangles.
const Expected kSurfaces[] = {
    {"surfaces/cgal/bear.off", 13826, 27648},        {"surfaces/cgal/blobby.off", 2027, 4050},
    {"surfaces/cgal/bunny00.off", 37706, 75408},     {"surfaces/cgal/cross.off", 40, 76},
    {"surfaces/cgal/cube-meshed.off", 866, 1728},    {"surfaces/cgal/dino.off", 3916, 7828},
    {"surfaces/cgal/dragknob.off", 161, 318},        {"surfaces/cgal/ellipsoid.off", 162, 320},
    {"surfaces/cgal/fandisk_large.off", 15843, 31682}, {"surfaces/cgal/hand.off", 1197, 2390},
    {"surfaces/cgal/handle.off", 1165, 2326},        {"surfaces/cgal/icosahedron.off", 12, 20},
    {"surfaces/cgal/larger_sphere.off", 812, 1620},  {"surfaces/cgal/oblong.off", 422, 840},
    {"surfaces/cgal/octahedron.off", 6, 8},          {"surfaces/cgal/part.off", 175, 346},
    {"surfaces/cgal/retinal.off", 3643, 7282},       {"surfaces/cgal/spool.off", 649, 1294},
    {"surfaces/cgal/star.off", 14, 24},              {"surfaces/cgal/tetrahedron.off", 4, 4},
    {"surfaces/cgal/triceratops.off", 2832, 5660},   {"surfaces/cgal/tripod.off", 24, 44},
    {"surfaces/cgal/u.off", 86, 168},                {"surfaces/cinolib/blub_triangulated.obj", 7106, 14208},
    {"surfaces/cinolib/bunny.obj", 14290, 28576},    {"surfaces/cinolib/cactus.off", 5261, 10518},
    {"surfaces/cinolib/cube_minus_sphere.obj", 2066, 4128}, {"surfaces/cinolib/cubespikes.obj", 1194, 2384},
    {"surfaces/common3d/igea.ply", 134345, 268686},  {"surfaces/gmsh/sphere-surf.stl", 326, 648},
    {"surfaces/nightmare_of_polycubes/7-connected.stl", 20, 36},
    {"surfaces/nightmare_of_polycubes/8-connected.stl", 25, 46},
    {"surfaces/nightmare_of_polycubes/conjoined_twins.stl", 19, 34},
    {"surfaces/nightmare_of_polycubes/cuboid_screw_thread.stl", 56, 108},
    {"surfaces/nightmare_of_polycubes/cuboid_tray_with_step.stl", 26, 48},
    {"surfaces/nightmare_of_polycubes/encrusted_cube.stl", 308, 612},
    {"surfaces/nightmare_of_polycubes/encrusted_cube_triangle_mesh.obj", 24823, 49642},
    {"negative/common3d_cow.obj", 2903, 5804},       {"negative/cgal_elephant-with-holes.off", 2798, 4463},
};
}  // namespace

TEST_CASE("surface: data files load with the README counts") {
  if (volmap_test::data_root().empty()) {
    MESSAGE("skipped: ../shared/data is absent");
    return;
  }
  for (const Expected& e : kSurfaces) {
    const std::string file = e.file;
    CAPTURE(file);
    const auto p = volmap_test::data_file(e.file);
    if (p.empty()) continue;
    const SurfaceData s = read_surface(p.string());
    CHECK(s.num_vertices() == e.v);
    CHECK(s.num_triangles() == e.t);
  }
  // Every surface file present loads (the list above is a subset with known counts).
  std::size_t loaded = 0;
  for (const auto& entry : fs::recursive_directory_iterator(volmap_test::data_root() / "surfaces")) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".obj" && ext != ".off" && ext != ".stl" && ext != ".ply") continue;
    const std::string file = entry.path().string();
    CAPTURE(file);
    SurfaceData s;
    CHECK_NOTHROW(s = read_surface(file));
    CHECK(s.num_triangles() > 0);
    ++loaded;
  }
  CHECK(loaded == 58);
}

TEST_CASE("surface: coordinates are correctly rounded doubles; fan triangulation") {
  // blobby.off's first vertex is "0.0958494 0.00115985 -0.166522".
  VOLMAP_REQUIRE_DATA(p, "surfaces/cgal/blobby.off");
  const SurfaceData s = read_surface(p.string());
  CHECK(s.xyz[0] == 0.0958494);
  CHECK(s.xyz[1] == 0.00115985);
  CHECK(s.xyz[2] == -0.166522);
  const SurfaceData q = read_surface(write_text("quad.obj", "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 -1/1\n"));
  CHECK(q.tris == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  const SurfaceData o = read_surface(write_text("pent.off", "OFF\n5 1 0\n0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n5 0 1 2 3 4\n"));
  CHECK(o.tris == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4});
}

TEST_CASE("surface: writers round-trip (OFF, OBJ, PLY exact; STL float)") {
  SurfaceData s;
  s.xyz = {0.1, 0.2, 0.3, 1.0 / 3.0, 0, 0, 0, 1, 0, 0, 0, 1};
  s.tris = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  for (const char* ext : {".off", ".obj", ".ply"}) {
    const std::string p = (scratch_dir() / (std::string("rt") + ext)).string();
    write_surface(p, s);
    const SurfaceData r = read_surface(p);
    CHECK(r.tris == s.tris);
    CHECK(std::memcmp(r.xyz.data(), s.xyz.data(), 8 * s.xyz.size()) == 0);
  }
  const std::string stl = (scratch_dir() / "rt.stl").string();
  write_surface(stl, s);
  const SurfaceData r = read_surface(stl);
  CHECK(r.num_vertices() == 4);
  CHECK(r.num_triangles() == 4);
}

TEST_CASE("surface: malformed files throw volmap::Error") {
  struct Case {
    const char* name;
    const char* text;
    std::size_t line;
  };
  const Case cases[] = {
      {"a.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", 0},
      {"b.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", 6},
      {"c.off", "OFF\n3 1 0\n0 nan 0\n1 0 0\n0 1 0\n3 0 1 2\n", 3},
      {"d.off", "NOPE\n", 1},
      {"e.off", "OFF\n999999999 1 0\n", 2},
      {"f.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n", 3},
      {"g.obj", "v 0 0\n", 1},
      {"h.obj", "v 0 0 0\n", 0},
      {"i.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n", 6},
      {"j.ply", "not a ply\n", 1},
  };
  for (const Case& c : cases) {
    const std::string name = c.name;
    CAPTURE(name);
    try {
      read_surface(write_text(c.name, c.text));
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::BadInput);
      CHECK(e.line() == c.line);
    }
  }
  CHECK_THROWS_AS(read_surface(write_text("x.xyz", "1 2 3")), Error);
  CHECK_THROWS_AS(read_surface((scratch_dir() / "missing.off").string()), Error);
  CHECK_THROWS_AS(read_surface(write_text("empty.stl", "")), Error);
  CHECK_THROWS_AS(read_surface(write_text("garbage.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex a b c\n")), Error);
}
