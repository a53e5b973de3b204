// Chords whose straight image leaves a non-convex domain (docs/mapping.md §3, boundary_image_solid.hpp).
// Oracles are analytic: an L-shaped solid meshed and mapped by the identity (point membership and
// segments between boundary vertices against the two boxes, sampled at rational parameters that hit
// the reflex edge exactly), and VOLMAP's star domain written as 24 triangles, onto which the
// boundary of a coarse Kuhn cube is projected from the centre (chords sampled against the union of
// the cube and its six pyramids). The mapper must then certify with B0 removing those chords. At
// fixed connectivity, a chord whose image crosses a dented boundary gets an exact certificate,
// confirmed by solving the segment-triangle intersection in rationals here.
#include <doctest/doctest.h>

#include <volmap/check/self_intersection.hpp>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/io/io.hpp>
#include <volmap/volume/boundary_image_solid.hpp>
#include <volmap/volume/feasibility.hpp>
#include <volmap/volume/infeasibility.hpp>
#include <volmap/volume/map_stages.hpp>
#include <volmap/volume/map_state.hpp>
#include <volmap/volume/volume_map.hpp>
#include <volmap/predicates.hpp>
#include <volmap/predicates_rational.hpp>

#include "map_test_meshes.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>

namespace {

using P3 = std::array<double, 3>;

// [0,2]×[0,2]×[0,2] minus the block x > 1, y > 1: a Kuhn grid of 2×2×2 cells without the two cells
// of that block; the unused corner vertices are dropped.
volmap::TetMeshData l_shape() {
  const volmap::TetMeshData grid = volmap::generate_kuhn_grid(2, 2, 2, 1.0);
  volmap::TetMeshData m;
  std::vector<std::uint32_t> new_id(grid.num_vertices(), UINT32_MAX);
  for (std::size_t t = 0; t < grid.num_tets(); ++t) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) c[i] += grid.xyz[3 * grid.tets[4 * t + k] + i] / 4;
    if (c[0] > 1 && c[1] > 1) continue;
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t v = grid.tets[4 * t + k];
      if (new_id[v] == UINT32_MAX) {
        new_id[v] = std::uint32_t(m.num_vertices());
        for (int i = 0; i < 3; ++i) m.xyz.push_back(grid.xyz[3 * v + i]);
      }
      m.tets.push_back(new_id[v]);
    }
  }
  m.tet_labels.assign(m.num_tets(), 0);
  return m;
}

// Strictly inside the open L-shape, by a margin.
bool in_l(const double* p, double margin) {
  for (int i = 0; i < 3; ++i)
    if (!(p[i] > margin && p[i] < 2 - margin)) return false;
  return p[0] < 1 - margin || p[1] < 1 - margin;
}

// VOLMAP's star (domain.cpp): the cube [0,100]^3 with a pyramid of height 100 on each face.
struct Star {
  std::vector<std::array<P3, 3>> tris;  // outward
  Star() {
    const P3 apex[6] = {{-100, 50, 50}, {200, 50, 50}, {50, -100, 50}, {50, 200, 50}, {50, 50, -100}, {50, 50, 200}};
    for (int k = 0; k < 6; ++k) {
      const int axis = k / 2;
      const double at = k % 2 ? 100 : 0;
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      const double corner[4][2] = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
      for (int j = 0; j < 4; ++j) {
        P3 a{}, b{};
        a[axis] = b[axis] = at;
        a[u] = corner[j][0], a[w] = corner[j][1];
        b[u] = corner[(j + 1) % 4][0], b[w] = corner[(j + 1) % 4][1];
        // Outward: the cube's centre sees (apex, a, b) or (apex, b, a) on its inner side.
        const P3 centre{50, 50, 50};
        std::array<P3, 3> t{apex[k], a, b};
        if (volmap::orient3d(t[0].data(), t[1].data(), t[2].data(), centre.data()) < 0) std::swap(t[1], t[2]);
        tris.push_back(t);
      }
    }
  }
  // Closed membership with a tolerance (eps > 0 grows the star, eps < 0 shrinks it).
  static bool contains(const P3& p, double eps) {
    bool in_cube = true;
    for (double c : p) in_cube = in_cube && c >= -eps && c <= 100 + eps;
    if (in_cube) return true;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        const double depth = side ? p[axis] - 100 : -p[axis];
        if (depth < -eps || depth > 100 + eps) continue;
        const double half = 50 * (1 - depth / 100) + eps;
        bool inside = true;
        for (int i = 0; i < 3; ++i)
          if (i != axis) inside = inside && std::abs(p[i] - 50) <= half;
        if (inside) return true;
      }
    return false;
  }
  // Where the ray from the centre along u leaves the star (it is star-shaped about the centre).
  P3 project(const P3& u) const {
    const P3 c{50, 50, 50};
    double best = 1e300;
    for (const auto& t : tris) {  // Möller–Trumbore in doubles; the image only has to be near ∂star
      P3 e1, e2, s, h, q;
      for (int i = 0; i < 3; ++i) e1[i] = t[1][i] - t[0][i], e2[i] = t[2][i] - t[0][i], s[i] = c[i] - t[0][i];
      h = {u[1] * e2[2] - u[2] * e2[1], u[2] * e2[0] - u[0] * e2[2], u[0] * e2[1] - u[1] * e2[0]};
      const double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
      if (std::abs(det) < 1e-14) continue;
      const double beta = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / det;
      q = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
      const double gamma = (u[0] * q[0] + u[1] * q[1] + u[2] * q[2]) / det;
      const double tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
      if (beta >= -1e-12 && gamma >= -1e-12 && beta + gamma <= 1 + 1e-12 && tt > 0) best = std::min(best, tt);
    }
    return {c[0] + best * u[0], c[1] + best * u[1], c[2] + best * u[2]};
  }
};

