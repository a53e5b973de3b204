// TetMesh construction, navigation, caches and boundary extraction, against brute-force oracles
// (std::map face/edge tables in mesh_test_util.hpp) and exact orientation tests.
#include <doctest/doctest.h>

#include <volmap/surface/boundary_surface.hpp>
#include <volmap/core/error.hpp>
#include <volmap/testing/generate.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/core/topology.hpp>

#include "mesh_test_util.hpp"
#include "test_support.hpp"

#include <filesystem>
#include <unordered_set>

using namespace volmap;

namespace {

TetMeshData single_tet() {
  TetMeshData d;
  d.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  d.tets = {0, 1, 2, 3};
  if (mesh_test::orient_tet(d.xyz, d.tets.data()) < 0) std::swap(d.tets[0], d.tets[1]);
  return d;
}

std::string build_error(const TetMeshData& d) {
  try {
    TetMesh m(d);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::BadInput);
    return e.reason();
  }
  return "";
}

}  // namespace

TEST_CASE("local tables: outward faces, even-permutation CROSS, edge table") {
  // A positive tet: outward faces have the apex strictly below (orient3d(F_i, v_i) > 0).
  const TetMeshData d = single_tet();
  const double* v[4];
  for (int i = 0; i < 4; ++i) v[i] = &d.xyz[3 * std::size_t(d.tets[i])];
  REQUIRE(orient3d(v[0], v[1], v[2], v[3]) > 0);
  for (int i = 0; i < 4; ++i) CHECK(orient3d(v[kTetFace[i][0]], v[kTetFace[i][1]], v[kTetFace[i][2]], v[i]) > 0);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      if (a == b) continue;
      const int dd = kTetCross[a][b];
      const int c = 6 - a - b - dd;
      REQUIRE(dd != a);
      REQUIRE(dd != b);
      // parity of (a,b,c,dd) by counting inversions
      const int p[4] = {a, b, c, dd};
      int inv = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inv += p[i] > p[j];
      CHECK(inv % 2 == 0);
      CHECK(kTetCross[b][a] == c);
      CHECK(kTetEdge[kTetEdgeOf[a][b]][0] == std::min(a, b));
      CHECK(kTetEdge[kTetEdgeOf[a][b]][1] == std::max(a, b));
    }
  for (int k = 0; k < 6; ++k) {  // EDGE[k] and EDGE[5-k] are disjoint
    CHECK(kTetEdge[k][0] != kTetEdge[5 - k][0]);
    CHECK(kTetEdge[k][0] != kTetEdge[5 - k][1]);
    CHECK(kTetEdge[k][1] != kTetEdge[5 - k][0]);
    CHECK(kTetEdge[k][1] != kTetEdge[5 - k][1]);
  }
}

TEST_CASE("typed ids") {
  CHECK_FALSE(VertexId().is_valid());
  CHECK(VertexId() == VertexId::kInvalid);
  CHECK(VertexId(3) < VertexId(4));
  const HalfFaceId h(TetId(5), 2);
  CHECK(h.idx() == 22);
  CHECK(h.tet() == TetId(5));
  CHECK(h.local() == 2);
  std::unordered_set<TetId> s{TetId(1), TetId(1), TetId(2)};
  CHECK(s.size() == 2);
  static_assert(!std::is_convertible_v<std::uint32_t, VertexId>, "explicit construction only");
  static_assert(!std::is_convertible_v<VertexId, TetId>, "ids of different entities do not mix");
}

TEST_CASE("single tet: all faces boundary, order kept, round trip") {
  const TetMeshData d = single_tet();
  const TetMesh m(d);
  CHECK(m.num_vertices() == 4);
  CHECK(m.num_tets() == 1);
  for (int i = 0; i < 4; ++i) {
    CHECK(m.tet_vertex(TetId(0), i).idx() == d.tets[i]);
    CHECK(m.half_face_is_boundary(m.half_face(TetId(0), i)));
    CHECK_FALSE(m.half_face_opposite(m.half_face(TetId(0), i)).is_valid());
    CHECK(m.half_face_apex(HalfFaceId(TetId(0), i)).idx() == d.tets[i]);
  }
  for (std::uint32_t v = 0; v < 4; ++v) CHECK(m.vertex_is_boundary(VertexId(v)));
  CHECK(m.boundary_half_faces().size() == 4);
  CHECK(m.num_edges() == 6);
  CHECK(m.check_invariants(true).ok);
  const TetMeshData back = m.to_data();
  CHECK(back.tets == d.tets);
  CHECK(back.xyz == d.xyz);
}

