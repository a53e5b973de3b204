// Exact triangle-surface self-intersection test: tiny hand-built configurations with known answers,
// and randomized comparison against an independent exact oracle (a rational linear program solved by
// enumerating basic solutions), plus the accelerated driver against brute force over all pairs.
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/predicates_rational.hpp>
#include <volmap/check/self_intersection.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

using volmap::find_self_intersections;
using volmap::Rational;

namespace {

struct Soup {
  std::vector<double> xyz;
  std::vector<std::uint32_t> tris;
  std::uint32_t v(double x, double y, double z) {
    xyz.insert(xyz.end(), {x, y, z});
    return std::uint32_t(xyz.size() / 3 - 1);
  }
  void t(std::uint32_t a, std::uint32_t b, std::uint32_t c) { tris.insert(tris.end(), {a, b, c}); }
};

// ---- oracle: points of closed T1 ∩ closed T2 as the feasible set of
//   alpha, beta >= 0, sum alpha = 1, sum beta = 1, sum alpha_i P_i - sum beta_j Q_j = 0.
// Returns false when infeasible; otherwise the min and max of alpha[k] over the set (attained at
// basic feasible solutions, enumerated over all column subsets with exact rational elimination).
struct OracleRange {
  bool feasible = false;
  Rational min_alpha[3], max_alpha[3];
};

OracleRange oracle(const double* P[3], const double* Q[3]) {
  Rational A[5][6];
  for (int j = 0; j < 3; ++j) {
    A[0][j] = 1;
    A[1][j] = 0;
    A[0][3 + j] = 0;
    A[1][3 + j] = 1;
    for (int k = 0; k < 3; ++k) {
      A[2 + k][j] = Rational(P[j][k]);
      A[2 + k][3 + j] = -Rational(Q[j][k]);
    }
  }
  const Rational rhs[5] = {1, 1, 0, 0, 0};
  OracleRange out;
  for (int subset = 1; subset < 64; ++subset) {
    int cols[6], n = 0;
    for (int j = 0; j < 6; ++j)
      if (subset & (1 << j)) cols[n++] = j;
    Rational M[5][7];
    for (int r = 0; r < 5; ++r) {
      for (int c = 0; c < n; ++c) M[r][c] = A[r][cols[c]];
      M[r][n] = rhs[r];
    }
    // Gaussian elimination; require full column rank and consistency.
    int row = 0;
    bool independent = true;
    int pivot_row[6];
    for (int c = 0; c < n; ++c) {
      int p = -1;
      for (int r = row; r < 5; ++r)
        if (M[r][c] != 0) {
          p = r;
          break;
        }
      if (p < 0) {
        independent = false;
        break;
      }
      for (int k = 0; k <= n; ++k) std::swap(M[row][k], M[p][k]);
      for (int r = 0; r < 5; ++r) {
        if (r == row || M[r][c] == 0) continue;
        const Rational f = M[r][c] / M[row][c];
        for (int k = 0; k <= n; ++k) M[r][k] -= f * M[row][k];
      }
      pivot_row[c] = row++;
    }
    if (!independent) continue;
    bool consistent = true;
    for (int r = row; r < 5; ++r)
      if (M[r][n] != 0) consistent = false;
    if (!consistent) continue;
    Rational x[6];
    bool nonnegative = true;
    for (int c = 0; c < n; ++c) {
      x[cols[c]] = M[pivot_row[c]][n] / M[pivot_row[c]][c];
      if (x[cols[c]] < 0) nonnegative = false;
    }
    if (!nonnegative) continue;
    for (int k = 0; k < 3; ++k) {
      if (!out.feasible || x[k] < out.min_alpha[k]) out.min_alpha[k] = x[k];
      if (!out.feasible || x[k] > out.max_alpha[k]) out.max_alpha[k] = x[k];
    }
    out.feasible = true;
  }
  return out;
}

// Oracle answer for "t and u intersect other than in what they share by id".
bool oracle_pair(const std::vector<double>& xyz, const std::uint32_t* t, const std::uint32_t* u) {
  const double* P[3] = {&xyz[3 * t[0]], &xyz[3 * t[1]], &xyz[3 * t[2]]};
  const double* Q[3] = {&xyz[3 * u[0]], &xyz[3 * u[1]], &xyz[3 * u[2]]};
  int shared_mask = 0, shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (t[i] == u[j]) {
        shared_mask |= 1 << i;
        ++shared;
      }
  const OracleRange r = oracle(P, Q);
  if (!r.feasible) return false;
  if (shared == 0 || shared == 3) return true;
  if (shared == 1) {
    int a = 0;
    while (!(shared_mask & (1 << a))) ++a;
    return r.min_alpha[a] < 1;  // a point of t other than its corner a
  }
  int c = 0;
  while (shared_mask & (1 << c)) ++c;
  return r.max_alpha[c] > 0;  // a point of t off the shared edge
}

// Closed bounding boxes of triangles i and j overlap (exact double comparisons).
bool boxes_overlap(const Soup& s, std::size_t i, std::size_t j) {
  for (int k = 0; k < 3; ++k) {
    double lo[2], hi[2];
    const std::size_t tri[2] = {i, j};
    for (int m = 0; m < 2; ++m) {
      lo[m] = hi[m] = s.xyz[3 * s.tris[3 * tri[m]] + k];
      for (int c = 1; c < 3; ++c) {
        lo[m] = std::min(lo[m], s.xyz[3 * s.tris[3 * tri[m] + c] + k]);
        hi[m] = std::max(hi[m], s.xyz[3 * s.tris[3 * tri[m] + c] + k]);
      }
    }
    if (lo[0] > hi[1] || lo[1] > hi[0]) return false;
  }
  return true;
}

bool pair_intersects(const Soup& s, int i, int j) {
  return volmap::triangle_pair_intersects(s.xyz.data(), &s.tris[3 * i], &s.tris[3 * j]);
}

}  // namespace

