// TetMesh edge removal (n -> 2n-4 flip) on random rings around an interior edge, against exact
// oracles: for every triangulation of the ring polygon, can_remove_edge must agree with the signs of
// the 2n-4 new tets computed in exact rationals (GMP), and a removal must keep the mesh valid
// (check_invariants with exact positivity), the oriented boundary, the exact total volume (a rational
// sum of determinants), and produce exactly the triangulation's tets. Round trip: removing a diagonal
// of degree 4 with the triangulation through (va, vb) restores the original edge. Refusals leave the
// mesh bit-identical.
#include <doctest/doctest.h>

#include <volmap/core/error.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/predicates_rational.hpp>

#include "mesh_test_util.hpp"

#include <cmath>
#include <random>
#include <set>

using namespace volmap;

namespace {

using Tri = std::array<int, 3>;

// Every triangulation of the polygon i..j (positions), as triangle lists.
std::vector<std::vector<Tri>> triangulations(int i, int j) {
  if (j - i < 2) return {{}};
  std::vector<std::vector<Tri>> out;
  for (int k = i + 1; k < j; ++k)
    for (const auto& left : triangulations(i, k))
      for (const auto& right : triangulations(k, j)) {
        std::vector<Tri> t = left;
        t.insert(t.end(), right.begin(), right.end());
        t.push_back({i, k, j});
        out.push_back(t);
      }
  return out;
}

// The 6·volume of (a,b,c,d) as an exact rational, sign convention of orient3d (det[a-d; b-d; c-d]).
Rational det6(const double* a, const double* b, const double* c, const double* d) {
  Rational m[3][3];
  for (int i = 0; i < 3; ++i) {
    m[0][i] = Rational(a[i]) - Rational(d[i]);
    m[1][i] = Rational(b[i]) - Rational(d[i]);
    m[2][i] = Rational(c[i]) - Rational(d[i]);
  }
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Rational total_volume(const TetMesh& m) {
  Rational s = 0;
  for (std::uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (!m.tet_is_live(TetId(t))) continue;
    const auto v = m.tet_vertices(TetId(t));
    s += det6(m.vertex_position(v[0]), m.vertex_position(v[1]), m.vertex_position(v[2]), m.vertex_position(v[3]));
  }
  return s;
}

std::set<std::array<std::uint32_t, 4>> sorted_tets(const TetMesh& m) {
  std::set<std::array<std::uint32_t, 4>> out;
  for (std::uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (!m.tet_is_live(TetId(t))) continue;
    const auto v = m.tet_vertices(TetId(t));
    std::array<std::uint32_t, 4> k = {v[0].idx(), v[1].idx(), v[2].idx(), v[3].idx()};
    std::sort(k.begin(), k.end());
    out.insert(k);
  }
  return out;
}

// n tets around the edge (va = 0, vb = 1): ring vertex 2+i at angle ~2πi/n, random radius and
// height, tets (r_i, r_{i+1}, vb, va); resampled until every tet is positive.
TetMeshData random_ring(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> radius(0.2, 1.6), height(-0.7, 0.7), jitter(-0.25, 0.25);
  for (;;) {
    TetMeshData d;
    d.xyz = {jitter(rng), jitter(rng), -1.0 + jitter(rng), jitter(rng), jitter(rng), 1.0 + jitter(rng)};
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * (i + 0.3 * jitter(rng)) / n, r = radius(rng);
      d.xyz.insert(d.xyz.end(), {r * std::cos(a), r * std::sin(a), height(rng)});
    }
    for (int i = 0; i < n; ++i) d.tets.insert(d.tets.end(), {std::uint32_t(2 + i), std::uint32_t(2 + (i + 1) % n), 1u, 0u});
    bool positive = true;
    for (int i = 0; i < n; ++i) positive = positive && mesh_test::orient_tet(d.xyz, &d.tets[4 * i]) > 0;
    if (positive) return d;
  }
}

// The edge (0, 1) as (tet, local a, local b).
std::array<int, 3> edge01(const TetMesh& m) {
  int a = -1, b = -1;
  const TetId t = m.find_edge(VertexId(0), VertexId(1), &a, &b);
  REQUIRE(t.is_valid());
  return {int(t.idx()), a, b};
}

}  // namespace