TEST_CASE("build errors name the offending element") {
  TetMeshData d = single_tet();
  // A second tet on face (d0,d1,d2) on the other side, a third one on the same face: non-manifold.
  const std::uint32_t a = d.tets[0], b = d.tets[1], c = d.tets[2];
  d.xyz.insert(d.xyz.end(), {0.3, 0.3, -1, 0.2, 0.2, -2});
  d.tets.insert(d.tets.end(), {b, a, c, 4});
  {
    const TetMeshData two = [&] { TetMeshData x = d; x.xyz.resize(15); return x; }();
    CHECK(build_error(two).empty());
    const TetMesh m(two);
    CHECK(m.check_invariants(true).ok);
  }
  d.tets.insert(d.tets.end(), {b, a, c, 5});
  std::string r = build_error(d);
  CHECK(r.find("shared by 3 tets (0, 1, 2)") != std::string::npos);

  TetMeshData inconsistent = single_tet();
  inconsistent.xyz.insert(inconsistent.xyz.end(), {0.3, 0.3, -1});
  inconsistent.tets.insert(inconsistent.tets.end(), {a, b, c, 4});  // same winding as tet 0's face
  r = build_error(inconsistent);
  CHECK(r.find("inconsistent orientation: tets 0 and 1") != std::string::npos);

  TetMeshData unused = single_tet();
  unused.xyz.insert(unused.xyz.end(), {5, 5, 5});
  CHECK(build_error(unused) == "vertex 4 is used by no tet");

  TetMeshData out_of_range = single_tet();
  out_of_range.tets[2] = 9;
  CHECK(build_error(out_of_range).find("tet 0 references vertex 9") != std::string::npos);

  TetMeshData repeated = single_tet();
  repeated.tets[2] = repeated.tets[0];
  CHECK(build_error(repeated).find("tet 0 repeats vertex") != std::string::npos);

  TetMeshData bad_size = single_tet();
  bad_size.tets.pop_back();
  CHECK(build_error(bad_size).find("not a multiple of 4") != std::string::npos);
}

TEST_CASE("large meshes (parallel matching) report the same first error as a serial pass") {
  TetMeshData d = generate_kuhn_grid(34, 34, 34);  // 235 824 tets: parallel path
  REQUIRE(d.num_tets() >= 200000);
  {
    const TetMesh big(d);  // parallel matching: symmetric opp with equal vertex sets, right boundary
    CHECK(big.check_invariants().ok);
    CHECK(big.boundary_half_faces().size() == analyze_topology(d).num_boundary_faces);
    CHECK(big.boundary_half_faces().size() == 12 * 34 * 34);
  }
  // Two inverted tets far apart: the error names the one met first in (vertex, face) order,
  // the same as analyze_topology's serial pass.
  for (std::size_t t : {d.num_tets() - 7, std::size_t(1000)}) std::swap(d.tets[4 * t], d.tets[4 * t + 1]);
  const TopologyReport r = analyze_topology(d);
  REQUIRE(r.num_inconsistent_faces >= 5);  // 4 + 1..4 (the last tets touch the boundary)
  const std::string first = "inconsistent orientation: tets " + std::to_string(r.example_inconsistent_face / 4) + " and ";
  std::string got = build_error(d);
  CHECK(got.rfind(first, 0) == 0);
  // A third tet on an interior face of tet 1000 (new apex far away), appended at the end.
  d = generate_kuhn_grid(34, 34, 34);
  const TetMesh valid(d);
  int i = 0;
  while (valid.half_face_is_boundary(HalfFaceId(TetId(1000), i))) ++i;
  const auto fv = valid.half_face_vertices(HalfFaceId(TetId(1000), i));
  const std::uint32_t apex = std::uint32_t(d.num_vertices());
  d.xyz.insert(d.xyz.end(), {-50.0, -50.0, -50.0});
  d.tets.insert(d.tets.end(), {fv[0].idx(), fv[2].idx(), fv[1].idx(), apex});
  d.vertex_labels.push_back(0);
  d.tet_labels.push_back(0);
  const std::size_t extra = d.num_tets() - 1;
  const TetId across = valid.tet_neighbor(TetId(1000), i);
  std::vector<std::uint32_t> three = {1000, across.idx(), std::uint32_t(extra)};
  std::sort(three.begin(), three.end());
  got = build_error(d);
  INFO(got);
  CHECK(got.find("is shared by 3 tets (" + std::to_string(three[0]) + ", " + std::to_string(three[1]) + ", " +
                 std::to_string(three[2]) + ")") != std::string::npos);
}

