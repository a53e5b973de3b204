// Edits (edge/face/tet splits, 2-3 and 3-2 flips), properties that follow them, compact() remaps,
// and a randomized edit test with check_invariants() and exact positivity after every edit.
#include <doctest/doctest.h>

#include <volmap/core/error.hpp>
#include <volmap/testing/generate.hpp>
#include <volmap/predicates.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/core/topology.hpp>

#include "mesh_test_util.hpp"

#include <random>

using namespace volmap;

namespace {

void require_ok(const TetMesh& m, bool positive = true) {
  const InvariantReport r = m.check_invariants(positive);
  INFO(r.problem);
  REQUIRE(r.ok);
}

// Positivity of the tets around vertex w (all the children of a split).
bool star_positive(const TetMesh& m, VertexId w) {
  std::vector<TetId> star;
  m.vertex_star(w, star);
  for (TetId t : star) {
    const auto v = m.tet_vertices(t);
    if (orient3d(m.vertex_position(v[0]), m.vertex_position(v[1]), m.vertex_position(v[2]), m.vertex_position(v[3])) <= 0)
      return false;
  }
  return !star.empty();
}

// Would replacing slot j of t by p keep t strictly positive?
bool replace_positive(const TetMesh& m, TetId t, int j, const double* p) {
  const double* q[4];
  for (int i = 0; i < 4; ++i) q[i] = i == j ? p : m.vertex_position(m.tet_vertex(t, i));
  return orient3d(q[0], q[1], q[2], q[3]) > 0;
}

void point_on(const TetMesh& m, const VertexId* v, const double* w, int n, double* p) {
  p[0] = p[1] = p[2] = 0;
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) p[c] += w[k] * m.vertex_position(v[k])[c];
}

TetMeshData bipyramid() {
  // Triangle a,b,c in z=0, d above, e below: segment de crosses the triangle.
  TetMeshData d;
  d.xyz = {0, 0, 0, 2, 0, 0, 0, 2, 0, 0.5, 0.5, 1, 0.5, 0.5, -1};
  d.tets = {0, 1, 2, 3, 1, 0, 2, 4};
  for (int t = 0; t < 2; ++t)
    if (mesh_test::orient_tet(d.xyz, &d.tets[4 * t]) < 0) std::swap(d.tets[4 * t], d.tets[4 * t + 1]);
  return d;
}

}  // namespace

TEST_CASE("tet split 1->4: counts, positivity, inherited properties and label") {
  TetMeshData d = generate_kuhn_grid(1, 1, 1);
  d.tet_labels[2] = 7;
  TetMesh m(d);
  TetProperty<int> tag(m, -1);
  VertexProperty<double> weight(m, 0.5);
  for (std::uint32_t t = 0; t < m.num_tets(); ++t) tag[TetId(t)] = int(100 + t);
  const auto tv = m.tet_vertices(TetId(2));
  const double w[4] = {0.25, 0.25, 0.25, 0.25};
  double p[3];
  point_on(m, tv.data(), w, 4, p);
  const std::uint64_t version = m.topology_version();
  m.build_caches();
  const VertexId nv = m.split_tet(TetId(2), p);
  CHECK(m.topology_version() != version);
  CHECK_FALSE(m.edge_cache_current());
  CHECK(m.num_tets() == 9);
  CHECK(m.num_vertices() == 9);
  CHECK(nv.idx() == 8);
  require_ok(m);
  CHECK(star_positive(m, nv));
  CHECK(weight[nv] == 0.5);
  CHECK(weight.size() == 9);
  CHECK(tag.size() == 9);
  std::vector<TetId> star;
  m.vertex_star(nv, star);
  CHECK(star.size() == 4);
  for (TetId t : star) {
    CHECK(tag[t] == 102);
    CHECK(m.tet_labels()[t.idx()] == 7);
  }
  // Untouched tets keep ids and vertices.
  for (std::uint32_t t = 0; t < 6; ++t)
    if (t != 2)
      for (int i = 0; i < 4; ++i) CHECK(m.tet_vertex(TetId(t), i).idx() == d.tets[4 * t + i]);
  CHECK(analyze_topology(m.to_data()).boundary_genus_zero);
}

