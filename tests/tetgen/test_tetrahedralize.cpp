// volmap-tetrahedralize: surfaces from the data (OFF, OBJ, binary STL, quads) become VOLMAP-positive
// meshes whose boundary is the input surface; bad surfaces from negative/ are refused (exit 1) with
// a reason, never a crash.
#include <doctest/doctest.h>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/surface/surface_map_check.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>

#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

using namespace volmap;

TEST_CASE("surfaces are tetrahedralized into VOLMAP-positive meshes keeping the boundary") {
  for (const char* rel : {"surfaces/gmsh/sphere-surf.stl", "surfaces/cgal/star.off",
                          "surfaces/nightmare_of_polycubes/7-connected.stl", "surfaces/libigl_tutorial/horse_quad.obj",
                          "surfaces/cinolib/sphere_coarse.obj"}) {
    CAPTURE(rel);
    const auto path = volmap_test::data_file(rel);
    if (path.empty()) continue;
    const TriangleSurface s = read_triangle_surface(path.string());
    CHECK(surface_topology_problem(s).empty());
    const TetMeshData m = tetrahedralize_surface(s);
    const auto signs = orient3d_tets(m.xyz.data(), m.num_vertices(), m.tets.data(), m.num_tets(), nullptr);
    CHECK(signs.positive == m.num_tets());
    // Y: no Steiner point on the boundary, so the boundary has exactly the input's triangles.
    CHECK(boundary_half_faces(m).size() == s.num_triangles());
    for (std::size_t k = 0; k < s.xyz.size(); ++k)
      if (s.xyz[k] != m.xyz[k]) FAIL("input vertex moved");
  }
}

TEST_CASE("bad surfaces are refused with a reason") {
  struct Case { const char* rel; const char* reason; };
  for (auto c : {Case{"negative/cinolib_torus.obj", "genus 1"}, Case{"negative/cinolib_two_spheres.obj", "2 connected"},
                 Case{"negative/cgal_elephant-with-holes.off", "not closed"},
                 Case{"negative/common3d_cow.obj", "not manifold"}, Case{"negative/libigl_3holes.off", "genus 3"}}) {
    CAPTURE(c.rel);
    const auto path = volmap_test::data_file(c.rel);
    if (path.empty()) continue;
    const std::string p = surface_topology_problem(read_triangle_surface(path.string()));
    CHECK(p.find(c.reason) != std::string::npos);
  }
}

TEST_CASE("volmap-tetrahedralize tool: exit codes, then the pipeline to a surface map") {
  VOLMAP_REQUIRE_DATA(stl, "surfaces/gmsh/sphere-surf.stl");
  const auto dir = std::filesystem::temp_directory_path() / ("volmap_tetgen_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string tool = volmap_test::tool("volmap-tetrahedralize").string();
  auto run = [](const std::string& cmd) { return WEXITSTATUS(std::system((cmd + " > /dev/null 2>&1").c_str())); };
  const std::string out = (dir / "sphere.mesh").string();
  CHECK(run(tool + " " + stl.string() + " " + out + " --max-volume 1e9") == 0);
  const TetMeshData m = read_medit(out);
  CHECK(m.num_tets() > 0);
  for (const char* d : {"cube", "star"}) {
    CAPTURE(d);
    CHECK_NOTHROW(map_surface_to_domain(m, builtin_domain(d)));
  }
  // cgal/part.off -> octa: the reference arc order traces the equator with nodes 4 and 5 on the same
  // side, so the mapper must fall back to tracing a spanning tree first.
  if (const auto part = volmap_test::data_file("surfaces/cgal/part.off"); !part.empty()) {
    const std::string pm = (dir / "part.mesh").string();
    CHECK(run(tool + " " + part.string() + " " + pm) == 0);
    const Domain octa = builtin_domain("octa");
    SurfaceMapResult r;
    CHECK_NOTHROW(r = map_surface_to_domain(read_medit(pm), octa));
    CHECK(check_surface_map(r.mesh, r.map, &octa).ok);
  }
  // A 4-vertex surface (one tet): too coarse for every domain but the tetrahedron until every boundary
  // edge is split; onto the tetrahedron its own 4 vertices and 6 edges are the nodes and arcs, and the
  // lean chord rule splits nothing (no chord).
  if (const auto tiny = volmap_test::data_file("surfaces/cgal/tetrahedron.off"); !tiny.empty()) {
    const std::string tm = (dir / "tiny.mesh").string();
    CHECK(run(tool + " " + tiny.string() + " " + tm) == 0);
    const TetMeshData t = read_medit(tm);
    for (const char* dn : {"cube", "tet", "pyr", "octa", "star"}) {
      CAPTURE(dn);
      const Domain d = builtin_domain(dn);
      SurfaceMapResult r;
      CHECK_NOTHROW(r = map_surface_to_domain(t, d));
      CHECK(check_surface_map(r.mesh, r.map, &d).ok);
      if (std::string(dn) == "tet")
        CHECK(r.added_vertices == 0);
      else
        CHECK(r.added_vertices > 0);
    }
  }
  for (const char* rel : {"negative/cinolib_torus.obj", "negative/cgal_bull.off", "negative/libigl_cow.off"}) {
    CAPTURE(rel);
    const auto p = volmap_test::data_file(rel);
    if (p.empty()) continue;
    CHECK(run(tool + " " + p.string() + " " + (dir / "bad.mesh").string()) == 1);
    CHECK(!std::filesystem::exists(dir / "bad.mesh"));
  }
  CHECK(run(tool + " /nonexistent.obj " + out) == 2);
  std::filesystem::remove_all(dir);
}