// The boundary of the Kuhn cube with n cells per side, projected from its centre onto the star.
volmap::BoundaryMap star_map_of(const volmap::TetMeshData& cube) {
  const Star star;
  volmap::BoundaryMap map;
  for (std::uint32_t v : volmap::boundary_vertex_ids(cube)) {
    const P3 u{cube.xyz[3 * v] - 0.5, cube.xyz[3 * v + 1] - 0.5, cube.xyz[3 * v + 2] - 0.5};
    const P3 p = star.project(u);
    map.vids.push_back(v);
    map.xyz.insert(map.xyz.end(), p.begin(), p.end());
  }
  return map;
}

// Does the closed segment pq meet the closed triangle abc? Cramer's rule in rationals on
// p + t (q − p) = a + u (b − a) + w (c − a); a segment parallel to the triangle's plane counts as
// "no" (the certificates under test never need that case).
bool rational_segment_meets_triangle(const double* p, const double* q, const double* a, const double* b, const double* c) {
  using volmap::Rational;
  Rational m[3][3], r[3];
  for (int i = 0; i < 3; ++i) {
    m[i][0] = Rational(q[i]) - Rational(p[i]);   // t
    m[i][1] = Rational(a[i]) - Rational(b[i]);   // u (moved to the left side)
    m[i][2] = Rational(a[i]) - Rational(c[i]);   // w
    r[i] = Rational(a[i]) - Rational(p[i]);
  }
  auto det = [](const Rational (&x)[3][3]) {
    return x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) - x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0]) +
           x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
  };
  const Rational d = det(m);
  if (d == 0) return false;
  Rational sol[3];
  for (int k = 0; k < 3; ++k) {
    Rational mk[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) mk[i][j] = j == k ? r[i] : m[i][j];
    sol[k] = det(mk) / d;
  }
  return sol[0] >= 0 && sol[0] <= 1 && sol[1] >= 0 && sol[2] >= 0 && sol[1] + sol[2] <= 1;
}

}  // namespace

TEST_CASE("boundary image solid: an L-shaped solid under the identity — points and chords against the two boxes") {
  const volmap::TetMeshData m = l_shape();
  REQUIRE(m.num_tets() == 36);
  const volmap::TetMesh mesh(m);
  const volmap::BoundaryImageSolid solid(mesh, m.xyz);
  std::size_t checked = 0;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j)
      for (int k = 0; k <= 20; ++k) {
        const double p[3] = {-0.05 + 0.105 * i, -0.05 + 0.105 * j, -0.05 + 0.105 * k};
        const bool near = !in_l(p, 1e-9) && in_l(p, -1e-9);  // within 1e-9 of ∂L: not decided here
        if (near) continue;
        CHECK(solid.contains(p) == in_l(p, 0));
        ++checked;
      }
  CHECK(checked > 8000);
  // Every pair of boundary vertices: the segment leaves unless its inner samples are strictly inside
  // (the reflex edge x = y = 1 is met at parameters with small denominators, all sampled).
  const std::vector<std::uint32_t> bv = volmap::boundary_vertex_ids(m);
  std::size_t leaving = 0, inside = 0;
  for (std::size_t x = 0; x < bv.size(); ++x)
    for (std::size_t y = x + 1; y < bv.size(); ++y) {
      const double *a = &m.xyz[3 * bv[x]], *b = &m.xyz[3 * bv[y]];
      bool all_inside = true;
      for (int s = 1; s < 840 && all_inside; ++s) {
        const double t = s / 840.0;
        const double p[3] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
        all_inside = in_l(p, 1e-12);
      }
      INFO("vertices " << bv[x] << " " << bv[y]);
      CHECK(solid.segment_leaves(bv[x], bv[y]) == !all_inside);
      (all_inside ? inside : leaving) += 1;
    }
  MESSAGE("L-shape: " << leaving << " boundary-vertex segments leave, " << inside << " stay inside");
  CHECK(leaving > 0);
  CHECK(inside > 0);
  // The mesh's own interior edges and faces are inside (the identity is a valid map).
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const std::uint32_t* v = &m.tets[4 * t];
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (std::count(bv.begin(), bv.end(), v[a]) && std::count(bv.begin(), bv.end(), v[b])) {
          const double* p = &m.xyz[3 * v[a]];
          const double* q = &m.xyz[3 * v[b]];
          const double mid[3] = {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
          if (in_l(mid, 1e-12)) CHECK_FALSE(solid.segment_leaves(v[a], v[b]));
        }
  }
}