TEST_CASE("face split: interior face (2x3 tets) and boundary face (1x3)") {
  TetMesh m(generate_kuhn_grid(2, 2, 2));
  const std::size_t t0 = m.num_tets(), v0 = m.num_vertices();
  for (bool want_boundary : {false, true}) {
    std::uint32_t h = 0;
    while (m.half_face_is_boundary(HalfFaceId(h)) != want_boundary) ++h;
    const auto fv = m.half_face_vertices(HalfFaceId(h));
    const double w[3] = {0.2, 0.3, 0.5};
    double p[3];
    point_on(m, fv.data(), w, 3, p);
    const bool was_boundary = m.half_face_is_boundary(HalfFaceId(h));
    const VertexId nv = m.split_face(HalfFaceId(h), p);
    require_ok(m);
    CHECK(star_positive(m, nv));
    std::vector<TetId> star;
    m.vertex_star(nv, star);
    CHECK(star.size() == (was_boundary ? 3u : 6u));
    CHECK(m.vertex_is_boundary(nv) == was_boundary);
  }
  CHECK(m.num_tets() == t0 + 4 + 2);
  CHECK(m.num_vertices() == v0 + 2);
  const TopologyReport r = analyze_topology(m.to_data());
  CHECK(r.boundary_genus_zero);
  CHECK(r.num_boundary_faces == 12 * 4 + 2);
}

TEST_CASE("edge split: interior and boundary edges, every tet of the star") {
  TetMesh m(generate_kuhn_grid(2, 2, 2));
  TetProperty<int> tag(m, -1);
  for (std::uint32_t t = 0; t < m.num_tets(); ++t) tag[TetId(t)] = int(t);
  const auto edges_before = mesh_test::brute_edges(m.tet_vertex_array());
  // An interior edge: both ends at the centre vertex (1,1,1) and a neighbour inside.
  int split = 0;
  for (std::uint32_t t = 0; t < m.num_tets() && split < 2; ++t)
    for (int k = 0; k < 6 && split < 2; ++k) {
      const int a = kTetEdge[k][0], b = kTetEdge[k][1];
      const bool closed = m.edge_star(TetId(t), a, b, [](TetId) {});
      if (closed != (split == 0)) continue;  // first an interior edge, then a boundary one
      const std::size_t deg = m.edge_degree(TetId(t), a, b);
      const VertexId ends[2] = {m.tet_vertex(TetId(t), a), m.tet_vertex(TetId(t), b)};
      const double w[2] = {0.5, 0.5};
      double p[3];
      point_on(m, ends, w, 2, p);
      const std::size_t nt = m.num_tets();
      const VertexId nv = m.split_edge(TetId(t), a, b, p);
      require_ok(m);
      CHECK(star_positive(m, nv));
      CHECK(m.num_tets() == nt + deg);
      CHECK(m.vertex_is_boundary(nv) == !closed);
      CHECK_FALSE(m.find_edge(ends[0], ends[1], nullptr, nullptr).is_valid());
      CHECK(m.find_edge(ends[0], nv, nullptr, nullptr).is_valid());
      CHECK(m.find_edge(nv, ends[1], nullptr, nullptr).is_valid());
      // Every child's tag is one of the parent's star.
      std::vector<TetId> star;
      m.vertex_star(nv, star);
      CHECK(star.size() == 2 * deg);
      const auto& parents = edges_before.at(std::minmax(ends[0].idx(), ends[1].idx()));
      for (TetId c : star) CHECK(std::find(parents.begin(), parents.end(), std::uint32_t(tag[c])) != parents.end());
      ++split;
    }
  CHECK(split == 2);
  // By vertex pair: the edge (0, 1) of the grid corner, then it is gone.
  const double mid[3] = {0.5, 0.0, 0.0};
  const VertexId w = m.split_edge(VertexId(0), VertexId(1), mid);
  require_ok(m);
  CHECK(star_positive(m, w));
  CHECK_THROWS_AS(m.split_edge(VertexId(0), VertexId(1), mid), Error);
  CHECK(analyze_topology(m.to_data()).boundary_genus_zero);
}

