// Exact local infeasibility certificates (infeasibility.hpp, mapping.md §10): constructed impossible
// cases give a certificate that an independent exact oracle (rationals computed here) confirms;
// feasible cases, shown feasible by an exactly checked witness point, never get one.
#include <doctest/doctest.h>

#include <volmap/core/tet_mesh.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates_rational.hpp>
#include <volmap/volume/infeasibility.hpp>
#include <volmap/volume/kernel_lp.hpp>
#include <volmap/volume/volume_map.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include <nlohmann/json.hpp>

#include "../../predicates/testing/oracle.hpp"
#include "test_support.hpp"
#include "map_test_meshes.hpp"
#include "vmap_test_util.hpp"

namespace {

using volmap::InfeasibilityKind;
using volmap::Rational;

// A bipyramid over the base A B C with apexes N (up) and S (down) around one free vertex v = 0 at
// the origin: ids v=0, A=1, B=2, C=3, N=4, S=5; each tet is (outward boundary face, v).
volmap::TetMeshData bipyramid() {
  volmap::TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, -0.5, 0.875, 0, -0.5, -0.875, 0, 0, 0, 1, 0, 0, -1};
  m.tets = {1, 2, 4, 0, 2, 3, 4, 0, 3, 1, 4, 0, 2, 1, 5, 0, 3, 2, 5, 0, 1, 3, 5, 0};
  return m;
}
const std::vector<std::uint8_t> kBipyramidLocked = {0, 1, 1, 1, 1, 1};

std::vector<volmap::InfeasibilityCertificate> certificates_of(const volmap::TetMeshData& m, const std::vector<std::uint8_t>& locked,
                                                              const std::vector<double>& target) {
  return volmap::find_local_infeasibility(volmap::TetMesh(m), locked, target);
}

bool has_kind(const std::vector<volmap::InfeasibilityCertificate>& cs, InfeasibilityKind k) {
  return std::any_of(cs.begin(), cs.end(), [&](const auto& c) { return c.kind == k; });
}

// The first certificate of kind k (nullptr when there is none).
const volmap::InfeasibilityCertificate* first_of_kind(const std::vector<volmap::InfeasibilityCertificate>& cs, InfeasibilityKind k) {
  const auto it = std::find_if(cs.begin(), cs.end(), [&](const auto& c) { return c.kind == k; });
  return it == cs.end() ? nullptr : &*it;
}

// The mapper at fixed connectivity, 5 s: its result (no map may be claimed where a certificate holds).
volmap::VolumeMapResult map_at_fixed_connectivity(const volmap::TetMeshData& m, const std::vector<std::uint8_t>& locked,
                                                  const std::vector<double>& target) {
  volmap::VolumeMapOptions o;
  o.allow_refinement = false;
  o.time_limit_seconds = 5;
  return volmap::compute_volume_map(m, map_test::boundary_map_of(locked, target), o);
}

// Independent oracle for an EmptyLinkKernel certificate of the bipyramid: each constraint tet is
// (a, b, c, v) with v last, so its constraint is orient3d(a, b, c, x) > 0, i.e. n·x > n·a with
// n = (c − a) × (b − a); the multipliers must be >= 0, not all 0, Σλn = 0 and Σλ n·a >= 0.
bool oracle_farkas(const volmap::TetMeshData& m, const std::vector<double>& X, const volmap::InfeasibilityCertificate& c) {
  Rational sx = 0, sy = 0, sz = 0, sd = 0;
  bool positive = false;
  for (std::size_t j = 0; j < c.constraint_tets.size(); ++j) {
    const std::uint32_t* t = &m.tets[4 * c.constraint_tets[j]];
    if (t[3] != c.simplex[0]) return false;
    Rational p[3][3];
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) p[k][i] = X[3 * t[k] + i];
    const Rational u[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const Rational w[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const Rational n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const Rational& l = c.multipliers[j];
    if (l < 0) return false;
    positive = positive || l > 0;
    sx += l * n[0];
    sy += l * n[1];
    sz += l * n[2];
    sd += l * (n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2]);
  }
  return positive && sx == 0 && sy == 0 && sz == 0 && sd >= 0;
}

}  // namespace