TEST_CASE("two crossing triangles (no shared vertex) intersect") {
  Soup s;
  s.t(s.v(0, 0, 0), s.v(2, 0, 0), s.v(0, 2, 0));
  s.t(s.v(0.5, 0.5, -1), s.v(0.5, 0.5, 1), s.v(3, 3, 0.25));
  CHECK(pair_intersects(s, 0, 1));
  const auto r = find_self_intersections(s.xyz, s.tris);
  CHECK(r.intersecting_pairs == 1);
  REQUIRE(r.first_pairs.size() == 1);
  CHECK(r.first_pairs[0] == volmap::TrianglePair{0, 1});
  CHECK_FALSE(r.clean());
}

TEST_CASE("separated and barely separated triangles do not intersect") {
  Soup s;
  s.t(s.v(0, 0, 0), s.v(1, 0, 0), s.v(0, 1, 0));
  // Above the plane by the smallest double step: a float tolerance would call this touching.
  const double z = std::nextafter(0.0, 1.0);
  s.t(s.v(0.1, 0.1, z), s.v(0.5, 0.1, z), s.v(0.1, 0.5, 1));
  CHECK_FALSE(pair_intersects(s, 0, 1));
  CHECK(find_self_intersections(s.xyz, s.tris).clean());
}

TEST_CASE("touching at a point counts when no vertex id is shared") {
  Soup s;
  s.t(s.v(0, 0, 0), s.v(2, 0, 0), s.v(0, 2, 0));
  // A vertex of the second triangle lies exactly inside the first.
  s.t(s.v(0.5, 0.5, 0), s.v(0.5, 0.5, 1), s.v(1, 0.7, 1));
  CHECK(pair_intersects(s, 0, 1));
  // Vertex to vertex at the same position but distinct ids: coincident vertices.
  Soup c;
  c.v(0, 0, 0);
  c.v(1, 0, 0);
  c.v(0, 1, 0);
  c.v(0, 0, 0);  // 3 coincides with 0
  c.v(-1, 0, 1);
  c.v(0, -1, 1);
  c.t(0, 1, 2);
  c.t(3, 4, 5);
  const auto r = find_self_intersections(c.xyz, c.tris);
  CHECK(r.coincident_vertices == 1);
  CHECK(r.intersecting_pairs == 1);
  REQUIRE(r.first_coincident.size() == 1);
  CHECK(r.first_coincident[0].first == 0);
  CHECK(r.first_coincident[0].second == 3);
  // −0 and +0 are the same coordinate; three vertices at one point are two coincident pairs.
  c.xyz[3 * 3 + 1] = -0.0;
  CHECK(find_self_intersections(c.xyz, c.tris).coincident_vertices == 1);
  c.v(0, 0, -0.0);
  c.t(6, 1, 5);
  CHECK(find_self_intersections(c.xyz, c.tris).coincident_vertices == 2);
}

