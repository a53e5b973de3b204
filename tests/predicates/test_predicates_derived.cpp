// The exact tests built on the predicates — points_equal, collinear, same_half_plane, enclosed_volume_sign and the
// certification count count_nonpositive / nonpositive_tets — against the independent GMP oracle of
// predicates/testing/oracle.hpp, on cases where double arithmetic gets them wrong.
#include <doctest/doctest.h>
#include <volmap/predicates.hpp>

#include "../../predicates/testing/oracle.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace or_ = volmap_oracle;

namespace {

// Outward boundary triangles of tet (v0..v3) (VOLMAP face table F0=(1,3,2) F1=(0,2,3) F2=(0,3,1) F3=(0,1,2)).
void add_tet_boundary(std::vector<std::uint32_t>& tris, std::uint32_t v0, std::uint32_t v1, std::uint32_t v2,
                      std::uint32_t v3) {
  const std::uint32_t f[4][3] = {{v1, v3, v2}, {v0, v2, v3}, {v0, v3, v1}, {v0, v1, v2}};
  for (const auto& t : f) tris.insert(tris.end(), t, t + 3);
}

int volmap_volume_sign(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tris) {
  return volmap::enclosed_volume_sign(xyz.data(), xyz.size() / 3, tris.data(), tris.size() / 3);
}
int oracle_volume_sign(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tris) {
  return or_::enclosed_volume_sign(xyz.data(), tris.data(), tris.size() / 3);
}

}  // namespace

TEST_CASE("points_equal: value equality of coordinates, ±0 equal, NaN and neighbours unequal") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double a[3] = {1, -0.0, 0x1p-1074}, b[3] = {1, 0.0, 0x1p-1074};
  CHECK(volmap::points_equal(a, b));
  CHECK(or_::points_equal(a, b));
  const double c[3] = {1, 0.0, 0.0};  // the subnormal against zero: distinct points
  CHECK_FALSE(volmap::points_equal(a, c));
  CHECK_FALSE(or_::points_equal(a, c));
  const double d[3] = {std::nextafter(1.0, 2.0), 0.0, 0x1p-1074};
  CHECK_FALSE(volmap::points_equal(b, d));
  const double n[3] = {nan, 0, 0};
  CHECK_FALSE(volmap::points_equal(n, n));
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> pick(0, 3);
  const double values[4] = {0.0, -0.0, 0x1p-1070, 1.5};
  for (int i = 0; i < 2000; ++i) {
    double p[3], q[3];
    for (int k = 0; k < 3; ++k) p[k] = values[pick(rng)], q[k] = values[pick(rng)];
    REQUIRE(volmap::points_equal(p, q) == or_::points_equal(p, q));
  }
}

TEST_CASE("same_half_plane: exact integer planes far from the origin, rounded near-coplanar points, points on the line") {
  std::mt19937_64 rng(23);
  std::uniform_int_distribution<int> small(-20, 20);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int same = 0, other = 0, on_line = 0, near_agree = 0, near_same = 0;
  for (int i = 0; i < 20000; ++i) {
    double a[3], b[3], p[3], q[3];
    const double shift = (i % 2) ? 1e15 : 0.0;  // integers far from the origin stay exact
    for (int k = 0; k < 3; ++k) {
      a[k] = shift + small(rng);
      b[k] = shift + small(rng);
      p[k] = shift + small(rng);
    }
    // q = a + s (p − a) + t (b − a) with small integers: coplanar exactly; s > 0 same side, s < 0 the
    // other, s = 0 on the line.
    const int s = small(rng) % 4, t = small(rng) % 4;
    for (int k = 0; k < 3; ++k) q[k] = a[k] + s * (p[k] - a[k]) + t * (b[k] - a[k]);
    const bool expected = or_::same_half_plane(a, b, p, q);
    REQUIRE(volmap::same_half_plane(a, b, p, q) == expected);
    REQUIRE(volmap::same_half_plane(b, a, q, p) == expected);  // symmetric in (a, b) and in (p, q)
    if (!volmap::collinear(a, b, p) && !volmap::points_equal(a, b)) {
      same += s > 0 && expected;
      other += s < 0 && !expected;
      on_line += s == 0 && !expected;
    }
    // Rounded: q from a fractional s, usually a hair off the plane.
    double r[3];
    const double sr = u(rng);
    for (int k = 0; k < 3; ++k) r[k] = a[k] - shift + sr * (p[k] - a[k]) + u(rng) * 1e-17 + shift;
    const bool e2 = or_::same_half_plane(a, b, p, r);
    near_same += e2;
    near_agree += volmap::same_half_plane(a, b, p, r) == e2;
  }
  CHECK(near_agree == 20000);
  CHECK(same > 1000);
  CHECK(other > 1000);
  CHECK(on_line > 500);
  MESSAGE("same_half_plane: " << same << " same side, " << other << " opposite, " << on_line << " on the line; rounded cases coplanar and same side: " << near_same);
  // p on the line ab: never a half-plane.
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, p[3] = {3, 0, 0}, q[3] = {0, 1, 0};
  CHECK_FALSE(volmap::same_half_plane(a, b, p, q));
  CHECK_FALSE(volmap::same_half_plane(a, b, q, p));
  // A subnormal lift of q off the plane is seen.
  const double p2[3] = {0, 1, 0}, q2[3] = {0.5, 2, 0x1p-1074};
  const double q3[3] = {0.5, 2, 0};
  CHECK_FALSE(volmap::same_half_plane(a, b, p2, q2));
  CHECK(volmap::same_half_plane(a, b, p2, q3));
}