TEST_CASE("B0 on the star: chords across a valley are blocking, and the refined map certifies") {
  const volmap::TetMeshData cube = map_test::kuhn_grid(3);  // 162 tets, 8 interior vertices
  const volmap::BoundaryMap map = star_map_of(cube);
  volmap::MapState state(cube, map);
  const volmap::FeasibilityReport report = volmap::analyze_feasibility(state);
  const std::set<std::array<std::uint32_t, 2>> blocking(report.blocking_chord_edges.begin(), report.blocking_chord_edges.end());
  const std::vector<double>& target = state.target_xyz();
  std::size_t outside = 0;
  for (const auto& e : report.chord_edges) {
    const double *a = &target[3 * e[0]], *b = &target[3 * e[1]];
    bool leaves = false;
    for (int s = 1; s < 64 && !leaves; ++s) {
      const double t = s / 64.0;
      leaves = !Star::contains({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])}, 1e-3);
    }
    if (!leaves) continue;
    ++outside;
    INFO("chord " << e[0] << " " << e[1]);
    CHECK(blocking.count({std::min(e[0], e[1]), std::max(e[0], e[1])}) == 1);
  }
  MESSAGE("Kuhn cube 3 -> star: " << report.chord_edges.size() << " chord edges, " << outside << " pass outside the star, "
                                  << report.blocking_chord_edges.size() << " blocking");
  REQUIRE(outside > 0);

  volmap::VolumeMapOptions options;
  options.max_threads = 1;
  options.time_limit_seconds = 30;
  const auto r = volmap::compute_volume_map(cube, map, options);
  CHECK(r.certified);
  CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
  CHECK(volmap::count_nonpositive(r.source.xyz, r.source.tets) == 0);
}

