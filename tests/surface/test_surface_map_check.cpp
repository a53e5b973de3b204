// Exact surface-map check against the reference maps of the dataset (every one must pass), plus
// maps broken on purpose (missing / extra ids, a mirrored map, a moved corner, a point off the domain).
#include <doctest/doctest.h>
#include <volmap/surface/domain.hpp>
#include <volmap/io/io.hpp>
#include <volmap/surface/surface_map_check.hpp>

#include "test_support.hpp"

#include <string>

using namespace volmap;

static void check_reference(const std::string& name, const std::string& dom) {
  VOLMAP_REQUIRE_DATA(mesh_path, "volmap/G1/" + name + ".mesh");
  VOLMAP_REQUIRE_DATA(map_path, "volmap/G1_" + dom + "/" + name + "_" + dom + ".txt");
  const TetMeshData mesh = read_medit(mesh_path.string());
  const BoundaryMap map = read_boundary_map(map_path.string());
  const Domain d = builtin_domain(dom);
  const auto r = check_surface_map(mesh, map, &d);
  CAPTURE(name);
  CAPTURE(dom);
  CAPTURE(r.reason);
  CHECK(r.ok);
  CHECK(r.positive == r.boundary_triangles);
  CHECK(r.corners_exact == d.num_nodes());
  CHECK(r.off_domain == 0);
}

TEST_CASE("reference maps of bone and duck pass the exact check") {
  for (const char* n : {"bone", "duck"})
    for (const char* d : {"cube", "tet", "pyr", "octa", "star"}) check_reference(n, d);
}

TEST_CASE("broken maps fail the check") {
  VOLMAP_REQUIRE_DATA(mesh_path, "volmap/G1/bone.mesh");
  VOLMAP_REQUIRE_DATA(map_path, "volmap/G1_cube/bone_cube.txt");
  const TetMeshData mesh = read_medit(mesh_path.string());
  const BoundaryMap map = read_boundary_map(map_path.string());
  const Domain cube = builtin_domain("cube");
  REQUIRE(check_surface_map(mesh, map).ok);
  {  // missing id
    BoundaryMap m = map;
    m.vids.pop_back();
    m.xyz.resize(m.xyz.size() - 3);
    const auto r = check_surface_map(mesh, m);
    CHECK(!r.ok);
    CHECK(r.missing == 1);
  }
  {  // extra (interior or out-of-range) id
    BoundaryMap m = map;
    m.vids.push_back(static_cast<std::uint32_t>(mesh.num_vertices() + 5));
    m.xyz.insert(m.xyz.end(), {1, 2, 3});
    const auto r = check_surface_map(mesh, m);
    CHECK(!r.ok);
    CHECK(r.not_boundary == 1);
  }
  {  // mirrored map: all cones negative, accepted only in the reference's either-sign mode
    BoundaryMap m = map;
    for (std::size_t i = 0; i < m.size(); ++i) m.xyz[3 * i] = 100 - m.xyz[3 * i];
    auto r = check_surface_map(mesh, m);
    CHECK(!r.ok);
    CHECK(r.negative == r.boundary_triangles);
    SurfaceMapCheckOptions o;
    o.accept_either_sign = true;
    CHECK(check_surface_map(mesh, m, nullptr, o).ok);
  }
  {  // a vertex pushed inside the cube: off the domain, and some cones flip or not - off_domain counts
    BoundaryMap m = map;
    std::size_t k = 0;
    while (m.xyz[3 * k] == 0 || m.xyz[3 * k] == 100 || m.xyz[3 * k + 1] == 0 || m.xyz[3 * k + 1] == 100) ++k;
    m.xyz[3 * k + 2] = 50;  // a face point (x and y strictly inside, so z is 0 or 100) moved to the middle
    auto r = check_surface_map(mesh, m, &cube);
    CHECK(!r.ok);
    CHECK(r.off_domain >= 1);
  }
  {  // a corner moved by one ulp along its face: still on the domain, but not exactly on its target
    BoundaryMap m = map;
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m.xyz[3 * i] == 0 && m.xyz[3 * i + 1] == 0 && m.xyz[3 * i + 2] == 0) m.xyz[3 * i] = 1e-300;
    auto r = check_surface_map(mesh, m, &cube);
    CHECK(r.corners_exact == 7);
  }
}

TEST_SUITE("long") {
  TEST_CASE("all 100 reference maps of G1 pass the exact check") {
    for (const char* n : {"bimba", "bird", "blade", "bone", "bumpy_sphere", "bunny", "buste", "camile_hand", "devil",
                          "duck", "foot", "gargoyle", "hand", "homer", "moai", "mouse", "octa_flower", "pig",
                          "ramses", "sphinx"})
      for (const char* d : {"cube", "tet", "pyr", "octa", "star"}) check_reference(n, d);
  }
}