TEST_CASE("2-3 and 3-2 flips on a bipyramid, round trip") {
  TetMesh m(bipyramid());
  require_ok(m);
  HalfFaceId shared;
  for (std::uint32_t h = 0; h < 4; ++h)
    if (!m.half_face_is_boundary(HalfFaceId(h))) shared = HalfFaceId(h);
  REQUIRE(shared.is_valid());
  CHECK(m.can_flip_2_3(shared));
  // Under other coordinates (e below the triangle plane moved away) the flip is invalid.
  std::vector<double> moved = m.positions();
  moved[3 * 4 + 0] = 5.0;
  moved[3 * 4 + 1] = 5.0;
  CHECK_FALSE(m.can_flip_2_3(shared, moved.data()));
  TetProperty<int> tag(m, -1);
  tag[TetId(0)] = 10;
  tag[TetId(1)] = 11;
  const auto three = m.flip_2_3(shared);
  CHECK(m.num_tets() == 3);
  require_ok(m);
  CHECK(tag[three[2]] == 10);  // the appended tet copies the first parent
  const VertexId d(3), e(4);
  int la = -1, lb = -1;
  const TetId t = m.find_edge(d, e, &la, &lb);
  REQUIRE(t.is_valid());
  CHECK(m.edge_degree(t, la, lb) == 3);
  CHECK(m.can_flip_3_2(t, la, lb));
  CHECK_FALSE(m.can_flip_2_3(HalfFaceId(t, la)));  // boundary or would recreate an edge
  const auto two = m.flip_3_2(t, la, lb);
  CHECK(m.num_tets() == 2);
  CHECK(m.num_free_tet_slots() == 1);
  require_ok(m);
  CHECK_FALSE(m.find_edge(d, e, nullptr, nullptr).is_valid());
  // compact: the tombstone goes, ids of the survivors shift down, properties follow.
  std::vector<std::array<VertexId, 4>> before;
  std::vector<int> tags_before;
  for (TetId x : two) {
    before.push_back(m.tet_vertices(x));
    tags_before.push_back(tag[x]);
  }
  const CompactRemap r = m.compact();
  CHECK(m.num_tet_slots() == 2);
  CHECK(tag.size() == 2);
  for (int k = 0; k < 2; ++k) {
    const TetId nt(r.tet_old_to_new[two[k].idx()]);
    CHECK(m.tet_vertices(nt) == before[k]);
    CHECK(tag[nt] == tags_before[k]);
  }
  require_ok(m);
  CHECK_THROWS_AS(m.flip_2_3(HalfFaceId(TetId(0), 0)), Error);  // boundary face (or no shared one)
}

TEST_CASE("compact after many edits: remaps, properties and positions agree") {
  TetMesh m(generate_kuhn_grid(2, 2, 2));
  VertexProperty<double> xcopy(m, -1.0);
  TetProperty<std::uint32_t> tv0(m);
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v) xcopy[VertexId(v)] = m.vertex_position(VertexId(v))[0];
  // split all tets; then 2-3/3-2 flip pairs to leave tombstones.
  const std::size_t n0 = m.num_tets();
  for (std::uint32_t t = 0; t < n0; ++t) {
    const auto tv = m.tet_vertices(TetId(t));
    const double w[4] = {0.1, 0.2, 0.3, 0.4};
    double p[3];
    point_on(m, tv.data(), w, 4, p);
    const VertexId nv = m.split_tet(TetId(t), p);
    xcopy[nv] = p[0];
  }
  int flips = 0;
  for (std::uint32_t h = 0; h < 4 * m.num_tet_slots() && flips < 20; ++h) {
    if (!m.tet_is_live(HalfFaceId(h).tet()) || !m.can_flip_2_3(HalfFaceId(h))) continue;
    const auto three = m.flip_2_3(HalfFaceId(h));
    // flip it back: the new edge is in all three
    const auto tv = m.tet_vertices(three[0]);
    int la = -1, lb = -1;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i != j && m.tet_local_index(three[1], tv[i]) >= 0 && m.tet_local_index(three[1], tv[j]) >= 0 &&
            m.tet_local_index(three[2], tv[i]) >= 0 && m.tet_local_index(three[2], tv[j]) >= 0) {
          la = i;
          lb = j;
        }
    REQUIRE(la >= 0);
    REQUIRE(m.can_flip_3_2(three[0], la, lb));
    m.flip_3_2(three[0], la, lb);
    require_ok(m);
    ++flips;
  }
  CHECK(flips > 0);
  for (std::uint32_t t = 0; t < m.num_tet_slots(); ++t)
    if (m.tet_is_live(TetId(t))) tv0[TetId(t)] = m.tet_vertex(TetId(t), 0).idx();
  CHECK(m.num_free_tet_slots() > 0);
  const TetMeshData before = m.to_data();
  const CompactRemap r = m.compact();
  CHECK(m.num_free_tet_slots() == 0);
  CHECK(m.num_tet_slots() == m.num_tets());
  require_ok(m);
  const TetMeshData after = m.to_data();
  CHECK(after.tets == before.tets);  // to_data() already lists survivors in compact order
  CHECK(after.xyz == before.xyz);
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v) CHECK(xcopy[VertexId(v)] == m.vertex_position(VertexId(v))[0]);
  for (std::uint32_t t = 0; t < m.num_tets(); ++t) CHECK(r.vertex_old_to_new[tv0[TetId(t)]] == m.tet_vertex(TetId(t), 0).idx());
}