TEST_CASE("a fixed tet with an inverted, flat or collinear image gets the matching certificate") {
  volmap::TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  m.tets = {0, 1, 2, 3};
  if (volmap::orient3d(&m.xyz[0], &m.xyz[3], &m.xyz[6], &m.xyz[9]) < 0) std::swap(m.tets[2], m.tets[3]);
  const std::vector<std::uint8_t> locked(4, 1);
  CHECK(certificates_of(m, locked, m.xyz).empty());  // the identity is feasible

  std::vector<double> swapped = m.xyz;  // two images exchanged: orient3d < 0
  std::swap_ranges(swapped.begin(), swapped.begin() + 3, swapped.begin() + 3);
  auto cs = certificates_of(m, locked, swapped);
  REQUIRE(cs.size() == 1);
  CHECK(cs[0].kind == InfeasibilityKind::FixedTet);
  CHECK(cs[0].tet == 0);
  const std::uint32_t* t = m.tets.data();
  CHECK(volmap::orient3d(&swapped[3 * t[0]], &swapped[3 * t[1]], &swapped[3 * t[2]], &swapped[3 * t[3]]) < 0);

  std::vector<double> coincident = m.xyz;  // vertex 1 onto vertex 0
  std::copy(coincident.begin(), coincident.begin() + 3, coincident.begin() + 3);
  cs = certificates_of(m, locked, coincident);
  CHECK(has_kind(cs, InfeasibilityKind::CoincidentEdge));
  CHECK(has_kind(cs, InfeasibilityKind::FixedTet));

  std::vector<double> collinear = m.xyz;  // vertex 2 at 3·(vertex 1): 0, 1, 2 on the x axis
  collinear[6] = 3, collinear[7] = 0, collinear[8] = 0;
  cs = certificates_of(m, locked, collinear);
  REQUIRE(has_kind(cs, InfeasibilityKind::DegenerateFace));
  CHECK(!has_kind(cs, InfeasibilityKind::CoincidentEdge));
  for (const auto& c : cs) CHECK(volmap::verify_certificate(volmap::TetMesh(m), locked, collinear, c));
}

TEST_CASE("a folded bipyramid link has an empty strict kernel with an exact Farkas certificate") {
  const volmap::TetMeshData m = bipyramid();
  const volmap::TetMesh mesh(m);
  for (std::size_t t = 0; t < m.num_tets(); ++t)
    REQUIRE(volmap::orient3d(&m.xyz[3 * m.tets[4 * t]], &m.xyz[3 * m.tets[4 * t + 1]], &m.xyz[3 * m.tets[4 * t + 2]],
                             &m.xyz[3 * m.tets[4 * t + 3]]) > 0);
  CHECK(certificates_of(m, kBipyramidLocked, m.xyz).empty());  // the source itself is a valid map

  std::vector<double> folded = m.xyz;  // N moved below the base and off the axis
  folded[12] = 2, folded[13] = 0, folded[14] = -0.5;
  const auto cs = certificates_of(m, kBipyramidLocked, folded);
  REQUIRE(cs.size() == 1);
  const auto& c = cs[0];
  CHECK(c.kind == InfeasibilityKind::EmptyLinkKernel);
  CHECK(c.simplex == std::vector<std::uint32_t>{0});
  CHECK(oracle_farkas(m, folded, c));
  CHECK(volmap::verify_certificate(mesh, kBipyramidLocked, folded, c));
  CHECK(volmap::describe(c).find("empty-link-kernel: free vertex 0") == 0);

  // Tampered certificates are refused.
  auto bad = c;
  bad.multipliers[0] = -bad.multipliers[0];
  CHECK(!volmap::verify_certificate(mesh, kBipyramidLocked, folded, bad));
  bad = c;
  bad.multipliers[0] *= 2;
  CHECK(!volmap::verify_certificate(mesh, kBipyramidLocked, folded, bad));
  bad = c;
  bad.simplex = {1};  // a locked vertex
  CHECK(!volmap::verify_certificate(mesh, kBipyramidLocked, folded, bad));
  CHECK(!volmap::verify_certificate(mesh, kBipyramidLocked, m.xyz, c));  // the same constraints, unfolded

  // The mapper at fixed connectivity reports it and certifies nothing; the boundary image still
  // encloses a positive volume, so this is not the any-refinement obstruction.
  volmap::BoundaryMap map;
  for (std::uint32_t v = 1; v < 6; ++v) {
    map.vids.push_back(v);
    map.xyz.insert(map.xyz.end(), folded.begin() + 3 * v, folded.begin() + 3 * v + 3);
  }
  volmap::VolumeMapOptions o;
  o.allow_refinement = false;
  o.time_limit_seconds = 5;
  const auto r = volmap::compute_volume_map(m, map, o);
  CHECK(!r.certified);
  CHECK(!r.feasibility.infeasible_with_any_refinement());
  REQUIRE(r.infeasibility.size() == 1);
  CHECK(r.infeasibility[0].kind == InfeasibilityKind::EmptyLinkKernel);
}

