// Surface maps on shapes that broke the mapper before, each built here from a Kuhn grid (every tet
// positive by construction) and judged by the exact check (an independent module: coverage, domain,
// corners, cones about the centroid), the refined tets' exact signs and the input vertices' positions.
//  - A worm: a one-cell-thick serpentine tube lying one cell above a block, attached at one end. It
//    sits inside one chart, where Tutte's uniform weights shrink it exponentially: in doubles its
//    triangles collapse. Before, every attempt failed (the "cannot trace arc" came from the
//    first attempt; the later ones failed the check with inverted and degenerate triangles).
//  - An uneven sphere: a cube grid graded towards one corner (x -> 100 (x/n)^4). Its projected cube
//    map is positive about the sphere's centre but 6 slivers are inverted about the centroid of the
//    image points, VOLMAP's kernel; `volmap-surface-map sphere` used to accept it.
//  - A single tet onto the sphere: no split (the regular tetrahedron's map), where the cube map needs
//    8 corners.
//  - G1's bird, hand and mouse sphere maps (the cases): the map tool and the check tool
//    agree, with and without --domain sphere. Long: all 20 G1 meshes.
#include <doctest/doctest.h>
#include <volmap/io/io.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/domain.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/surface/surface_map_check.hpp>
#include <volmap/testing/generate.hpp>

#include "test_support.hpp"

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <string>

using namespace volmap;

namespace {

// W x W x 2 block; the worm runs on level z = 3 along rows y = 3, 5, ... (x from 3 to W-4), joined
// at alternating ends, and stands on the block through one cell at (3, 3, 2).
TetMeshData worm_on_block(std::size_t W) {
  return generate_kuhn_grid(W, W, 4, [W](std::size_t i, std::size_t j, std::size_t k) {
    if (k < 2) return true;
    if (k == 2) return i == 3 && j == 3;
    if (k != 3 || i < 3 || i > W - 4 || j < 3 || j > W - 4) return false;
    const std::size_t r = j - 3;
    if (r % 2 == 0) return true;
    return (r / 2) % 2 == 0 ? i == W - 4 : i == 3;
  });
}

TetMeshData graded_cube(std::size_t n, double power) {
  TetMeshData d = generate_kuhn_grid(n, n, n);
  for (double& x : d.xyz) x = 100.0 * std::pow(x / static_cast<double>(n), power);
  return d;
}

// The map is valid (exact check with the domain), the refined tets are positive and the input
// vertices did not move.
void require_valid(const TetMeshData& input, const SurfaceMapResult& r, const Domain& d) {
  const auto c = check_surface_map(r.mesh, r.map, &d);
  CAPTURE(c.reason);
  CHECK(c.ok);
  CHECK(c.positive == c.boundary_triangles);
  CHECK(c.corners_exact == d.num_nodes());
  const auto signs = orient3d_tets(r.mesh.xyz.data(), r.mesh.num_vertices(), r.mesh.tets.data(), r.mesh.num_tets(), nullptr);
  CHECK(signs.positive == r.mesh.num_tets());
  REQUIRE(r.mesh.xyz.size() >= input.xyz.size());
  for (std::size_t k = 0; k < input.xyz.size(); ++k)
    if (input.xyz[k] != r.mesh.xyz[k]) FAIL("an input vertex moved");
}

// Cones about the centroid (no options: VOLMAP's check), about the centre, and the sphere test.
void require_valid_sphere(const SurfaceMapResult& s) {
  const auto plain = check_surface_map(s.mesh, s.map);
  CAPTURE(plain.reason);
  CHECK(plain.ok);
  SurfaceMapCheckOptions sphere;
  sphere.sphere_centre = {50, 50, 50};
  sphere.sphere_radius = 50;
  CHECK(check_surface_map(s.mesh, s.map, nullptr, sphere).ok);
  SurfaceMapCheckOptions centre;
  centre.override_kernel = true;
  centre.kernel = {50, 50, 50};
  CHECK(check_surface_map(s.mesh, s.map, nullptr, centre).ok);
}

int run(const std::string& cmd) {
  const int rc = std::system((cmd + " > /dev/null 2>&1").c_str());
  return WEXITSTATUS(rc);
}

// volmap-surface-map sphere on a G1 mesh; the check tool must accept the map without options and
// with --domain sphere.
void check_g1_sphere_agreement(const std::string& name) {
  CAPTURE(name);
  const auto mesh = volmap_test::data_file("volmap/G1/" + name + ".mesh");
  REQUIRE(!mesh.empty());
  const auto dir = volmap_test::scratch_dir("sphere_" + name);
  const std::string map = (dir / "map.txt").string(), refined = (dir / "map_in.mesh").string();
  REQUIRE(run(volmap_test::tool("volmap-surface-map").string() + " sphere " + mesh.string() + " " + map +
              " --refined " + refined) == 0);
  const std::string used = std::filesystem::exists(refined) ? refined : mesh.string();
  const std::string check = volmap_test::tool("volmap-surface-map-check").string() + " " + used + " " + map;
  CHECK(run(check) == 0);
  CHECK(run(check + " --domain sphere") == 0);
  std::filesystem::remove_all(dir);
}

}  // namespace