TEST_CASE("properties: value semantics, detach, survive a moved mesh") {
  TetMesh m(generate_kuhn_grid(1, 1, 1));
  VertexProperty<int> a(m, 3);
  CHECK(m.property_registry().size(ElementKind::Vertex) == 1);
  {
    VertexProperty<int> b = a;  // copy follows edits on its own
    b[VertexId(0)] = 9;
    CHECK(a[VertexId(0)] == 3);
    CHECK(m.property_registry().size(ElementKind::Vertex) == 2);
  }
  CHECK(m.property_registry().size(ElementKind::Vertex) == 1);
  VertexProperty<bool> visited(m);
  visited[VertexId(1)] = true;
  CHECK(visited[VertexId(1)]);
  TetMesh moved = std::move(m);
  const double p[3] = {0.2, 0.3, 0.4};
  // Find a tet containing p strictly: try each.
  for (std::uint32_t t = 0; t < moved.num_tets(); ++t) {
    bool inside = true;
    for (int j = 0; j < 4; ++j) inside = inside && replace_positive(moved, TetId(t), j, p);
    if (!inside) continue;
    const VertexId nv = moved.split_tet(TetId(t), p);
    CHECK(a[nv] == 3);
    CHECK_FALSE(visited[nv]);
    CHECK(a.size() == moved.num_vertex_slots());
    break;
  }
  CHECK(a.size() == 9);
  const TetMesh copy = moved;  // a copy has no properties attached
  CHECK(copy.property_registry().size(ElementKind::Vertex) == 0);
  require_ok(copy);
  TetMesh other(generate_kuhn_grid(2, 1, 1));
  TetProperty<int> on_other(other, 4);
  on_other[TetId(0)] = 8;
  other = copy;  // assignment: properties stay attached, reset to defaults at the new size
  CHECK(on_other.size() == other.num_tet_slots());
  CHECK(on_other[TetId(0)] == 4);
}

