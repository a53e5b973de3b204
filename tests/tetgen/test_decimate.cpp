// Surface decimation (volmap::tetgen decimate_surface): the result keeps the topology (closed,
// oriented, genus 0; independent oracle), reaches the target face count, stays close to the input,
// leaves small surfaces alone, keeps an embedded thin part embedded and refuses surfaces that are not
// closed genus-0 manifolds.
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/tetgen/decimate.hpp>
#include <volmap/check/self_intersection.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/testing/generate.hpp>

#include "surface_oracle.hpp"
#ifdef VOLMAP_TEST_THIN_SHAPES
#include "support/shapes.hpp"
#endif

#include <cmath>
#include <unordered_map>

using namespace volmap;

namespace {

// The boundary of an n^3 Kuhn grid (12 n^2 triangles, outward) with its vertices pushed onto a bumpy
// radial surface r = 1 + bump * sin(5x) sin(4y) sin(3z) about the cube's centre: closed, genus 0.
SurfaceData bumpy_sphere(std::size_t n, double bump) {
  const TetMeshData grid = generate_kuhn_unit_cube(n);
  std::unordered_map<std::uint32_t, std::uint32_t> index;
  SurfaceData s;
  for (auto hf : boundary_half_faces(grid))
    for (auto v : half_face_vertices(grid, hf)) {
      const auto [it, fresh] = index.emplace(v, std::uint32_t(index.size()));
      s.tris.push_back(it->second);
      if (!fresh) continue;
      double p[3], r2 = 0;
      for (int k = 0; k < 3; ++k) {
        p[k] = grid.xyz[3 * v + k] - 0.5;
        r2 += p[k] * p[k];
      }
      const double r = std::sqrt(r2), radius = 1 + bump * std::sin(5 * p[0]) * std::sin(4 * p[1]) * std::sin(3 * p[2]);
      for (int k = 0; k < 3; ++k) s.xyz.push_back(radius * p[k] / r);
    }
  return s;
}

}  // namespace

TEST_CASE("decimation keeps a closed genus-0 surface, reaches its target and stays near the input") {
  for (double bump : {0.0, 0.3}) {
    CAPTURE(bump);
    const SurfaceData in = bumpy_sphere(20, bump);  // 4,800 triangles
    REQUIRE(volmap_test::closed_genus0_problem(in) == "");
    DecimateOptions options;
    options.target_faces = 800;
    const DecimateResult r = decimate_surface(in, options);
    CHECK(r.faces_before == in.num_triangles());
    CHECK(r.faces_after == r.surface.num_triangles());
    CHECK(r.faces_after <= 800u);
    CHECK(r.faces_after >= 600u);  // it stops at the target, it does not over-collapse
    CHECK(r.reached_target);
    CHECK(volmap_test::closed_genus0_problem(r.surface) == "");
    // Every kept vertex is an input vertex (collapses move none): each output point is an input point.
    for (std::size_t v = 0; v < r.surface.num_vertices(); ++v) {
      bool found = false;
      for (std::size_t u = 0; u < in.num_vertices() && !found; ++u)
        found = in.xyz[3 * u] == r.surface.xyz[3 * v] && in.xyz[3 * u + 1] == r.surface.xyz[3 * v + 1] &&
                in.xyz[3 * u + 2] == r.surface.xyz[3 * v + 2];
      CHECK(found);
    }
  }
}

TEST_CASE("a surface already under the target is returned unchanged") {
  const SurfaceData in = bumpy_sphere(5, 0.2);  // 300 triangles
  DecimateOptions options;
  options.target_faces = 1000;
  const DecimateResult r = decimate_surface(in, options);
  CHECK(r.surface.tris == in.tris);
  CHECK(r.surface.xyz == in.xyz);
  CHECK(r.faces_after == 300u);
}

TEST_CASE("decimation refuses surfaces that are not closed genus-0 manifolds") {
  SurfaceData open = bumpy_sphere(8, 0.2);
  open.tris.resize(open.tris.size() - 3);  // one triangle removed: a hole
  DecimateOptions options;
  options.target_faces = 100;
  CHECK_THROWS_AS(decimate_surface(open, options), Error);
  try {
    decimate_surface(open, options);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::BadInput);
  }
}

#ifdef VOLMAP_TEST_THIN_SHAPES
TEST_CASE("decimating a thin part keeps it embedded: a self-intersecting run is redone towards a larger target") {
  const SurfaceData in = make_builtin_shape("tentacles_coarse", 3);  // 2,016 triangles, thin arms
  SelfIntersectionOptions check;
  REQUIRE(find_self_intersections(in.xyz, in.tris, check).clean());
  DecimateOptions options;
  options.target_faces = 400;
  options.keep_embedded = false;  // the plain collapse sequence: its arms collapse into each other
  const DecimateResult plain = decimate_surface(in, options);
  CHECK(plain.faces_after <= 400u);
  CHECK(find_self_intersections(plain.surface.xyz, plain.surface.tris, check).intersecting_pairs > 0);

  options.keep_embedded = true;
  const DecimateResult r = decimate_surface(in, options);
  CHECK(r.embedding_retries > 0);
  CHECK(r.target_used > 400u);
  CHECK(r.faces_after <= r.target_used);
  CHECK(r.faces_after < in.num_triangles());
  CHECK_FALSE(r.reached_target);
  CHECK(find_self_intersections(r.surface.xyz, r.surface.tris, check).clean());
  CHECK(volmap_test::closed_genus0_problem(r.surface) == "");
  // The kept run is the plain run at the target it settled on (the retries are deterministic).
  options.keep_embedded = false;
  options.target_faces = r.target_used;
  const DecimateResult same = decimate_surface(in, options);
  CHECK(same.surface.tris == r.surface.tris);
  CHECK(same.surface.xyz == r.surface.xyz);
}
#endif