TEST_CASE("a shared vertex: touching only there is fine, overlap or piercing is not") {
  Soup s;
  const auto a = s.v(0, 0, 0), b = s.v(1, 0, 0), c = s.v(0, 1, 0);
  s.t(a, b, c);
  s.t(a, s.v(-1, 0, 1), s.v(0, -1, 1));      // 1: only a in common
  s.t(a, s.v(0.5, 0.2, 0), s.v(0.2, 0.5, 0)); // 2: coplanar, inside t's corner
  s.t(a, s.v(0.3, 0.3, 1), s.v(0.3, 0.3, -1)); // 3: crosses t's plane inside its corner
  s.t(a, s.v(-1, 0, 0), s.v(0, -1, 0));      // 4: coplanar, opposite corner (vertical angle)
  s.t(a, s.v(-1, -1, 1), s.v(-1, -1, -1));   // 5: crosses the plane outside the corner
  s.t(a, s.v(2, 0, 0), s.v(2, 0, 1));        // 6: runs along edge ab (shares a segment)
  CHECK_FALSE(pair_intersects(s, 0, 1));
  CHECK(pair_intersects(s, 0, 2));
  CHECK(pair_intersects(s, 0, 3));
  CHECK_FALSE(pair_intersects(s, 0, 4));
  CHECK_FALSE(pair_intersects(s, 0, 5));
  CHECK(pair_intersects(s, 0, 6));
  CHECK(pair_intersects(s, 6, 0));
}

TEST_CASE("a shared edge: a proper hinge is fine, a fold onto itself is not") {
  Soup s;
  const auto a = s.v(0, 0, 0), b = s.v(1, 0, 0), c = s.v(0, 1, 0);
  s.t(a, b, c);
  s.t(b, a, s.v(0.5, -1, 0));  // 1: flat continuation across ab
  s.t(b, a, s.v(0.5, 0.5, 1)); // 2: hinge
  s.t(b, a, s.v(0.3, 0.2, 0)); // 3: folded back onto t, coplanar
  s.t(a, b, s.v(3, 5, 0));     // 4: folded, covering t partially
  CHECK_FALSE(pair_intersects(s, 0, 1));
  CHECK_FALSE(pair_intersects(s, 0, 2));
  CHECK(pair_intersects(s, 0, 3));
  CHECK(pair_intersects(s, 4, 0));
  // Same three ids twice.
  Soup d;
  const auto p = d.v(0, 0, 0), q = d.v(1, 0, 0), r = d.v(0, 1, 0);
  d.t(p, q, r);
  d.t(r, q, p);
  CHECK(pair_intersects(d, 0, 1));
}

TEST_CASE("coplanar overlap without shared ids, and coplanar disjoint") {
  Soup s;
  s.t(s.v(0, 0, 0), s.v(4, 0, 0), s.v(0, 4, 0));
  s.t(s.v(1, 1, 0), s.v(5, 1, 0), s.v(1, 5, 0));  // overlapping
  s.t(s.v(3, 3, 0), s.v(6, 3, 0), s.v(3, 6, 0));  // beyond the hypotenuse of 0 (x+y>4), overlaps 1
  s.t(s.v(2, 2, 0), s.v(6, 2, 0), s.v(2, 6, 0));  // touches triangle 0 at (2,2) only
  CHECK(pair_intersects(s, 0, 1));
  CHECK_FALSE(pair_intersects(s, 0, 2));
  CHECK(pair_intersects(s, 1, 2));
  CHECK(pair_intersects(s, 0, 3));
}

TEST_CASE("degenerate triangles are reported") {
  Soup s;
  s.t(s.v(0, 0, 0), s.v(1, 1, 1), s.v(2, 2, 2));
  s.t(s.v(5, 0, 0), s.v(6, 0, 0), s.v(5, 1, 0));
  s.t(4, 4, 5);
  const auto r = find_self_intersections(s.xyz, s.tris);
  CHECK(r.degenerate_triangles == 2);
  CHECK(r.first_degenerate == std::vector<std::uint32_t>{0, 2});
  CHECK(volmap::triangle_is_degenerate(&s.xyz[0], &s.xyz[3], &s.xyz[6]));
}