TEST_CASE("random bipyramid images: a certificate and an exactly checked kernel point never coexist") {
  const volmap::TetMeshData m = bipyramid();
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> jitter(-0.9, 0.9);
  int feasible = 0, certified_empty = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<double> X = m.xyz;
    for (std::size_t k = 3; k < X.size(); ++k) X[k] += jitter(rng);
    // Witness: a point strictly inside every link face (exact orient3d), from the kernel LP.
    std::vector<double> tri;
    for (std::size_t t = 0; t < m.num_tets(); ++t)
      for (int k = 0; k < 3; ++k) tri.insert(tri.end(), &X[3 * m.tets[4 * t + k]], &X[3 * m.tets[4 * t + k]] + 3);
    double q[3];
    bool witness = volmap::strict_kernel_point(tri, q);
    if (witness)
      for (std::size_t t = 0; t < m.num_tets(); ++t)
        witness = witness && volmap::orient3d(&X[3 * m.tets[4 * t]], &X[3 * m.tets[4 * t + 1]], &X[3 * m.tets[4 * t + 2]], q) > 0;
    const auto cs = certificates_of(m, kBipyramidLocked, X);
    for (const auto& c : cs) CHECK(oracle_farkas(m, X, c));
    CHECK(!(witness && !cs.empty()));
    feasible += witness;
    certified_empty += !cs.empty();
  }
  // Both outcomes occur, so the test exercises both sides.
  CHECK(feasible > 20);
  CHECK(certified_empty > 20);
}

TEST_CASE("volmap-map --no-refine --json: the folded bipyramid is reported infeasible with its certificate, exit 1") {
  const volmap::TetMeshData m = bipyramid();
  const std::filesystem::path dir = volmap_test::scratch_dir("infeasible_bipyramid");
  volmap::write_medit((dir / "in.mesh").string(), m);
  {
    std::ofstream map(dir / "map.txt");
    map.precision(17);
    const double folded_n[3] = {2, 0, -0.5};
    for (std::uint32_t v = 1; v < 6; ++v) {
      const double* p = v == 4 ? folded_n : &m.xyz[3 * v];
      map << v << " " << p[0] << " " << p[1] << " " << p[2] << "\n";
    }
  }
  const auto r = vmap_test::run(volmap_test::tool("volmap-map").string() + " " + (dir / "in.mesh").string() + " " +
                                (dir / "map.txt").string() + " " + (dir / "out.mesh").string() + " --no-refine --json --time-limit 5");
  CHECK(r.code == 1);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["certified"] == false);
  REQUIRE(j.contains("infeasible"));
  CHECK(j["infeasible"]["scope"] == "this-connectivity");
  REQUIRE(j["infeasible"]["certificates"].size() == 1);
  const auto& c = j["infeasible"]["certificates"][0];
  CHECK(c["kind"] == "empty-link-kernel");
  CHECK(c["simplex"] == std::vector<std::uint32_t>{0});
  CHECK(c["constraint_tets"].size() == c["multipliers"].size());
  CHECK(c["constraint_tets"].size() >= 2);
  std::filesystem::remove_all(dir);
}