TEST_CASE("remove_edge: every triangulation of random rings, against exact rational signs") {
  std::mt19937 rng(20260517);
  int valid = 0, invalid = 0;
  for (int n = 3; n <= 7; ++n) {
    const auto all = triangulations(0, n - 1);
    for (int trial = 0; trial < 12; ++trial) {
      const TetMeshData data = random_ring(n, rng);
      const TetMesh base(data);
      REQUIRE(base.check_invariants(true).ok);
      const auto e = edge01(base);
      const std::vector<VertexId> ring = base.edge_ring(TetId(e[0]), e[1], e[2]);
      REQUIRE(ring.size() == std::size_t(n));
      // Orientation of the ring: (ring[i], ring[i+1], vb, va) is a positive tet of the mesh.
      for (int i = 0; i < n; ++i) {
        const double* q[4] = {base.vertex_position(ring[i]), base.vertex_position(ring[(i + 1) % n]), base.vertex_position(VertexId(1)),
                              base.vertex_position(VertexId(0))};
        CHECK(det6(q[0], q[1], q[2], q[3]) > 0);
      }
      const Rational volume = total_volume(base);
      const auto boundary = mesh_test::oriented_boundary(base);
      for (const auto& tris : all) {
        // Oracle: all 2n-4 new tets strictly positive in exact rationals.
        bool oracle = true;
        std::set<std::array<std::uint32_t, 4>> expected;
        for (const Tri& tri : tris) {
          const VertexId p = ring[tri[0]], q = ring[tri[1]], r = ring[tri[2]];
          const double *P = base.vertex_position(p), *Q = base.vertex_position(q), *R = base.vertex_position(r);
          oracle = oracle && det6(P, Q, R, base.vertex_position(VertexId(0))) > 0 && det6(R, Q, P, base.vertex_position(VertexId(1))) > 0;
          for (std::uint32_t apex : {0u, 1u}) {
            std::array<std::uint32_t, 4> k = {p.idx(), q.idx(), r.idx(), apex};
            std::sort(k.begin(), k.end());
            expected.insert(k);
          }
        }
        CHECK(base.can_remove_edge(TetId(e[0]), e[1], e[2], tris) == oracle);
        if (!oracle) {
          ++invalid;
          continue;
        }
        ++valid;
        TetMesh m(data);
        const auto made = m.remove_edge(TetId(e[0]), e[1], e[2], tris);
        CHECK(made.size() == std::size_t(2 * n - 4));
        const InvariantReport rep = m.check_invariants(true);
        INFO(rep.problem);
        CHECK(rep.ok);
        CHECK(m.num_tets() == std::size_t(2 * n - 4));
        CHECK(m.num_free_tet_slots() == (n == 3 ? 1u : 0u));
        CHECK(!m.find_edge(VertexId(0), VertexId(1), nullptr, nullptr).is_valid());
        CHECK(sorted_tets(m) == expected);
        CHECK(mesh_test::oriented_boundary(m) == boundary);
        CHECK(total_volume(m) == volume);
      }
    }
  }
  MESSAGE("triangulations removable " << valid << ", refused " << invalid);
  CHECK(valid > 100);
  CHECK(invalid > 100);
}

TEST_CASE("remove_edge: round trip through a degree-4 diagonal, and refusals leave the mesh unchanged") {
  // A convex ring of 4: both triangulations are valid.
  TetMeshData data;
  data.xyz = {0, 0, -1, 0, 0, 1, 1, 0, 0.1, 0, 1, -0.1, -1, 0, 0.05, 0, -1, 0};
  for (int i = 0; i < 4; ++i) data.tets.insert(data.tets.end(), {std::uint32_t(2 + i), std::uint32_t(2 + (i + 1) % 4), 1u, 0u});
  TetMesh m(data);
  REQUIRE(m.check_invariants(true).ok);
  const auto before = sorted_tets(m);
  auto e = edge01(m);
  const std::vector<VertexId> ring = m.edge_ring(TetId(e[0]), e[1], e[2]);
  // Refused: a boundary edge, a non-triangulation (a side used twice), crossing diagonals.
  int ba = -1, bb = -1;
  const TetId bt = m.find_edge(VertexId(0), ring[0], &ba, &bb);
  CHECK_THROWS_AS(m.edge_ring(bt, ba, bb), Error);
  CHECK_FALSE(m.can_remove_edge(bt, ba, bb, {{0, 1, 2}}));
  const std::vector<std::vector<Tri>> bad = {{{0, 1, 2}}, {{0, 1, 2}, {1, 2, 3}}, {{0, 1, 3}, {0, 2, 3}}, {{0, 1, 2}, {0, 2, 3}, {0, 1, 3}}};
  const auto tv = m.tet_vertex_array();
  const auto opp = m.opposite_array();
  for (const auto& tris : bad) {
    CHECK_FALSE(m.can_remove_edge(TetId(e[0]), e[1], e[2], tris));
    CHECK_THROWS_AS(m.remove_edge(TetId(e[0]), e[1], e[2], tris), Error);
    CHECK(m.tet_vertex_array() == tv);
    CHECK(m.opposite_array() == opp);
  }
  // Remove (0,1) through the diagonal ring[0]-ring[2], then remove that diagonal again through (0,1).
  REQUIRE(m.can_remove_edge(TetId(e[0]), e[1], e[2], {{0, 1, 2}, {0, 2, 3}}));
  m.remove_edge(TetId(e[0]), e[1], e[2], {{0, 1, 2}, {0, 2, 3}});
  REQUIRE(m.check_invariants(true).ok);
  int a = -1, b = -1;
  const TetId t = m.find_edge(ring[0], ring[2], &a, &b);
  REQUIRE(t.is_valid());
  const std::vector<VertexId> ring2 = m.edge_ring(t, a, b);
  REQUIRE(ring2.size() == 4);
  int p0 = -1;  // the position of vertex 0 in the new ring: the diagonal (0, 1) joins positions p0 and p0+2
  for (int i = 0; i < 4; ++i)
    if (ring2[i] == VertexId(0)) p0 = i;
  REQUIRE(p0 >= 0);
  CHECK(ring2[(p0 + 2) % 4] == VertexId(1));
  const std::vector<Tri> tris = p0 % 2 == 0 ? std::vector<Tri>{{0, 1, 2}, {0, 2, 3}} : std::vector<Tri>{{0, 1, 3}, {1, 2, 3}};
  REQUIRE(m.can_remove_edge(t, a, b, tris));
  m.remove_edge(t, a, b, tris);
  CHECK(m.check_invariants(true).ok);
  CHECK(sorted_tets(m) == before);
}