TEST_CASE("closed polyhedra are clean; a dented one is not") {
  Soup s;  // octahedron
  const auto px = s.v(1, 0, 0), nx = s.v(-1, 0, 0), py = s.v(0, 1, 0), ny = s.v(0, -1, 0), pz = s.v(0, 0, 1),
             nz = s.v(0, 0, -1);
  const std::uint32_t faces[8][3] = {{px, py, pz}, {py, nx, pz}, {nx, ny, pz}, {ny, px, pz},
                                     {py, px, nz}, {nx, py, nz}, {ny, nx, nz}, {px, ny, nz}};
  for (auto& f : faces) s.t(f[0], f[1], f[2]);
  auto r = find_self_intersections(s.xyz, s.tris);
  CHECK(r.clean());
  CHECK(r.candidate_pairs == 8 * 7 / 2);  // every box overlaps (they all contain the origin's axes)
  // A second octahedron shifted by half its size intersects the first (and nothing is shared).
  const std::uint32_t offset = std::uint32_t(s.xyz.size() / 3);
  for (std::size_t i = 0; i < 6; ++i) s.v(s.xyz[3 * i] + 0.5, s.xyz[3 * i + 1], s.xyz[3 * i + 2]);
  for (auto& f : faces) s.t(f[0] + offset, f[1] + offset, f[2] + offset);
  r = find_self_intersections(s.xyz, s.tris);
  CHECK(r.intersecting_pairs > 0);
  CHECK(r.coincident_vertices == 0);
  CHECK_THROWS_AS(find_self_intersections(s.xyz.data(), 5, s.tris.data(), 8), volmap::Error);
}

TEST_CASE("randomized: pair test equals an exact LP oracle on grid points (many degeneracies)") {
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> coord(0, 2);
  int checked = 0, positives = 0, by_shared[3] = {0, 0, 0};
  for (int iter = 0; iter < 4000; ++iter) {
    Soup s;
    for (int i = 0; i < 6; ++i) s.v(coord(rng), coord(rng), coord(rng));
    // t uses 0,1,2; u shares 0, 1 or 2 ids.
    const int shared = iter % 3;
    std::uint32_t t[3] = {0, 1, 2};
    std::uint32_t u[3] = {3, 4, 5};
    for (int k = 0; k < shared; ++k) u[k] = t[k];
    std::shuffle(u, u + 3, rng);
    const double* X = s.xyz.data();
    if (volmap::triangle_is_degenerate(X + 3 * t[0], X + 3 * t[1], X + 3 * t[2]) ||
        volmap::triangle_is_degenerate(X + 3 * u[0], X + 3 * u[1], X + 3 * u[2]))
      continue;
    const bool expected = oracle_pair(s.xyz, t, u);
    const bool got = volmap::triangle_pair_intersects(X, t, u);
    const bool got_swapped = volmap::triangle_pair_intersects(X, u, t);
    INFO("iter " << iter << " shared " << shared);
    CHECK(got == expected);
    CHECK(got_swapped == expected);
    ++checked;
    positives += expected;
    ++by_shared[shared];
  }
  MESSAGE("checked " << checked << " pairs, " << positives << " intersecting");
  CHECK(checked > 1000);
  CHECK(positives > 100);
  CHECK(checked - positives > 100);
  CHECK(by_shared[1] > 200);
  CHECK(by_shared[2] > 200);
}