TEST_CASE("Kuhn grid: generator is positive and the structure matches brute force") {
  const std::size_t n = 4;
  const TetMeshData d = generate_kuhn_grid(n, n, n);
  REQUIRE(d.num_tets() == 6 * n * n * n);
  REQUIRE(d.num_vertices() == (n + 1) * (n + 1) * (n + 1));
  const TetMesh m(d);
  for (std::size_t t = 0; t < d.num_tets(); ++t) REQUIRE(mesh_test::orient_tet(d.xyz, &d.tets[4 * t]) > 0);
  CHECK(m.check_invariants(true).ok);
  // opp vs a map of sorted triples.
  const auto faces = mesh_test::brute_faces(d.tets);
  std::size_t boundary = 0;
  for (const auto& [key, hs] : faces) {
    REQUIRE(hs.size() <= 2);
    if (hs.size() == 1) {
      ++boundary;
      CHECK(m.half_face_is_boundary(HalfFaceId(hs[0])));
    } else {
      CHECK(m.half_face_opposite(HalfFaceId(hs[0])) == HalfFaceId(hs[1]));
      CHECK(m.half_face_opposite(HalfFaceId(hs[1])) == HalfFaceId(hs[0]));
      CHECK(m.tet_neighbor(HalfFaceId(hs[0]).tet(), HalfFaceId(hs[0]).local()) == HalfFaceId(hs[1]).tet());
    }
  }
  CHECK(boundary == 12 * n * n);
  CHECK(m.boundary_half_faces().size() == boundary);
  // Boundary vertices are exactly those on the box surface; v2h contains the vertex.
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v) {
    const double* p = m.vertex_position(VertexId(v));
    bool on_box = false;
    for (int c = 0; c < 3; ++c) on_box = on_box || p[c] == 0.0 || p[c] == double(n);
    CHECK(m.vertex_is_boundary(VertexId(v)) == on_box);
    const HalfFaceId h = m.vertex_half_face(VertexId(v));
    const auto fv = m.half_face_vertices(h);
    CHECK((fv[0] == VertexId(v) || fv[1] == VertexId(v) || fv[2] == VertexId(v)));
  }
  // Half-face vertices: outward (apex strictly behind) and in the FACE table order.
  for (std::uint32_t h = 0; h < 4 * m.num_tets(); ++h) {
    const auto fv = m.half_face_vertices(HalfFaceId(h));
    const VertexId apex = m.half_face_apex(HalfFaceId(h));
    CHECK(orient3d(m.vertex_position(fv[0]), m.vertex_position(fv[1]), m.vertex_position(fv[2]),
                   m.vertex_position(apex)) > 0);
  }
}