namespace {
// Random edits on a Kuhn grid: every split is checked exactly beforehand (children strictly positive)
// and its children exactly afterwards; flips only when can_flip_* says so. check_invariants() after
// every edit, the full exact positivity pass every `full_every` edits.
void run_random_edits(std::size_t grid, int kOps, std::uint64_t seed, int full_every) {
  std::mt19937_64 rng(seed);
  TetMesh m(generate_kuhn_grid(grid, grid, grid));
  TetProperty<std::uint32_t> generation(m, 0);
  std::uniform_real_distribution<double> uni(0.05, 1.0);
  std::size_t done[5] = {0, 0, 0, 0, 0};
  std::vector<TetId> star;
  for (int op = 0; op < kOps; ++op) {
    std::uint32_t t;
    do t = std::uint32_t(rng() % m.num_tet_slots());
    while (!m.tet_is_live(TetId(t)));
    const int kind = int(rng() % 5);
    const auto tv = m.tet_vertices(TetId(t));
    if (kind == 0) {  // tet split at a random interior point
      double w[4], s = 0;
      for (double& x : w) s += (x = uni(rng));
      for (double& x : w) x /= s;
      double p[3];
      point_on(m, tv.data(), w, 4, p);
      bool ok = true;
      for (int j = 0; j < 4; ++j) ok = ok && replace_positive(m, TetId(t), j, p);
      if (!ok) continue;
      const VertexId nv = m.split_tet(TetId(t), p);
      REQUIRE(star_positive(m, nv));
      ++done[0];
    } else if (kind == 1) {  // face split
      const int i = int(rng() % 4);
      const HalfFaceId h(TetId(t), i);
      const auto fv = m.half_face_vertices(h);
      double w[3], s = 0;
      for (double& x : w) s += (x = uni(rng));
      for (double& x : w) x /= s;
      double p[3];
      point_on(m, fv.data(), w, 3, p);
      bool ok = true;
      for (int j = 0; j < 4; ++j)
        if (j != i) ok = ok && replace_positive(m, TetId(t), j, p);
      const HalfFaceId o = m.half_face_opposite(h);
      if (o.is_valid())
        for (int j = 0; j < 4; ++j)
          if (j != o.local()) ok = ok && replace_positive(m, o.tet(), j, p);
      if (!ok) continue;
      const VertexId nv = m.split_face(h, p);
      REQUIRE(star_positive(m, nv));
      ++done[1];
    } else if (kind == 2) {  // edge split at a random point of the segment
      const int k = int(rng() % 6);
      const int a = kTetEdge[k][0], b = kTetEdge[k][1];
      const double s = uni(rng) * 0.9;
      const VertexId ends[2] = {tv[a], tv[b]};
      const double w[2] = {s, 1 - s};
      double p[3];
      point_on(m, ends, w, 2, p);
      bool ok = true;
      m.edge_star(TetId(t), a, b, [&](TetId x, int la, int lb) {
        ok = ok && replace_positive(m, x, la, p) && replace_positive(m, x, lb, p);
      });
      if (!ok) continue;
      const VertexId nv = m.split_edge(TetId(t), a, b, p);
      REQUIRE(star_positive(m, nv));
      ++done[2];
    } else if (kind == 3) {  // 2-3 flip
      const HalfFaceId h(TetId(t), int(rng() % 4));
      if (!m.can_flip_2_3(h)) continue;
      const auto three = m.flip_2_3(h);
      for (TetId x : three) generation[x] += 1;
      ++done[3];
    } else {  // 3-2 flip
      const int k = int(rng() % 6);
      if (!m.can_flip_3_2(TetId(t), kTetEdge[k][0], kTetEdge[k][1])) continue;
      m.flip_3_2(TetId(t), kTetEdge[k][0], kTetEdge[k][1]);
      ++done[4];
    }
    const InvariantReport r = m.check_invariants(false);
    INFO("op " << op << " kind " << kind << ": " << r.problem);
    REQUIRE(r.ok);
    if (op % full_every == 0) require_ok(m, true);  // full exact positivity pass now and then
  }
  MESSAGE("tet splits " << done[0] << ", face splits " << done[1] << ", edge splits " << done[2] << ", 2-3 flips "
                        << done[3] << ", 3-2 flips " << done[4] << "; tets " << m.num_tets());
  CHECK(done[0] > std::size_t(kOps / 50));
  CHECK(done[1] > std::size_t(kOps / 50));
  CHECK(done[2] > std::size_t(kOps / 50));
  CHECK(done[3] > std::size_t(kOps / 250));
  CHECK(done[4] > std::size_t(kOps / 1000));
  require_ok(m, true);
  const TopologyReport topo = analyze_topology(m.to_data());
  CHECK(topo.boundary_genus_zero);
  CHECK(topo.single_tet_component);
  CHECK(topo.boundary_edges_manifold);
  m.compact();
  require_ok(m, true);
  CHECK(generation.size() == m.num_tets());
  // Rebuilding from the flat arrays gives the same adjacency.
  const TetMesh rebuilt(m.to_data());
  CHECK(rebuilt.opposite_array() == m.opposite_array());
}
}  // namespace

TEST_CASE("randomized edits: splits and flips with invariants and exact positivity after each") {
  run_random_edits(3, 5000, 12345, 500);
}

TEST_SUITE("long") {
  TEST_CASE("randomized edits long run with 40000 edits on a 5^3 grid") { run_random_edits(5, 40000, 987, 2000); }
}