namespace {

// A pyramid over a flat quad floor a q b d with apex t, and one free vertex w inside the tet
// (a, b, c, q) of the source; c is a floor vertex inside the triangle a q b. Around the floor edge ab
// the fan runs c → w → q → t → d. In the source q is lifted (the tet a b c q has volume); in the
// target q lies on the floor, on c's side of ab: the tets from c through w to q would have to turn a
// full circle about ab. Ids a=0 b=1 c=2 d=3 q=4 t=5 w=6; each tet ordered VOLMAP-positive in the source.
struct FlatFloorFan {
  volmap::TetMeshData mesh;
  std::vector<std::uint8_t> locked = {1, 1, 1, 1, 1, 1, 0};
  std::vector<double> target;
  FlatFloorFan() {
    mesh.xyz = {0, 0, 0, 2, 0, 0, 1, -1, 0, 1, 1, 0, 1, -1.5, 1, 1, 0, 2, 1, -0.6, 0.25};
    mesh.tets = {0, 1, 2, 6, 0, 1, 4, 6, 0, 2, 4, 6, 1, 2, 4, 6, 0, 1, 4, 5, 0, 1, 5, 3};
    for (std::size_t t = 0; t < mesh.tets.size(); t += 4) {
      const double* x = mesh.xyz.data();
      if (volmap::orient3d(x + 3 * mesh.tets[t], x + 3 * mesh.tets[t + 1], x + 3 * mesh.tets[t + 2], x + 3 * mesh.tets[t + 3]) < 0)
        std::swap(mesh.tets[t], mesh.tets[t + 1]);
    }
    target = mesh.xyz;
    target[3 * 4 + 1] = -2, target[3 * 4 + 2] = 0;  // q on the floor, beyond c
    target[3 * 5 + 1] = -0.5;                       // t above the quad's middle (a convex pyramid)
  }
};

// Independent oracle (GMP rationals, predicates/testing/oracle.hpp) of same_half_plane on ids.
bool oracle_same_half_plane(const std::vector<double>& X, std::uint32_t a, std::uint32_t b, std::uint32_t p, std::uint32_t q) {
  return volmap_oracle::same_half_plane(&X[3 * a], &X[3 * b], &X[3 * p], &X[3 * q]);
}

}  // namespace

TEST_CASE("an edge fan whose fixed ring vertices share a half-plane of the edge's line: an exact edge-fan-wraps certificate") {
  const FlatFloorFan f;
  const volmap::TetMesh mesh(f.mesh);
  REQUIRE(volmap::count_nonpositive(f.mesh.xyz, f.mesh.tets) == 0);  // a valid source
  const auto cs = certificates_of(f.mesh, f.locked, f.target);
  const volmap::InfeasibilityCertificate* found = first_of_kind(cs, InfeasibilityKind::EdgeFanWraps);
  REQUIRE(found != nullptr);
  const volmap::InfeasibilityCertificate& c = *found;
  INFO(volmap::describe(c));
  // The edge a b, the ring c (or q) .. w .. q (or c): its ends fixed and in one half-plane (oracle),
  // the free vertex between them, one constraint tet per step.
  CHECK(std::set<std::uint32_t>(c.simplex.begin(), c.simplex.end()) == std::set<std::uint32_t>{0, 1});
  REQUIRE(c.ring.size() == 3);
  CHECK(std::set<std::uint32_t>{c.ring.front(), c.ring.back()} == std::set<std::uint32_t>{2, 4});
  CHECK(c.ring[1] == 6);
  CHECK(c.constraint_tets.size() == 2);
  CHECK(oracle_same_half_plane(f.target, c.simplex[0], c.simplex[1], c.ring.front(), c.ring.back()));
  CHECK(volmap::verify_certificate(mesh, f.locked, f.target, c));
  // The same claim is refused where it does not hold: q lifted off the floor (not coplanar), q moved
  // to d's side of ab, the ring's middle vertex locked, a ring that skips a step of the fan.
  std::vector<double> lifted = f.target;
  lifted[3 * 4 + 2] = 0.25;
  CHECK_FALSE(oracle_same_half_plane(lifted, c.simplex[0], c.simplex[1], c.ring.front(), c.ring.back()));
  CHECK_FALSE(volmap::verify_certificate(mesh, f.locked, lifted, c));
  CHECK_FALSE(has_kind(certificates_of(f.mesh, f.locked, lifted), InfeasibilityKind::EdgeFanWraps));
  std::vector<double> other_side = f.target;
  other_side[3 * 4 + 1] = 0.5;  // on the floor, across ab from c
  CHECK_FALSE(oracle_same_half_plane(other_side, c.simplex[0], c.simplex[1], c.ring.front(), c.ring.back()));
  CHECK_FALSE(volmap::verify_certificate(mesh, f.locked, other_side, c));
  std::vector<std::uint8_t> all_locked(7, 1);
  CHECK_FALSE(volmap::verify_certificate(mesh, all_locked, f.target, c));
  volmap::InfeasibilityCertificate skipping = c;
  skipping.ring = {c.ring.front(), c.ring.back()};
  skipping.constraint_tets = {c.constraint_tets.front()};
  CHECK_FALSE(volmap::verify_certificate(mesh, f.locked, f.target, skipping));
  // The mapper at fixed connectivity stops with the certificate (no map is claimed).
  const auto r = map_at_fixed_connectivity(f.mesh, f.locked, f.target);
  CHECK_FALSE(r.certified);
  CHECK(has_kind(r.infeasibility, InfeasibilityKind::EdgeFanWraps));
}