TEST_CASE("fixed connectivity: a chord whose image crosses a dented boundary face gets an exact certificate, confirmed in rationals") {
  // Kuhn grid 2 (one interior vertex; its chords join boundary vertices through one cell). Boundary
  // images: the grid's own positions with every boundary vertex moved by up to 0.45 (seeded). The
  // first draw whose image is embedded (exact self-intersection test) and in which some chord's image
  // meets a boundary face away from its ends (rational oracle below) is the case.
  const volmap::TetMeshData cube = map_test::kuhn_grid(2);
  const std::vector<std::uint32_t> bv = volmap::boundary_vertex_ids(cube);
  std::vector<std::uint8_t> locked(cube.num_vertices(), 0);
  for (std::uint32_t v : bv) locked[v] = 1;
  std::set<std::array<std::uint32_t, 3>> faces;
  std::set<std::array<std::uint32_t, 2>> boundary_edges;
  std::vector<std::uint32_t> tris;
  for (std::uint64_t h : volmap::boundary_half_faces(cube)) {
    auto f = volmap::half_face_vertices(cube, h);
    tris.insert(tris.end(), f.begin(), f.end());
    std::sort(f.begin(), f.end());
    faces.insert(f);
    boundary_edges.insert({f[0], f[1]});
    boundary_edges.insert({f[1], f[2]});
    boundary_edges.insert({f[0], f[2]});
  }
  std::set<std::array<std::uint32_t, 2>> chords;
  for (std::size_t t = 0; t < cube.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const std::uint32_t a = std::min(cube.tets[4 * t + i], cube.tets[4 * t + j]), b = std::max(cube.tets[4 * t + i], cube.tets[4 * t + j]);
        if (locked[a] && locked[b] && !boundary_edges.count({a, b})) chords.insert({a, b});
      }
  REQUIRE(!chords.empty());
  auto crossing = [&](const std::vector<double>& X, const std::array<std::uint32_t, 2>& e, const std::array<std::uint32_t, 3>& f) {
    if (std::count(f.begin(), f.end(), e[0]) || std::count(f.begin(), f.end(), e[1])) return false;
    return rational_segment_meets_triangle(&X[3 * e[0]], &X[3 * e[1]], &X[3 * f[0]], &X[3 * f[1]], &X[3 * f[2]]);
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> shift(-0.45, 0.45);
  std::vector<double> target;
  std::size_t crossings = 0;
  int draw = 0;
  for (; draw < 5000 && crossings == 0; ++draw) {
    target = cube.xyz;
    for (std::uint32_t v : bv)
      for (int i = 0; i < 3; ++i) target[3 * v + i] += shift(rng);
    if (!volmap::find_self_intersections(target, tris).clean()) continue;
    for (const auto& e : chords)
      for (const auto& f : faces) crossings += crossing(target, e, f);
  }
  MESSAGE("draw " << draw << ": " << crossings << " (chord, boundary face) crossings");
  REQUIRE(crossings > 0);

  volmap::InfeasibilityOptions options;
  options.max_certificates = 0;
  const auto certificates = volmap::find_local_infeasibility(volmap::TetMesh(cube), locked, target, options);
  std::size_t found = 0;
  for (const auto& c : certificates) {
    if (c.kind != volmap::InfeasibilityKind::ChordTouchesBoundary) continue;
    ++found;
    INFO(volmap::describe(c));
    REQUIRE(c.simplex.size() == 2);
    REQUIRE(c.boundary_face.size() == 3);
    const std::array<std::uint32_t, 2> e = {std::min(c.simplex[0], c.simplex[1]), std::max(c.simplex[0], c.simplex[1])};
    CHECK(chords.count(e) == 1);
    const std::uint32_t* t = &cube.tets[4 * c.tet];
    CHECK(std::count(t, t + 4, e[0]) == 1);
    CHECK(std::count(t, t + 4, e[1]) == 1);
    std::array<std::uint32_t, 3> f = {c.boundary_face[0], c.boundary_face[1], c.boundary_face[2]};
    std::sort(f.begin(), f.end());
    CHECK(faces.count(f) == 1);
    CHECK(crossing(target, e, f));
  }
  // Every crossing chord is found (one certificate per chord: the first face it meets).
  std::set<std::array<std::uint32_t, 2>> crossing_chords;
  for (const auto& e : chords)
    for (const auto& f : faces)
      if (crossing(target, e, f)) crossing_chords.insert(e);
  CHECK(found == crossing_chords.size());

  // The mapper at fixed connectivity reports the certificate and claims no map.
  volmap::BoundaryMap map;
  for (std::uint32_t v : bv) {
    map.vids.push_back(v);
    map.xyz.insert(map.xyz.end(), &target[3 * v], &target[3 * v] + 3);
  }
  volmap::VolumeMapOptions mo;
  mo.allow_refinement = false;
  mo.max_threads = 1;
  mo.time_limit_seconds = 10;
  const auto r = volmap::compute_volume_map(cube, map, mo);
  CHECK_FALSE(r.certified);
  CHECK(std::any_of(r.infeasibility.begin(), r.infeasibility.end(),
                    [](const auto& c) { return c.kind == volmap::InfeasibilityKind::ChordTouchesBoundary; }));
}

TEST_CASE("a self-overlapping boundary image bounds no solid: LIM's armadillo keeps its chords and maps at fixed connectivity") {
  // LIM's deformation benchmark: the initial map's boundary overlaps itself (530 triangle pairs
  // cross), yet a map with every tet positive exists at the input connectivity. Chords of such a
  // map may cross the boundary image, so none may be called blocking for leaving it (98 were, and
  // the mapper refined and failed where it had certified in 0.6 s).
  VOLMAP_REQUIRE_DATA(rest_path, "maps/lim_benchmark/armadillo-598-rest.vtk");
  VOLMAP_REQUIRE_DATA(init_path, "maps/lim_benchmark/armadillo-598-init.vtk");
  const volmap::TetMeshData rest = volmap::read_tet_mesh(rest_path.string());
  const volmap::TetMeshData init = volmap::read_tet_mesh(init_path.string());
  volmap::BoundaryMap map;
  for (std::uint32_t v : volmap::boundary_vertex_ids(rest)) {
    map.vids.push_back(v);
    map.xyz.insert(map.xyz.end(), &init.xyz[3 * v], &init.xyz[3 * v] + 3);
  }
  volmap::MapState state(rest, map, init.xyz);
  const volmap::TetMesh& mesh = state.source;
  REQUIRE_FALSE(volmap::boundary_image_is_embedded(mesh, state.target_xyz()));
  const volmap::FeasibilityReport report = volmap::analyze_feasibility(state);
  CHECK(report.blocking_chord_edges.empty());
  CHECK(report.blocking_chord_faces.empty());

  volmap::VolumeMapOptions options;
  options.allow_refinement = false;
  options.max_threads = 1;
  options.time_limit_seconds = 30;
  options.initial_xyz = init.xyz;
  const auto r = volmap::compute_volume_map(rest, map, options);
  CHECK(r.certified);
  CHECK(volmap::count_nonpositive(r.target_xyz, r.source.tets) == 0);
}