TEST_CASE("edge stars and edge cache vs brute force; Euler characteristic of a ball") {
  const TetMesh m(generate_kuhn_grid(4, 3, 5));
  const auto edges = mesh_test::brute_edges(m.tet_vertex_array());
  CHECK(m.num_edges() == edges.size());
  const std::size_t nf = (4 * m.num_tets() + m.boundary_half_faces().size()) / 2;
  CHECK(long(m.num_vertices()) - long(m.num_edges()) + long(nf) - long(m.num_tets()) == 1);
  std::vector<char> seen_edge(m.num_edges(), 0);
  for (std::uint32_t t = 0; t < m.num_tets(); ++t) {
    for (int k = 0; k < 6; ++k) {
      const int a = kTetEdge[k][0], b = kTetEdge[k][1];
      std::uint32_t va = m.tet_vertex(TetId(t), a).idx(), vb = m.tet_vertex(TetId(t), b).idx();
      std::vector<std::uint32_t> star;
      const bool closed = m.edge_star(TetId(t), a, b, [&](TetId s, int la, int lb) {
        CHECK(m.tet_vertex(s, la).idx() == va);
        CHECK(m.tet_vertex(s, lb).idx() == vb);
        star.push_back(s.idx());
      });
      std::sort(star.begin(), star.end());
      const auto& expect = edges.at({std::min(va, vb), std::max(va, vb)});
      CHECK(star == expect);
      CHECK(closed == !(m.vertex_is_boundary(VertexId(va)) && m.vertex_is_boundary(VertexId(vb)) &&
                        [&] {  // boundary edge iff some boundary face holds both
                          for (HalfFaceId h : m.boundary_half_faces()) {
                            const auto f = m.half_face_vertices(h);
                            int hits = 0;
                            for (auto x : f) hits += x.idx() == va || x.idx() == vb;
                            if (hits == 2) return true;
                          }
                          return false;
                        }()));
      // Ordered walk: same set, consecutive tets share a face, starts at a boundary face if open.
      std::vector<std::uint32_t> ordered;
      m.edge_star_ordered(TetId(t), a, b, [&](TetId s) { ordered.push_back(s.idx()); });
      for (std::size_t i = 0; i + 1 < ordered.size(); ++i) {
        bool adjacent = false;
        for (int f = 0; f < 4; ++f) adjacent = adjacent || m.tet_neighbor(TetId(ordered[i]), f) == TetId(ordered[i + 1]);
        CHECK(adjacent);
      }
      std::sort(ordered.begin(), ordered.end());
      CHECK(ordered == expect);
      CHECK(m.edge_degree(TetId(t), a, b) == expect.size());
      // Edge ids: same id in every tet of the star, vertices match.
      const EdgeId e = m.tet_edge(TetId(t), k);
      seen_edge[e.idx()] = 1;
      const auto ev = m.edge_vertices(e);
      CHECK(std::minmax(ev[0].idx(), ev[1].idx()) == std::minmax(va, vb));
      for (std::uint32_t s : expect) {
        const int la = m.tet_local_index(TetId(s), VertexId(va)), lb = m.tet_local_index(TetId(s), VertexId(vb));
        CHECK(m.tet_edge(TetId(s), kTetEdgeOf[la][lb]) == e);
      }
      int fa = -1, fb = -1;
      const TetId ft = m.find_edge(VertexId(va), VertexId(vb), &fa, &fb);
      REQUIRE(ft.is_valid());
      CHECK(m.tet_vertex(ft, fa).idx() == va);
      CHECK(m.tet_vertex(ft, fb).idx() == vb);
    }
  }
  CHECK(std::count(seen_edge.begin(), seen_edge.end(), 1) == long(m.num_edges()));
  const Span<VertexId> ev_all = m.edge_vertex_array();
  REQUIRE(ev_all.size() == 2 * m.num_edges());
  for (std::uint32_t e = 0; e < m.num_edges(); ++e)
    CHECK(edges.count(std::minmax(ev_all[2 * e].idx(), ev_all[2 * e + 1].idx())) == 1);
  for (std::uint32_t e = 0; e < m.num_edges(); ++e) {  // stars by edge id
    const auto ev = m.edge_vertices(EdgeId(e));
    std::vector<std::uint32_t> star;
    m.edge_star(EdgeId(e), [&](TetId s) { star.push_back(s.idx()); });
    std::sort(star.begin(), star.end());
    CHECK(star == edges.at(std::minmax(ev[0].idx(), ev[1].idx())));
  }
  CHECK_FALSE(m.find_edge(VertexId(0), VertexId(std::uint32_t(m.num_vertices() - 1)), nullptr, nullptr).is_valid());
}