namespace {

// An octahedron N, S over the ring x1..x4 with an interior edge uv on its axis: ids u=0, v=1, ring
// 2..5, N=6, S=7; tets (u, v, x_i, x_i+1), (v, N, ...) and (u, S, ...), oriented positive. Only u and
// v are free. In the image the ring is a bow-tie in z = 0, so no line (no placement of u and v) sees
// the four ring edges turn one way. (u's and v's cones over the same ring are empty kernels too, by
// the same argument for the lines uS and vN; on G1 the free edge is stuck alone, see the data test.)
struct FreeEdgeOverBowtie {
  volmap::TetMeshData mesh;
  std::vector<std::uint8_t> locked = {0, 0, 1, 1, 1, 1, 1, 1};
  std::vector<double> target;
  FreeEdgeOverBowtie() {
    mesh.xyz = {0, 0, -0.3, 0, 0, 0.3, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    for (std::uint32_t i = 0; i < 4; ++i) {
      const std::uint32_t a = 2 + i, b = 2 + (i + 1) % 4;
      for (std::array<std::uint32_t, 4> t : {std::array<std::uint32_t, 4>{0, 1, a, b}, {1, 6, a, b}, {0, 7, a, b}}) {
        const double* x = mesh.xyz.data();
        if (volmap::orient3d(x + 3 * t[0], x + 3 * t[1], x + 3 * t[2], x + 3 * t[3]) < 0) std::swap(t[2], t[3]);
        mesh.tets.insert(mesh.tets.end(), t.begin(), t.end());
      }
    }
    target = mesh.xyz;
    const double bowtie[4][2] = {{-1, -1}, {1, 1}, {1, -1}, {-1, 1}};
    for (int i = 0; i < 4; ++i) target[3 * (2 + i)] = bowtie[i][0], target[3 * (2 + i) + 1] = bowtie[i][1];
  }
};

// Exact 4×4 determinant det[p_i 1] of a tet with u's and v's images replaced by U and V (oracle
// rationals, Laplace expansion): the tet's orient3d as a function of the free pair.
volmap_oracle::Q tet_det(const volmap::TetMeshData& m, const std::vector<double>& X, std::uint32_t t, const volmap_oracle::Q* U,
                         const volmap_oracle::Q* V, std::uint32_t u, std::uint32_t v) {
  using volmap_oracle::Q;
  Q a[4][4];
  for (int r = 0; r < 4; ++r) {
    const std::uint32_t w = m.tets[4 * t + std::size_t(r)];
    for (int i = 0; i < 3; ++i) a[r][i] = w == u ? U[i] : w == v ? V[i] : Q(X[3 * w + std::size_t(i)]);
    a[r][3] = 1;
  }
  auto det3 = [&](int skip_row, int c0, int c1, int c2) {
    int r[3], k = 0;
    for (int i = 0; i < 4; ++i)
      if (i != skip_row) r[k++] = i;
    return a[r[0]][c0] * (a[r[1]][c1] * a[r[2]][c2] - a[r[1]][c2] * a[r[2]][c1]) -
           a[r[0]][c1] * (a[r[1]][c0] * a[r[2]][c2] - a[r[1]][c2] * a[r[2]][c0]) +
           a[r[0]][c2] * (a[r[1]][c0] * a[r[2]][c1] - a[r[1]][c1] * a[r[2]][c0]);
  };
  Q d = 0;  // expansion along the last column (all ones)
  for (int r = 0; r < 4; ++r) d += ((r % 2 == 0) ? -1 : 1) * det3(r, 0, 1, 2);
  return d;
}

// Independent oracle for a FreeEdgeLine certificate: Σ λ_j orient3d(tet_j) is the zero polynomial in
// the free pair's images (checked exactly at random rational points), so the orientations cannot all
// be positive; and λ >= 0, not all zero.
bool oracle_free_edge_line(const volmap::TetMeshData& m, const std::vector<double>& X, const volmap::InfeasibilityCertificate& c) {
  using volmap_oracle::Q;
  if (c.simplex.size() != 2 || c.multipliers.size() != c.constraint_tets.size()) return false;
  bool positive = false;
  for (const Rational& l : c.multipliers) {
    if (l < 0) return false;
    positive = positive || l > 0;
  }
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> g(-1000, 1000);
  for (int it = 0; it < 12; ++it) {
    Q U[3], V[3];
    for (int i = 0; i < 3; ++i) U[i] = Q(g(rng), 7), V[i] = Q(g(rng), 11);
    Q sum = 0;
    for (std::size_t j = 0; j < c.constraint_tets.size(); ++j)
      sum += Q(c.multipliers[j]) * tet_det(m, X, c.constraint_tets[j], U, V, c.simplex[0], c.simplex[1]);
    if (sum != 0) return false;
  }
  return positive;
}

}  // namespace

TEST_CASE("a free edge over a bow-tie ring of fixed vertices: an exact free-edge-line certificate") {
  const FreeEdgeOverBowtie f;
  const volmap::TetMesh mesh(f.mesh);
  REQUIRE(volmap::count_nonpositive(f.mesh.xyz, f.mesh.tets) == 0);  // a valid source
  CHECK(certificates_of(f.mesh, f.locked, f.mesh.xyz).empty());       // the source itself is a valid map
  const auto cs = certificates_of(f.mesh, f.locked, f.target);
  const volmap::InfeasibilityCertificate* found = first_of_kind(cs, InfeasibilityKind::FreeEdgeLine);
  REQUIRE(found != nullptr);
  const volmap::InfeasibilityCertificate& c = *found;
  INFO(volmap::describe(c));
  CHECK(std::set<std::uint32_t>(c.simplex.begin(), c.simplex.end()) == std::set<std::uint32_t>{0, 1});
  CHECK(c.constraint_tets.size() == 4);
  CHECK(oracle_free_edge_line(f.mesh, f.target, c));
  CHECK(volmap::verify_certificate(mesh, f.locked, f.target, c));
  // Falsification by sampling: no placement of u and v tried makes all of the constraint tets positive.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> g(-2, 2);
  for (int it = 0; it < 2000; ++it) {
    std::vector<double> X = f.target;
    for (int i = 0; i < 6; ++i) X[std::size_t(i)] = g(rng);
    bool all_positive = true;
    for (std::uint32_t t : c.constraint_tets) {
      const std::uint32_t* v = &f.mesh.tets[4 * t];
      all_positive = all_positive && volmap_oracle::orient3d(&X[3 * v[0]], &X[3 * v[1]], &X[3 * v[2]], &X[3 * v[3]]) > 0;
    }
    CHECK_FALSE(all_positive);
  }
  // Refused where the claim does not hold: the ring convex again, a multiplier changed, u locked.
  CHECK_FALSE(volmap::verify_certificate(mesh, f.locked, f.mesh.xyz, c));
  volmap::InfeasibilityCertificate changed = c;
  changed.multipliers.back() *= 2;
  CHECK_FALSE(volmap::verify_certificate(mesh, f.locked, f.target, changed));
  std::vector<std::uint8_t> u_locked = f.locked;
  u_locked[0] = 1;
  CHECK_FALSE(volmap::verify_certificate(mesh, u_locked, f.target, c));
  // The mapper at fixed connectivity stops with the certificate (no map is claimed).
  const auto r = map_at_fixed_connectivity(f.mesh, f.locked, f.target);
  CHECK_FALSE(r.certified);
  CHECK(has_kind(r.infeasibility, InfeasibilityKind::FreeEdgeLine));
}

namespace {
// A G1 case at fixed connectivity: the source, its locked (boundary) vertices and their images.
struct G1FixedCase {
  volmap::TetMeshData mesh;
  std::vector<std::uint8_t> locked;
  std::vector<double> target;
  G1FixedCase(const std::filesystem::path& mesh_path, const std::filesystem::path& map_path)
      : mesh(volmap::read_medit(mesh_path.string())), locked(mesh.num_vertices(), 0), target(3 * mesh.num_vertices(), 0.0) {
    const volmap::BoundaryMap map = volmap::read_boundary_map(map_path.string());
    for (std::size_t i = 0; i < map.size(); ++i) {
      locked[map.vids[i]] = 1;
      std::copy_n(&map.xyz[3 * i], 3, &target[3 * map.vids[i]]);
    }
  }
};
}  // namespace

TEST_CASE("bone onto the cube at fixed connectivity: a free edge that no line can serve (G1 data)") {
  VOLMAP_REQUIRE_DATA(mesh_path, "volmap/G1/bone.mesh");
  VOLMAP_REQUIRE_DATA(map_path, "volmap/G1_cube/bone_cube.txt");
  const G1FixedCase g(mesh_path, map_path);
  const volmap::TetMeshData& m = g.mesh;
  const std::vector<double>& X = g.target;
  const std::vector<std::uint8_t>& locked = g.locked;
  const volmap::TetMesh mesh(m);
  const auto cs = volmap::find_local_infeasibility(mesh, locked, X);
  // The only certificate: no fixed simplex, no fixed link is infeasible on its own.
  REQUIRE(cs.size() == 1);
  const auto it = cs.begin();
  INFO(volmap::describe(*it));
  CHECK(it->kind == InfeasibilityKind::FreeEdgeLine);
  CHECK(oracle_free_edge_line(m, X, *it));
  CHECK(volmap::verify_certificate(mesh, locked, X, *it));
}

TEST_CASE("ramses onto the pyramid at fixed connectivity: the six-vectors a free edge needs hold no line (G1 data)") {
  // The line LP over the edge's constraints has a positive optimum (about 1e-7), so no Gordan
  // multipliers exist; the cone of those six-vectors lies off the Klein quadric.
  VOLMAP_REQUIRE_DATA(mesh_path, "volmap/G1/ramses.mesh");
  VOLMAP_REQUIRE_DATA(map_path, "volmap/G1_pyr/ramses_pyr.txt");
  const G1FixedCase g(mesh_path, map_path);
  const volmap::TetMesh mesh(g.mesh);
  const auto cs = volmap::find_local_infeasibility(mesh, g.locked, g.target);
  CHECK_FALSE(has_kind(cs, InfeasibilityKind::FreeEdgeLine));
  const volmap::InfeasibilityCertificate* found = first_of_kind(cs, InfeasibilityKind::FreeEdgeCone);
  REQUIRE(found != nullptr);
  const volmap::InfeasibilityCertificate& c = *found;
  INFO(volmap::describe(c));
  CHECK(std::set<std::uint32_t>(c.simplex.begin(), c.simplex.end()) == std::set<std::uint32_t>{16950, 17399});
  CHECK(volmap::verify_certificate(mesh, g.locked, g.target, c));
  // Five constraint tets leave a cone with a linear subspace in it: refused.
  volmap::InfeasibilityCertificate five = c;
  five.constraint_tets.resize(5);
  CHECK_FALSE(volmap::verify_certificate(mesh, g.locked, g.target, five));
}