TEST_CASE("collinear: near-collinear rounded points, exact integer lines, coincident points") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int naive_wrong = 0, exact_lines = 0;
  for (int i = 0; i < 20000; ++i) {
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k) a[k] = u(rng), b[k] = u(rng);
    const double s = (i % 3 == 0) ? 0.5 : u(rng);  // s = 0.5 of dyadic points is sometimes exact
    for (int k = 0; k < 3; ++k) c[k] = a[k] + s * (b[k] - a[k]);
    const bool expected = or_::collinear(a, b, c);
    exact_lines += expected;
    REQUIRE(volmap::collinear(a, b, c) == expected);
    REQUIRE(volmap::collinear(c, a, b) == expected);
    double n[3];  // double cross product: what an unfiltered test decides
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      n[k] = (b[k1] - a[k1]) * (c[k2] - a[k2]) - (b[k2] - a[k2]) * (c[k1] - a[k1]);
    }
    naive_wrong += (n[0] == 0 && n[1] == 0 && n[2] == 0) != expected;
  }
  CHECK(naive_wrong > 100);  // the set really is hard for doubles
  CHECK(exact_lines > 0);
  // Integer lines, including far from the origin and with a repeated point.
  const double a[3] = {1e15, -3, 7}, b[3] = {1e15 + 2, -1, 11};
  const double c[3] = {1e15 + 20, 17, 47}, c_off[3] = {1e15 + 20, 17, 48};
  CHECK(volmap::collinear(a, b, c));
  CHECK_FALSE(volmap::collinear(a, b, c_off));
  CHECK(volmap::collinear(a, a, c_off));
  CHECK(volmap::collinear(a, a, a));
  // Subnormal offsets off the line are seen.
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0.5, 0x1p-1074, 0};
  CHECK_FALSE(volmap::collinear(o, x, y));
  CHECK(or_::collinear(o, x, y) == false);
}