TEST_CASE("a worm lying in one chart maps onto every domain and the sphere") {
  const TetMeshData worm = worm_on_block(13);
  REQUIRE(worm.num_tets() == 2220);
  for (const char* name : {"cube", "tet", "pyr", "octa", "star"}) {
    CAPTURE(name);
    const Domain d = builtin_domain(name);
    SurfaceMapResult r;
    REQUIRE_NOTHROW(r = map_surface_to_domain(worm, d));
    require_valid(worm, r, d);
    // Only chord splits (the reference's rule): no other arc order, no subdivision round (the
    // probes may be rotated, surface_map.hpp step 6).
    CHECK(r.attempt.rfind("reference arc order", 0) == 0);
    CHECK(r.attempt.find("subdivision") == std::string::npos);
    CHECK(r.attempt.find("spanning tree") == std::string::npos);
    if (std::string(name) == "cube") require_valid_sphere(project_to_sphere(r, {50, 50, 50}, 50));
  }
}

TEST_CASE("an unevenly sampled cube gets a sphere map that is valid about the centroid of its points") {
  const TetMeshData graded = graded_cube(6, 4);
  // The reference's chord rule: its extra vertices along the arcs crowd one corner of this grading.
  SurfaceMapOptions reference;
  reference.reference_chord_splits = true;
  const SurfaceMapResult cube = map_surface_to_domain(graded, builtin_domain("cube"), reference);
  require_valid(graded, cube, builtin_domain("cube"));
  // The plain projection is the case this fixes: positive about the centre, not about the centroid.
  SurfaceMapResult projected = cube;
  for (std::size_t i = 0; i < projected.map.size(); ++i) {
    double* p = &projected.map.xyz[3 * i];
    const double d[3] = {p[0] - 50, p[1] - 50, p[2] - 50};
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; ++k) p[k] = 50 + 50 * (d[k] / n);
  }
  CHECK(!check_surface_map(projected.mesh, projected.map).ok);
  const SurfaceMapResult sphere = project_to_sphere(cube, {50, 50, 50}, 50);
  require_valid_sphere(sphere);
  CHECK(sphere.check.ok);
  CHECK(sphere.map.vids == cube.map.vids);
}

TEST_CASE("volmap-surface-map sphere and volmap-surface-map-check agree on G1's bird, hand and mouse") {
  VOLMAP_REQUIRE_DATA(bird, "volmap/G1/bird.mesh");
  for (const char* name : {"bird", "hand", "mouse"}) check_g1_sphere_agreement(name);
}

TEST_SUITE("long") {
  TEST_CASE("every G1 sphere map passes the check tool with and without --domain sphere") {
    VOLMAP_REQUIRE_DATA(bird, "volmap/G1/bird.mesh");
    for (const char* name : {"bimba", "bird", "blade", "bone", "bumpy_sphere", "bunny", "buste", "camile_hand",
                             "devil", "duck", "foot", "gargoyle", "hand", "homer", "moai", "mouse", "octa_flower",
                             "pig", "ramses", "sphinx"})
      check_g1_sphere_agreement(name);
  }
}

TEST_CASE("a single tet maps onto the sphere with no split: the regular tetrahedron's map needs no corner more") {
  TetMeshData one;
  one.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  one.tets = {0, 1, 2, 3};
  if (orient3d(&one.xyz[0], &one.xyz[3], &one.xyz[6], &one.xyz[9]) < 0) std::swap(one.tets[0], one.tets[1]);
  one.vertex_labels.assign(4, 0);
  one.tet_labels.assign(1, 0);
  const SurfaceMapResult s = map_surface_to_sphere(one, {50, 50, 50}, 50);
  require_valid_sphere(s);
  CHECK(s.added_vertices == 0);
  CHECK(s.mesh.num_tets() == 1);
  CHECK(s.attempt.find("regular tetrahedron") != std::string::npos);
  // The cube map alone must split: 8 corners on a 4-vertex boundary.
  CHECK(map_surface_to_domain(one, builtin_domain("cube")).added_vertices >= 4);
}