TEST_CASE("vertex stars: with and without the cache, vs brute force") {
  const TetMesh m(generate_kuhn_grid(3, 4, 2));
  std::vector<std::vector<TetId>> brute(m.num_vertices());
  for (std::uint32_t t = 0; t < m.num_tets(); ++t)
    for (VertexId v : m.tet_vertices(TetId(t))) brute[v.idx()].push_back(TetId(t));
  std::vector<TetId> star;
  CHECK_FALSE(m.vertex_tets_cache_current());
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v) {
    m.vertex_star(VertexId(v), star);  // face-walk path
    CHECK(star == brute[v]);
    m.vertex_star_unsorted(VertexId(v), star);  // the same tets, each once, in walk order
    std::sort(star.begin(), star.end());
    CHECK(star == brute[v]);
  }
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v)  // find_edge: the smallest tet holding both
    for (TetId t : brute[v])
      for (VertexId w : m.tet_vertices(t)) {
        if (w.idx() == v) continue;
        TetId smallest = TetId::kInvalid;
        for (TetId s : brute[v])
          if (m.tet_local_index(s, w) >= 0) { smallest = s; break; }
        int la = -1, lb = -1;
        CHECK(m.find_edge(VertexId(v), w, &la, &lb) == smallest);
        CHECK(m.tet_vertex(smallest, la).idx() == v);
        CHECK(m.tet_vertex(smallest, lb) == w);
      }
  m.build_caches();
  CHECK(m.vertex_tets_cache_current());
  CHECK(m.edge_cache_current());
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v) {
    m.vertex_star(VertexId(v), star);  // cache path
    CHECK(star == brute[v]);
    const auto span = m.vertex_tets(VertexId(v));
    CHECK(std::vector<TetId>(span.begin(), span.end()) == brute[v]);
  }
  CHECK(m.cache_bytes() > 0);
  m.clear_caches();
  CHECK(m.cache_bytes() == 0);
}

TEST_CASE("boundary surface of a Kuhn ball: chi = 2, outward normals, back-maps") {
  const std::size_t n = 3;
  const TetMesh m(generate_kuhn_grid(n, n, n));
  const BoundarySurface s = extract_boundary_surface(m);
  CHECK(s.complete());
  const auto& sm = s.mesh;
  CHECK(sm.n_faces() == 12 * n * n);
  CHECK(sm.n_vertices() == (n + 1) * (n + 1) * (n + 1) - (n - 1) * (n - 1) * (n - 1));
  CHECK(long(sm.n_vertices()) - long(sm.n_edges()) + long(sm.n_faces()) == 2);
  std::uint32_t prev = 0;
  bool first = true;
  for (auto vh : sm.vertices()) {
    const std::uint32_t v = s.tet_vertex_of(vh);
    if (!first) CHECK(v > prev);  // increasing vid order
    first = false;
    prev = v;
    CHECK(s.surface_vertex[v] == std::uint32_t(vh.idx()));
    const double* p = m.vertex_position(VertexId(v));
    CHECK(sm.point(vh)[0] == p[0]);
    CHECK(m.vertex_is_boundary(VertexId(v)));
  }
  for (auto fh : sm.faces()) {
    const HalfFaceId h = s.half_face_of(fh);
    CHECK(m.half_face_is_boundary(h));
    const auto fv = m.half_face_vertices(h);
    int k = 0;
    for (auto vh : sm.fv_range(fh)) CHECK(s.tet_vertex_of(vh) == fv[k++].idx());
    // Outward: the face normal points away from the box centre (exact: centre strictly behind).
    const double c[3] = {n / 2.0, n / 2.0, n / 2.0};
    CHECK(orient3d(m.vertex_position(fv[0]), m.vertex_position(fv[1]), m.vertex_position(fv[2]), c) > 0);
  }
  CHECK(sm.is_valid_handle(sm.vertex_handle(0)));
  for (auto eh : sm.edges()) CHECK_FALSE(sm.is_boundary(eh));
}

TEST_CASE("boundary surface reports faces OpenMesh refuses (pinched edge)") {
  // Two cubes sharing one grid edge: the boundary has an edge with 4 faces.
  const TetMeshData d = generate_kuhn_grid(2, 2, 1, [](std::size_t i, std::size_t j, std::size_t) { return i == j; });
  const TetMesh m(d);  // face-manifold: builds
  const BoundarySurface s = extract_boundary_surface(m);
  CHECK(s.mesh.n_faces() + s.rejected_half_faces.size() == m.boundary_half_faces().size());
  CHECK_FALSE(s.complete());
  for (HalfFaceId h : s.rejected_half_faces) CHECK(m.half_face_is_boundary(h));
}

TEST_CASE("pinched vertex: vertex_star is the face-connected cluster, vertex_tets lists all") {
  const TetMeshData d = generate_kuhn_grid(2, 2, 2, [](std::size_t i, std::size_t j, std::size_t k) {
    return (i == 0 && j == 0 && k == 0) || (i == 1 && j == 1 && k == 1);
  });
  const TetMesh m(d);
  CHECK(m.check_invariants(true).ok);
  VertexId centre;
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v)
    if (m.vertex_position(VertexId(v))[0] == 1.0 && m.vertex_position(VertexId(v))[1] == 1.0 &&
        m.vertex_position(VertexId(v))[2] == 1.0)
      centre = VertexId(v);
  REQUIRE(centre.is_valid());
  std::vector<TetId> star;
  m.vertex_star(centre, star);
  CHECK(star.size() == 6);  // the 6 Kuhn tets of one cube (all hold both ends of its main diagonal)
  CHECK(m.vertex_tets(centre).size() == 12);
  m.vertex_star(centre, star);  // same answer with the cache built
  CHECK(star.size() == 6);
}