TEST_CASE("enclosed_volume_sign: tet boundaries follow orient3d; flat, cancelling and far-away surfaces") {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.0, 1.0);
  int filter_hard = 0;
  for (int i = 0; i < 3000; ++i) {
    std::vector<double> xyz(12);
    for (auto& x : xyz) x = u(rng);
    const int kind = i % 4;
    if (i % 8 == 1)  // dyadic points and weights below: the apex lies exactly on the plane
      for (auto& x : xyz) x = std::ldexp(std::round(std::ldexp(x, 10)), -10);
    if (kind >= 1) {  // near-coplanar: the apex rounded onto the plane of the others
      const double s = i % 8 == 1 ? 0.25 : w(rng), t = i % 8 == 1 ? 0.5 : w(rng);
      for (int k = 0; k < 3; ++k) xyz[9 + k] = xyz[k] + s * (xyz[3 + k] - xyz[k]) + t * (xyz[6 + k] - xyz[k]);
    }
    if (kind >= 2)  // far from the origin: large cancelling terms in the sum
      for (int v = 0; v < 4; ++v) xyz[3 * v] += 1e9, xyz[3 * v + 1] -= 3e8;
    if (kind == 3)  // outside Shewchuk's range: the rational layer
      for (auto& x : xyz) x = std::ldexp(x, -700);
    std::vector<std::uint32_t> tris;
    add_tet_boundary(tris, 0, 1, 2, 3);
    const int expected = oracle_volume_sign(xyz, tris);
    REQUIRE(volmap_volume_sign(xyz, tris) == expected);
    REQUIRE(expected == or_::orient3d(&xyz[0], &xyz[3], &xyz[6], &xyz[9]));  // the convention in the header
    filter_hard += expected == 0;
  }
  CHECK(filter_hard > 0);  // the exactly coplanar cases

  // Two copies of one surface, the second reversed and translated by an inexact offset: exactly 0
  // only when the offset is exact; the doubles see noise either way.
  for (double offset : {0.375, 0.1, 1e7 + 0.3}) {
    std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int k = 0; k < 12; ++k) xyz.push_back(xyz[k] + offset * (k % 3 == 1 ? 1 : 0.5));
    std::vector<std::uint32_t> tris;
    add_tet_boundary(tris, 0, 1, 2, 3);
    add_tet_boundary(tris, 5, 4, 6, 7);  // odd permutation: negative
    CHECK(volmap_volume_sign(xyz, tris) == oracle_volume_sign(xyz, tris));
  }
  // A closed surface traversed twice with opposite orientations encloses exactly nothing.
  {
    std::vector<double> xyz(12);
    for (auto& x : xyz) x = u(rng) * 1e6 + 0.1;
    std::vector<std::uint32_t> tris;
    add_tet_boundary(tris, 0, 1, 2, 3);
    add_tet_boundary(tris, 1, 0, 2, 3);
    CHECK(volmap_volume_sign(xyz, tris) == 0);
  }
  // Many tets, one of them tiny and the rest cancelling in pairs: the sign is the tiny tet's.
  {
    std::vector<double> xyz;
    std::vector<std::uint32_t> tris;
    for (int pair = 0; pair < 200; ++pair) {
      const std::uint32_t base = std::uint32_t(xyz.size() / 3);
      for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) xyz.push_back(u(rng) * 1e3 + 5e3);
      add_tet_boundary(tris, base, base + 1, base + 2, base + 3);
      add_tet_boundary(tris, base + 1, base, base + 2, base + 3);
    }
    const std::uint32_t base = std::uint32_t(xyz.size() / 3);
    const double tiny[12] = {0, 0, 0, 0x1p-40, 0, 0, 0, 0x1p-40, 0, 0, 0, 0x1p-40};
    xyz.insert(xyz.end(), tiny, tiny + 12);
    add_tet_boundary(tris, base, base + 1, base + 2, base + 3);  // orient3d(0, e1, e2, e3) < 0
    CHECK(oracle_volume_sign(xyz, tris) == -1);
    CHECK(volmap_volume_sign(xyz, tris) == -1);
  }
  // Refused input.
  std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, std::numeric_limits<double>::infinity()};
  std::vector<std::uint32_t> tris;
  add_tet_boundary(tris, 0, 1, 2, 3);
  CHECK_THROWS_AS(volmap_volume_sign(xyz, tris), volmap::NonFiniteInput);
  xyz[11] = 1;
  tris[4] = 9;
  CHECK_THROWS_AS(volmap_volume_sign(xyz, tris), std::out_of_range);
  CHECK(volmap::enclosed_volume_sign(xyz.data(), 4, nullptr, 0) == 0);
}

TEST_CASE("count_nonpositive / nonpositive_tets: oracle counts on a flattened grid; refused input counts all") {
  or_::IndexedTets g = or_::kuhn_grid(10, 1.0 / 16);
  const double zc = 5.0 / 16;
  for (std::size_t v = 0; v < g.xyz.size() / 3; ++v) {  // upper half onto a tilted plane (exact)
    double* p = &g.xyz[3 * v];
    if (p[2] > zc + (p[0] + p[1]) / 4) p[2] = zc + (p[0] + p[1]) / 4;
  }
  for (std::size_t t = 0; t < 40; ++t) std::swap(g.tets[4 * (37 * t)], g.tets[4 * (37 * t) + 1]);  // some negative
  const std::size_t nv = g.xyz.size() / 3, nt = g.tets.size() / 4;
  std::vector<std::uint32_t> expected;
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* q = &g.tets[4 * t];
    if (or_::orient3d(&g.xyz[3 * q[0]], &g.xyz[3 * q[1]], &g.xyz[3 * q[2]], &g.xyz[3 * q[3]]) <= 0)
      expected.push_back(std::uint32_t(t));
  }
  REQUIRE(expected.size() > 40);
  REQUIRE(expected.size() < nt);
  std::vector<std::int8_t> signs(nt, 7);
  CHECK(volmap::count_nonpositive(g.xyz.data(), nv, g.tets.data(), nt, signs.data()) == expected.size());
  std::size_t listed = 0;
  for (std::size_t t = 0; t < nt; ++t) listed += signs[t] <= 0;
  CHECK(listed == expected.size());
  CHECK(volmap::count_nonpositive(g.xyz, g.tets) == expected.size());
  CHECK(volmap::nonpositive_tets(g.xyz, g.tets) == expected);

  std::vector<double> bad = g.xyz;
  bad[5] = std::numeric_limits<double>::quiet_NaN();
  CHECK(volmap::count_nonpositive(bad.data(), nv, g.tets.data(), nt, signs.data()) == nt);
  for (std::size_t t = 0; t < nt; ++t) REQUIRE(signs[t] == 0);
  CHECK(volmap::nonpositive_tets(bad, g.tets).size() == nt);
  std::vector<std::uint32_t> bad_ids = g.tets;
  bad_ids[4 * 3 + 2] = std::uint32_t(nv);
  CHECK(volmap::count_nonpositive(g.xyz, bad_ids) == nt);
}