TEST_CASE("randomized: the accelerated driver finds exactly the brute-force pairs") {
  // Jittered grid vertices; small triangles between grid neighbours, some sharing ids, many crossing.
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> jitter(-0.45, 0.45);
  constexpr int G = 10;
  Soup s;
  for (int x = 0; x < G; ++x)
    for (int y = 0; y < G; ++y)
      for (int z = 0; z < G; ++z) s.v(x + jitter(rng), y + jitter(rng), z + jitter(rng));
  auto id = [&](int x, int y, int z) { return std::uint32_t((x * G + y) * G + z); };
  std::uniform_int_distribution<int> cell(0, G - 2), bit(0, 1);
  for (int i = 0; i < 2500; ++i) {
    const int x = cell(rng), y = cell(rng), z = cell(rng);
    std::uint32_t c[3];
    do {
      for (auto& v : c) v = id(x + bit(rng), y + bit(rng), z + bit(rng));
    } while (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]);
    s.t(c[0], c[1], c[2]);
  }
  const std::size_t n = s.tris.size() / 3;
  std::size_t brute = 0, overlapping = 0;
  std::vector<volmap::TrianglePair> first;
  std::vector<char> degenerate(n);
  for (std::size_t i = 0; i < n; ++i)
    degenerate[i] = volmap::triangle_is_degenerate(&s.xyz[3 * s.tris[3 * i]], &s.xyz[3 * s.tris[3 * i + 1]],
                                                   &s.xyz[3 * s.tris[3 * i + 2]]);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (degenerate[i] || degenerate[j] || !boxes_overlap(s, i, j)) continue;
      ++overlapping;
      if (volmap::triangle_pair_intersects(s.xyz.data(), &s.tris[3 * i], &s.tris[3 * j])) {
        ++brute;
        if (first.size() < 5) first.push_back({std::uint32_t(i), std::uint32_t(j)});
      }
    }
  volmap::SelfIntersectionOptions options;
  options.max_reported = 5;
  for (bool parallel : {false, true}) {
    options.parallel = parallel;
    const auto r = find_self_intersections(s.xyz, s.tris, options);
    CHECK(r.intersecting_pairs == brute);
    CHECK(r.first_pairs == first);
    CHECK(r.candidate_pairs == overlapping);      // every box-overlapping pair visited exactly once
    CHECK(r.candidate_pairs < n * (n - 1) / 50);  // the hierarchy prunes
  }
  MESSAGE(n << " triangles, " << brute << " intersecting pairs");
  CHECK(brute > 0);
}

namespace {

// Closed surfaces whose vertex fans are mostly injective under an axis projection (the driver then
// settles adjacent pairs per vertex) with dents that fold some fans: the driver must still find
// exactly the brute-force pairs, adjacent ones included.
struct BruteForce {
  std::size_t pairs = 0, adjacent_pairs = 0;
  std::vector<volmap::TrianglePair> first;
};

// Pairs of non-degenerate triangles that intersect (the driver reports degenerate ones apart).
BruteForce brute_force(const Soup& s, std::size_t max_first) {
  BruteForce b;
  const std::size_t n = s.tris.size() / 3;
  auto degenerate = [&](std::size_t i) {
    const double* X = s.xyz.data();
    return volmap::triangle_is_degenerate(X + 3 * s.tris[3 * i], X + 3 * s.tris[3 * i + 1], X + 3 * s.tris[3 * i + 2]);
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const std::uint32_t* t = &s.tris[3 * i];
      const std::uint32_t* u = &s.tris[3 * j];
      if (degenerate(i) || degenerate(j) || !volmap::triangle_pair_intersects(s.xyz.data(), t, u)) continue;
      ++b.pairs;
      const bool adjacent = std::count(u, u + 3, t[0]) + std::count(u, u + 3, t[1]) + std::count(u, u + 3, t[2]) > 0;
      b.adjacent_pairs += adjacent;
      if (b.first.size() < max_first) b.first.push_back({std::uint32_t(i), std::uint32_t(j)});
    }
  return b;
}

// The boundary of the cube [0, n]³ in unit squares, two triangles each, wound outwards.
Soup grid_cube_surface(int n) {
  Soup s;
  std::vector<std::uint32_t> id((n + 1) * (n + 1) * (n + 1), 0xFFFFFFFFu);
  auto vertex = [&](int x, int y, int z) {
    std::uint32_t& v = id[std::size_t((x * (n + 1) + y) * (n + 1) + z)];
    if (v == 0xFFFFFFFFu) v = s.v(x, y, z);
    return v;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side <= 1; ++side)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          int corner[4][3];
          const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            corner[k][axis] = side * n;
            corner[k][(axis + 1) % 3] = i + di[k];
            corner[k][(axis + 2) % 3] = j + dj[k];
          }
          std::uint32_t q[4];
          for (int k = 0; k < 4; ++k) q[k] = vertex(corner[k][0], corner[k][1], corner[k][2]);
          if (side == 1) {
            s.t(q[0], q[1], q[2]);
            s.t(q[0], q[2], q[3]);
          } else {
            s.t(q[0], q[2], q[1]);
            s.t(q[0], q[3], q[2]);
          }
        }
  return s;
}

}  // namespace