TEST_CASE("memory: core bytes per tet within budget on a grid") {
  const TetMesh m(generate_kuhn_grid(10, 10, 10));
  const double per_tet = double(m.core_bytes()) / double(m.num_tets());
  MESSAGE("core bytes/tet = " << per_tet);
  CHECK(per_tet <= 40.0);
  CHECK(m.label_bytes() == 0);  // all-zero labels are not stored
}

namespace {
// Builds a real mesh and cross-checks it against analyze_topology, the boundary surface and
// to_data(); returns the topology report.
TopologyReport check_real_mesh(const std::filesystem::path& path) {
  INFO(path.string());
  const TetMeshData d = read_tet_mesh(path.string());
  const TopologyReport r = analyze_topology(d);
  const TetMesh m(d);
  const InvariantReport inv = m.check_invariants();
  INFO(inv.problem);
  CHECK(inv.ok);
  CHECK(r.boundary_half_faces.size() == m.boundary_half_faces().size());
  for (std::size_t k = 0; k < r.boundary_half_faces.size(); ++k)
    CHECK(r.boundary_half_faces[k] == m.boundary_half_faces()[k].idx());
  const BoundarySurface s = extract_boundary_surface(m);
  CHECK(s.complete());
  CHECK(long(s.mesh.n_vertices()) - long(s.mesh.n_edges()) + long(s.mesh.n_faces()) == r.boundary_euler);
  CHECK(s.mesh.n_vertices() == r.num_boundary_vertices);
  const TetMeshData back = m.to_data();
  CHECK(back.tets == d.tets);
  CHECK(back.xyz == d.xyz);
  return r;
}
}  // namespace

TEST_CASE("G1 meshes build, are genus-0 balls, and agree with analyze_topology") {
  VOLMAP_REQUIRE_DATA(dir, "volmap/G1");
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".mesh") continue;
    const TopologyReport r = check_real_mesh(entry.path());
    INFO(entry.path().filename().string());
    CHECK(r.boundary_genus_zero);
    CHECK(r.single_tet_component);
    CHECK(r.single_boundary_component);
    CHECK(r.boundary_closed);
    ++count;
  }
  CHECK(count == 20);
}

TEST_CASE("viewer samples and standalone tet meshes (either orientation) build") {
  VOLMAP_REQUIRE_DATA(root, "volmap/viewer-samples");
  const char* files[] = {"volmap/viewer-samples/bimba_input.mesh", "volmap/viewer-samples/bimba_output.mesh",
                         "volmap/viewer-samples/bunny_input.mesh", "volmap/viewer-samples/duck_input.mesh",
                         "volmap/viewer-samples/hand_aigerman.mesh", "volmap/viewer-samples/max.mesh",
                         "volmap/viewer-samples/bimba_object.vtk", "tetmeshes/cinolib/sphere.mesh",
                         "tetmeshes/libigl_tutorial/bunny.mesh", "tetmeshes/robustpolycube/B0.mesh",
                         "tetmeshes/robustpolycube/pente.mesh", "tetmeshes/stardecompositionmaps/open.vtk"};
  for (const char* f : files) {
    const auto p = volmap_test::data_file(f);
    if (p.empty()) {
      MESSAGE("skipped: " << f << " is absent");
      continue;
    }
    const TopologyReport r = check_real_mesh(p);
    INFO(f);
    CHECK(r.boundary_genus_zero);
    CHECK(r.single_tet_component);
  }
}

TEST_CASE("negative: robustpolycube_NY_2 has a genus-1 boundary") {
  VOLMAP_REQUIRE_DATA(p, "negative/robustpolycube_NY_2.mesh");
  const TopologyReport r = check_real_mesh(p);
  CHECK(r.boundary_genus_defined);
  CHECK(r.boundary_genus == 1);
  CHECK_FALSE(r.boundary_genus_zero);
}
