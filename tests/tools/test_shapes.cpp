// Built-in demo shapes: closed, oriented 2-manifolds of genus 0 with outward triangles.
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/check/self_intersection.hpp>
#include "support/shapes.hpp"
#include "surface_oracle.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

TEST_CASE("every built-in shape is a closed oriented genus-0 surface with outward triangles") {
  for (const auto& name : volmap::builtin_shape_names()) {
    CAPTURE(name);
    const auto s = volmap::make_builtin_shape(name, 2);
    const std::size_t nv = s.xyz.size() / 3, nf = s.tris.size() / 3;
    CHECK(nf == 20u * 16u);
    // Directed edges: each must appear once, and its reverse once (closed, consistently oriented).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> directed;
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) directed.emplace_back(s.tris[3 * f + k], s.tris[3 * f + (k + 1) % 3]);
    std::sort(directed.begin(), directed.end());
    CHECK(std::adjacent_find(directed.begin(), directed.end()) == directed.end());
    for (const auto& [a, b] : directed) CHECK(std::binary_search(directed.begin(), directed.end(), std::make_pair(b, a)));
    const std::size_t ne = directed.size() / 2;
    CHECK(static_cast<long>(nv) - static_cast<long>(ne) + static_cast<long>(nf) == 2);
    // Outward: the enclosed signed volume is positive (sum of origin cones, right-handed).
    double volume = 0;
    for (std::size_t f = 0; f < nf; ++f) {
      const double* a = &s.xyz[3 * s.tris[3 * f]];
      const double* b = &s.xyz[3 * s.tris[3 * f + 1]];
      const double* c = &s.xyz[3 * s.tris[3 * f + 2]];
      volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
    }
    CHECK(volume > 0.5);
    // Radial shapes are star-shaped about the origin: every outward triangle sees it on its inner
    // side, i.e. orient3d(a, b, c, origin) > 0 exactly (VOLMAP convention).
    if (name != "banana") {
      const double origin[3] = {0, 0, 0};
      for (std::size_t f = 0; f < nf; ++f)
        CHECK(volmap::orient3d(&s.xyz[3 * s.tris[3 * f]], &s.xyz[3 * s.tris[3 * f + 1]], &s.xyz[3 * s.tris[3 * f + 2]],
                               origin) > 0);
    }
  }
  CHECK_THROWS_AS(volmap::make_builtin_shape("torus"), volmap::Error);
  CHECK_THROWS_AS(volmap::make_builtin_shape("ellipsoid", 9), volmap::Error);
}

TEST_CASE("every thin-feature shape is a closed, embedded, outward genus-0 surface at each resolution") {
  CHECK(volmap::thin_shape_names().size() >= 12u);
  for (const auto& name : volmap::thin_shape_names())
    for (int sub : {1, 3}) {
      CAPTURE(name);
      CAPTURE(sub);
      const auto s = volmap::make_builtin_shape(name, sub);
      CHECK(volmap_test::closed_genus0_problem(s) == "");
      // Embedded: no two non-adjacent triangles meet (exact test from the check wing).
      const auto si = volmap::find_self_intersections(s.xyz, s.tris);
      CHECK(si.clean());
    }
  // Resolution grows with the subdivision parameter; out-of-range values are refused.
  const auto coarse = volmap::make_builtin_shape("tentacles", 1), fine = volmap::make_builtin_shape("tentacles", 3);
  CHECK(fine.num_triangles() > 2 * coarse.num_triangles());
  CHECK_THROWS_AS(volmap::make_builtin_shape("tentacles", 0), volmap::Error);
  CHECK_THROWS_AS(volmap::make_builtin_shape("tentacles", 6), volmap::Error);
}