TEST_CASE("closed surfaces with folded fans: the driver finds exactly the brute-force pairs") {
  std::mt19937 rng(2024);
  for (const bool integer_dents : {true, false}) {
    CAPTURE(integer_dents);
    Soup s = grid_cube_surface(5);
    const volmap::SelfIntersectionResult clean = find_self_intersections(s.xyz, s.tris);
    CHECK(clean.clean());
    // Move some vertices: by small integers (exact coplanar folds and touching) or by real offsets.
    const std::size_t nv = s.xyz.size() / 3;
    std::uniform_int_distribution<std::size_t> pick(0, nv - 1);
    std::uniform_int_distribution<int> step(-2, 2);
    std::uniform_real_distribution<double> offset(-1.5, 1.5);
    for (int k = 0; k < 12; ++k) {
      const std::size_t v = pick(rng);
      for (int c = 0; c < 3; ++c) s.xyz[3 * v + c] += integer_dents ? double(step(rng)) : offset(rng);
    }
    const BruteForce expected = brute_force(s, 5);
    volmap::SelfIntersectionOptions options;
    options.max_reported = 5;
    for (const bool parallel : {false, true}) {
      options.parallel = parallel;
      const volmap::SelfIntersectionResult r = find_self_intersections(s.xyz, s.tris, options);
      CHECK(r.intersecting_pairs == expected.pairs);
      CHECK(r.first_pairs == expected.first);
    }
    MESSAGE((s.tris.size() / 3) << " triangles, " << expected.pairs << " intersecting pairs, "
                                << expected.adjacent_pairs << " of them adjacent");
    CHECK(expected.adjacent_pairs > 0);  // folds inside fans: the per-vertex settling must not hide them
    CHECK(expected.pairs > expected.adjacent_pairs);
  }
}

TEST_CASE("a closed fan whose projection winds twice around its vertex is not settled by its fan") {
  // Ring b_k at angle 4πk/7 below a: every projected triangle (a, b_{k+1}, b_k) has the same
  // orientation, but the ring is the star polygon {7/2}, so triangles sharing only a cross.
  Soup fan;
  const std::uint32_t a = fan.v(0, 0, 0);
  std::uint32_t ring[7];
  for (int k = 0; k < 7; ++k)
    ring[k] = fan.v(std::cos(4 * M_PI * k / 7), std::sin(4 * M_PI * k / 7), -1.0 - 0.01 * k);
  for (int k = 0; k < 7; ++k) fan.t(a, ring[(k + 1) % 7], ring[k]);
  const BruteForce expected = brute_force(fan, 0);
  CHECK(expected.pairs > 0);
  CHECK(find_self_intersections(fan.xyz, fan.tris).intersecting_pairs == expected.pairs);
}

#if defined(__SSE2__)
TEST_CASE("self-intersections of a dented surface at float-denormal scale, under FTZ|DAZ as by default") {
  // The float pre-selection converts the boxes outside any predicate scope, so the caller's flush
  // modes apply there: scaled to 1e-40 (below float's smallest normal) the boxes flush towards 0,
  // and the pairs found must not change.
  Soup s = grid_cube_surface(5);
  std::mt19937 rng(99);
  std::uniform_int_distribution<std::size_t> pick(0, s.xyz.size() / 3 - 1);
  std::uniform_real_distribution<double> offset(-1.5, 1.5);
  for (int k = 0; k < 12; ++k) {
    const std::size_t v = pick(rng);
    for (int c = 0; c < 3; ++c) s.xyz[3 * v + c] += offset(rng);
  }
  for (double& x : s.xyz) x *= 1e-40;
  const volmap::SelfIntersectionResult plain = find_self_intersections(s.xyz, s.tris);
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(saved | 0x8040u);  // FTZ (bit 15) | DAZ (bit 6)
  const volmap::SelfIntersectionResult flushed = find_self_intersections(s.xyz, s.tris);
  _mm_setcsr(saved);
  CHECK(plain.intersecting_pairs > 0);
  CHECK(plain.intersecting_pairs == brute_force(s, 0).pairs);
  CHECK(flushed.intersecting_pairs == plain.intersecting_pairs);
  CHECK(flushed.candidate_pairs == plain.candidate_pairs);
  CHECK(flushed.first_pairs == plain.first_pairs);
}
#endif
