// analyze_topology on good and deliberately broken raw arrays (known counts as oracles).
#include <doctest/doctest.h>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/core/local_tables.hpp>
#include <volmap/testing/generate.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/core/topology.hpp>

#include "mesh_test_util.hpp"

#include <array>
#include <map>
#include <random>
#include <set>

using namespace volmap;

namespace {
// Concatenates b after a (vertex ids shifted).
TetMeshData concat(const TetMeshData& a, const TetMeshData& b, double shift_x) {
  TetMeshData d = a;
  const std::uint32_t off = std::uint32_t(a.num_vertices());
  for (std::size_t v = 0; v < b.num_vertices(); ++v) {
    d.xyz.push_back(b.xyz[3 * v] + shift_x);
    d.xyz.push_back(b.xyz[3 * v + 1]);
    d.xyz.push_back(b.xyz[3 * v + 2]);
  }
  for (std::uint32_t v : b.tets) d.tets.push_back(v + off);
  d.vertex_labels.assign(d.num_vertices(), 0);
  d.tet_labels.assign(d.num_tets(), 0);
  return d;
}
}  // namespace

TEST_CASE("a Kuhn ball: every check passes, counts match the grid") {
  const std::size_t n = 3;
  const TopologyReport r = analyze_topology(generate_kuhn_grid(n, n, n));
  CHECK(r.num_tets == 6 * n * n * n);
  CHECK(r.num_boundary_faces == 12 * n * n);
  CHECK(r.num_boundary_vertices == 6 * n * n + 2);  // chi = 2 on a closed triangulated sphere: V = F/2 + 2
  CHECK(r.num_boundary_edges == 18 * n * n);
  CHECK(r.boundary_euler == 2);
  CHECK(r.boundary_genus == 0);
  CHECK(r.boundary_genus_defined);
  CHECK(r.num_tet_components == 1);
  CHECK(r.num_boundary_components == 1);
  CHECK(r.faces_manifold);
  CHECK(r.orientation_consistent);
  CHECK(r.boundary_edges_manifold);
  CHECK(r.boundary_vertices_manifold);
  CHECK(r.boundary_closed);
  CHECK(r.single_tet_component);
  CHECK(r.single_boundary_component);
  CHECK(r.boundary_genus_zero);
  CHECK(r.no_degenerate_tets);
  CHECK(r.no_unused_vertices);
  const auto faces = mesh_test::brute_faces(generate_kuhn_grid(n, n, n).tets);
  CHECK(r.num_faces == faces.size());
  CHECK(r.num_interior_faces == faces.size() - r.num_boundary_faces);
}

TEST_CASE("two components") {
  const TetMeshData a = generate_kuhn_grid(2, 2, 2);
  const TopologyReport r = analyze_topology(concat(a, a, 5.0));
  CHECK(r.num_tet_components == 2);
  CHECK(r.num_boundary_components == 2);
  CHECK_FALSE(r.single_tet_component);
  CHECK_FALSE(r.single_boundary_component);
  CHECK(r.boundary_euler == 4);
  CHECK(r.boundary_genus == 0);  // two spheres
  CHECK(r.boundary_edges_manifold);
  CHECK(r.boundary_vertices_manifold);
}

TEST_CASE("solid torus (3x3x1 grid with the centre cube removed): genus 1") {
  const TetMeshData d = generate_kuhn_grid(3, 3, 1, [](std::size_t i, std::size_t j, std::size_t) { return !(i == 1 && j == 1); });
  const TopologyReport r = analyze_topology(d);
  CHECK(r.boundary_euler == 0);
  CHECK(r.boundary_genus == 1);
  CHECK(r.boundary_genus_defined);
  CHECK_FALSE(r.boundary_genus_zero);
  CHECK(r.single_tet_component);
  CHECK(r.boundary_closed);
  CHECK(r.boundary_edges_manifold);
  CHECK(r.boundary_vertices_manifold);
  CHECK_NOTHROW(TetMesh{d});
}

TEST_CASE("pinched vertex: two cubes touching at one corner") {
  const TetMeshData d = generate_kuhn_grid(2, 2, 2, [](std::size_t i, std::size_t j, std::size_t k) {
    return (i == 0 && j == 0 && k == 0) || (i == 1 && j == 1 && k == 1);
  });
  const TopologyReport r = analyze_topology(d);
  CHECK(r.num_tet_components == 2);        // no shared face
  CHECK(r.num_boundary_components == 1);   // vertex-connected surface
  CHECK(r.boundary_edges_manifold);
  CHECK(r.num_nonmanifold_boundary_vertices == 1);
  CHECK_FALSE(r.boundary_vertices_manifold);
  CHECK_FALSE(r.boundary_genus_defined);
  CHECK(r.example_nonmanifold_vertex != 0xFFFFFFFFu);
  const double* p = &d.xyz[3 * std::size_t(r.example_nonmanifold_vertex)];
  CHECK(p[0] == 1.0);
  CHECK(p[1] == 1.0);
  CHECK(p[2] == 1.0);
}

TEST_CASE("pinched edge: two cubes sharing one grid edge") {
  const TetMeshData d = generate_kuhn_grid(2, 2, 1, [](std::size_t i, std::size_t j, std::size_t) { return i == j; });
  const TopologyReport r = analyze_topology(d);
  CHECK(r.num_overshared_edges == 1);
  CHECK(r.num_nonmanifold_boundary_edges == 1);
  CHECK(r.num_border_edges == 0);
  CHECK(r.boundary_closed);
  CHECK_FALSE(r.boundary_edges_manifold);
  // The two end points of the shared edge have links made of two cycles.
  CHECK(r.num_nonmanifold_boundary_vertices == 2);
}

TEST_CASE("face shared by three tets, inconsistent orientation, degenerate tet, unused vertex") {
  TetMeshData d;
  d.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.3, 0.3, -1, 0.2, 0.2, -2, 9, 9, 9};
  d.tets = {0, 1, 2, 3};
  if (mesh_test::orient_tet(d.xyz, d.tets.data()) < 0) std::swap(d.tets[0], d.tets[1]);
  const std::uint32_t a = d.tets[0], b = d.tets[1], c = d.tets[2];
  d.tets.insert(d.tets.end(), {b, a, c, 4, b, a, c, 5});
  TopologyReport r = analyze_topology(d);
  CHECK(r.num_nonmanifold_faces == 1);
  CHECK_FALSE(r.faces_manifold);
  CHECK(r.example_nonmanifold_face / 4 == 0);
  CHECK(r.num_boundary_faces == 9);
  CHECK(r.num_tet_components == 1);
  CHECK(r.num_unused_vertices == 1);  // vertex 6
  CHECK_FALSE(r.no_unused_vertices);
  CHECK_THROWS_AS(TetMesh{d}, Error);

  TetMeshData inc;
  inc.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.3, 0.3, -1};
  inc.tets = {0, 1, 2, 3, 0, 1, 2, 4};  // shared face (0,1,2) with equal winding
  r = analyze_topology(inc);
  CHECK(r.num_inconsistent_faces == 1);
  CHECK_FALSE(r.orientation_consistent);
  CHECK(r.num_interior_faces == 1);

  TetMeshData deg;
  deg.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  deg.tets = {0, 1, 2, 3, 0, 1, 1, 2};
  r = analyze_topology(deg);
  CHECK(r.num_degenerate_tets == 1);
  CHECK_FALSE(r.no_degenerate_tets);
  CHECK(r.num_boundary_faces == 4);
  CHECK(r.boundary_genus_zero);

  TetMeshData bad = deg;
  bad.tets[3] = 17;
  CHECK_THROWS_AS(analyze_topology(bad), Error);
}

TEST_CASE("empty input") {
  const TopologyReport r = analyze_topology(TetMeshData{});
  CHECK(r.num_tets == 0);
  CHECK(r.num_tet_components == 0);
  CHECK_FALSE(r.single_tet_component);
  CHECK_FALSE(r.boundary_genus_zero);
}

TEST_CASE("random tet soups: analyze_topology agrees with a std::map oracle") {
  std::mt19937 rng(7);
  for (int round = 0; round < 400; ++round) {
    TetMeshData d;
    // Odd rounds: few vertices under many tets, so the face grouping's buckets exceed its
    // insertion-sort size (48 faces) and take the large-bucket sort, with many repeated faces.
    const bool crowded = round % 2 == 1;
    const std::uint32_t nv = crowded ? 5 + rng() % 5 : 4 + rng() % 10;
    const std::size_t nt = crowded ? 20 + rng() % 60 : 1 + rng() % 12;
    d.xyz.assign(3 * nv, 0.0);
    for (std::size_t t = 0; t < nt; ++t)
      for (int i = 0; i < 4; ++i) d.tets.push_back(rng() % nv);
    const TopologyReport r = analyze_topology(d);
    // Oracle.
    std::vector<char> deg(nt, 0);
    for (std::size_t t = 0; t < nt; ++t)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < i; ++j) deg[t] |= d.tets[4 * t + i] == d.tets[4 * t + j];
    TetMeshData live = d;
    for (std::size_t t = 0; t < nt; ++t)
      if (deg[t]) live.tets[4 * t] = 0xFFFFFFFFu;
    const auto faces = mesh_test::brute_faces(live.tets);
    std::size_t boundary = 0, nonmanifold = 0, interior = 0;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> bedges;
    std::set<std::uint32_t> bverts;
    for (const auto& [key, hs] : faces) {
      if (hs.size() == 1) {
        ++boundary;
        for (int a = 0; a < 3; ++a) {
          bverts.insert(key[a]);
          for (int b = a + 1; b < 3; ++b) ++bedges[{key[a], key[b]}];
        }
      } else if (hs.size() == 2) {
        ++interior;
      } else {
        ++nonmanifold;
      }
    }
    std::size_t border = 0, over = 0;
    for (const auto& [e, c] : bedges) {
      border += c == 1;
      over += c > 2;
    }
    // Tet components by repeated relaxation over shared faces.
    std::vector<std::size_t> comp(nt);
    for (std::size_t t = 0; t < nt; ++t) comp[t] = t;
    for (bool changed = true; changed;) {
      changed = false;
      for (const auto& [key, hs] : faces)
        for (std::uint32_t h : hs)
          for (std::uint32_t g : hs)
            if (comp[g / 4] > comp[h / 4]) {
              comp[g / 4] = comp[h / 4];
              changed = true;
            }
    }
    std::set<std::size_t> roots;
    for (std::size_t t = 0; t < nt; ++t)
      if (!deg[t]) roots.insert(comp[t]);
    INFO("round " << round);
    CHECK(r.num_degenerate_tets == std::size_t(std::count(deg.begin(), deg.end(), 1)));
    CHECK(r.num_faces == faces.size());
    CHECK(r.num_boundary_faces == boundary);
    CHECK(r.num_interior_faces == interior);
    CHECK(r.num_nonmanifold_faces == nonmanifold);
    CHECK(r.num_boundary_edges == bedges.size());
    CHECK(r.num_boundary_vertices == bverts.size());
    CHECK(r.num_border_edges == border);
    CHECK(r.num_overshared_edges == over);
    CHECK(r.boundary_euler == long(bverts.size()) - long(bedges.size()) + long(boundary));
    CHECK(r.num_tet_components == roots.size());
    // Duplicates: tets (of four distinct ids) whose vertex set is an earlier tet's.
    std::map<std::array<std::uint32_t, 4>, std::uint32_t> first_with;
    std::size_t duplicates = 0;
    std::uint32_t dup_first = 0xFFFFFFFFu, dup_second = 0xFFFFFFFFu;
    for (std::uint32_t t = 0; t < nt; ++t) {
      if (deg[t]) continue;
      std::array<std::uint32_t, 4> key;
      std::copy(&d.tets[4 * t], &d.tets[4 * t] + 4, key.begin());
      std::sort(key.begin(), key.end());
      const auto [it, fresh] = first_with.emplace(key, t);
      if (fresh) continue;
      if (duplicates++ == 0) dup_first = it->second, dup_second = t;
    }
    CHECK(r.num_duplicate_tets == duplicates);
    CHECK(r.example_duplicate_first == dup_first);
    CHECK(r.example_duplicate_second == dup_second);
  }
}

TEST_CASE("boundary half-faces agree with the IO module's boundary_half_faces (independent code)") {
  std::mt19937 rng(11);
  std::vector<TetMeshData> cases = {generate_kuhn_grid(3, 2, 4),
                                    generate_kuhn_grid(3, 3, 1, [](std::size_t i, std::size_t j, std::size_t) { return !(i == 1 && j == 1); })};
  for (int round = 0; round < 100; ++round) {  // soups without repeated ids in a tet
    TetMeshData d;
    const std::uint32_t nv = 4 + rng() % 8;
    d.xyz.assign(3 * nv, 0.0);
    for (std::size_t t = 0, nt = 1 + rng() % 10; t < nt; ++t) {
      std::uint32_t p[4];
      do {
        for (auto& x : p) x = rng() % nv;
      } while (p[0] == p[1] || p[0] == p[2] || p[0] == p[3] || p[1] == p[2] || p[1] == p[3] || p[2] == p[3]);
      d.tets.insert(d.tets.end(), p, p + 4);
    }
    cases.push_back(d);
  }
  for (const TetMeshData& d : cases) {
    const TopologyReport r = analyze_topology(d);
    const std::vector<std::uint64_t> io = boundary_half_faces(d);
    REQUIRE(io.size() == r.boundary_half_faces.size());
    for (std::size_t k = 0; k < io.size(); ++k) CHECK(io[k] == r.boundary_half_faces[k]);
    const std::vector<std::uint32_t> bv = boundary_vertex_ids(d);
    CHECK(bv.size() == r.num_boundary_vertices);
  }
}

namespace {
// analyze_surface_topology against std::map / std::set oracles: per undirected edge of a triangle
// with three distinct ids, its triangles and how many traverse it from the lower id to the higher;
// per vertex, its link (the edges (next, prev) of its triangles): manifold when the link is
// connected and no link vertex has degree above 2.
void check_surface_against_oracle(std::uint32_t nv, const std::vector<std::uint32_t>& tris) {
  const SurfaceTopology s = analyze_surface_topology(nv, tris);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<int, int>> edges;  // (count, forward)
  std::map<std::uint32_t, std::vector<std::pair<std::uint32_t, std::uint32_t>>> links;
  std::set<std::uint32_t> used;
  std::size_t valid = 0;
  for (std::size_t t = 0; t < tris.size() / 3; ++t) {
    const std::uint32_t* v = &tris[3 * t];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
    ++valid;
    for (int k = 0; k < 3; ++k) {
      used.insert(v[k]);
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      auto& e = edges[{std::min(a, b), std::max(a, b)}];
      ++e.first;
      e.second += a < b;
      links[a].push_back({b, v[(k + 2) % 3]});
    }
  }
  std::size_t border = 0, over = 0, inconsistent = 0, nonmanifold = 0;
  std::uint32_t example = 0xFFFFFFFFu, example_vertex = 0xFFFFFFFFu;
  for (const auto& [e, c] : edges) {
    border += c.first == 1;
    over += c.first > 2;
    inconsistent += c.first == 2 && c.second != 1;
    if (c.first != 2 && example == 0xFFFFFFFFu) example = e.first;
  }
  for (const auto& [v, link] : links) {
    std::map<std::uint32_t, std::set<std::uint32_t>> adjacent;
    std::map<std::uint32_t, int> degree;
    for (const auto& [a, b] : link) adjacent[a].insert(b), adjacent[b].insert(a), ++degree[a], ++degree[b];
    std::set<std::uint32_t> seen{adjacent.begin()->first};
    std::vector<std::uint32_t> stack{adjacent.begin()->first};
    while (!stack.empty()) {
      const std::uint32_t w = stack.back();
      stack.pop_back();
      for (std::uint32_t x : adjacent[w])
        if (seen.insert(x).second) stack.push_back(x);
    }
    bool ok = seen.size() == adjacent.size();
    for (const auto& [w, d] : degree) ok = ok && d <= 2;
    if (!ok && nonmanifold++ == 0) example_vertex = v;
  }
  CHECK(s.num_triangles == valid);
  CHECK(s.num_used_vertices == used.size());
  CHECK(s.num_edges == edges.size());
  CHECK(s.num_border_edges == border);
  CHECK(s.num_overshared_edges == over);
  CHECK(s.num_inconsistent_edges == inconsistent);
  CHECK(s.example_nonmanifold_edge_vertex == example);
  CHECK(s.num_nonmanifold_vertices == nonmanifold);
  CHECK(s.example_nonmanifold_vertex == example_vertex);
  CHECK(s.euler == long(used.size()) - long(edges.size()) + long(valid));
}

// The outward boundary triangles of a tet mesh.
std::vector<std::uint32_t> boundary_triangles(const TetMeshData& mesh) {
  std::vector<std::uint32_t> tris;
  for (std::uint32_t h : analyze_topology(mesh).boundary_half_faces)
    for (int k = 0; k < 3; ++k) tris.push_back(mesh.tets[4 * (h / 4) + kTetFace[h % 4][k]]);
  return tris;
}
}  // namespace

TEST_CASE("random triangle soups: analyze_surface_topology agrees with std::map oracles") {
  std::mt19937 rng(19);
  for (int round = 0; round < 300; ++round) {
    const std::uint32_t nv = 3 + rng() % 8;
    std::vector<std::uint32_t> tris;
    for (std::size_t t = 0, nt = 1 + rng() % 14; t < nt; ++t)
      for (int k = 0; k < 3; ++k) tris.push_back(rng() % nv);
    INFO("round " << round);
    check_surface_against_oracle(nv, tris);
  }
}

// Closed, consistently oriented 2-manifolds take the per-vertex cycle test (closed_manifold_links);
// one defect anywhere must send them to the general analysis with the same counts as the oracle.
TEST_CASE("closed surfaces and their one-defect variants: analyze_surface_topology agrees with the oracles") {
  std::mt19937 rng(23);
  const std::vector<TetMeshData> solids = {generate_kuhn_grid(1, 1, 1), generate_kuhn_grid(3, 2, 2),
                                           generate_kuhn_grid(4, 4, 3)};
  for (const TetMeshData& solid : solids) {
    const std::uint32_t nv = std::uint32_t(solid.num_vertices());
    const std::vector<std::uint32_t> closed = boundary_triangles(solid);
    const std::size_t nf = closed.size() / 3;
    const SurfaceTopology s = analyze_surface_topology(nv, closed);
    CHECK(s.genus_defined);
    CHECK(s.genus == 0);
    CHECK(s.num_edges == 3 * nf / 2);
    check_surface_against_oracle(nv, closed);
    for (int round = 0; round < 40; ++round) {
      std::vector<std::uint32_t> t = closed;
      const std::size_t f = rng() % nf, g = (f + 1 + rng() % (nf - 1)) % nf;
      switch (round % 6) {
        case 0: std::swap(t[3 * f + 1], t[3 * f + 2]); break;       // one triangle flipped
        case 1: t.erase(t.begin() + 3 * f, t.begin() + 3 * f + 3); break;  // a hole
        case 2: t.insert(t.end(), t.begin() + 3 * f, t.begin() + 3 * f + 3); break;  // a triangle twice
        case 3: t.insert(t.end(), {t[3 * f], t[3 * f + 2], t[3 * f + 1]}); break;    // and reversed
        case 4: t[3 * f] = t[3 * g + (round / 6) % 3]; break;        // a corner moved: pinches
        case 5: {                                                    // a second copy through one vertex
          const std::uint32_t shared = t[3 * f];
          const std::size_t n = t.size();
          for (std::size_t k = 0; k < n; ++k) t.push_back(t[k] == shared ? shared : t[k] + nv);
          break;
        }
      }
      std::uint32_t max_id = 0;
      for (std::uint32_t v : t) max_id = std::max(max_id, v);
      INFO("solid with " << nv << " vertices, round " << round);
      check_surface_against_oracle(max_id + 1, t);
      if (round % 6 == 5) CHECK(analyze_surface_topology(max_id + 1, t).num_nonmanifold_vertices == 1);
    }
  }
}

// Duplicate tets are counted only where they can exist (a non-manifold face, a second component, or
// no boundary at all); each of the three situations must still find them.
TEST_CASE("duplicate tets in a clean mesh's three possible situations are counted") {
  const TetMeshData grid = generate_kuhn_grid(3, 3, 3);
  const TopologyReport clean = analyze_topology(grid);
  CHECK(clean.num_duplicate_tets == 0);
  SUBCASE("a copy of an inner tet: its faces become non-manifold") {
    TetMeshData d = grid;
    const std::size_t t = grid.num_tets() / 2;
    d.tets.insert(d.tets.end(), grid.tets.begin() + 4 * t, grid.tets.begin() + 4 * t + 4);
    const TopologyReport r = analyze_topology(d);
    CHECK(r.num_duplicate_tets == 1);
    CHECK(r.example_duplicate_first == t);
    CHECK(r.example_duplicate_second == grid.num_tets());
  }
  SUBCASE("a lone tet and its copy (reversed) beside the grid: a second component") {
    const TetMeshData one = generate_kuhn_grid(1, 1, 1);
    TetMeshData pair = one;
    pair.tets.assign({one.tets[0], one.tets[1], one.tets[2], one.tets[3], one.tets[1], one.tets[0], one.tets[2], one.tets[3]});
    const TetMeshData d = concat(grid, pair, 10.0);
    const TopologyReport r = analyze_topology(d);
    CHECK(r.num_tet_components == 2);
    CHECK(r.num_nonmanifold_faces == 0);
    CHECK(r.num_duplicate_tets == 1);
    CHECK(r.example_duplicate_first == grid.num_tets());
  }
  SUBCASE("the whole mesh is one tet twice: no boundary") {
    TetMeshData d = generate_kuhn_grid(1, 1, 1);
    d.tets.resize(4);
    d.tets.insert(d.tets.end(), {d.tets[1], d.tets[0], d.tets[2], d.tets[3]});
    const TopologyReport r = analyze_topology(d);
    CHECK(r.num_tet_components == 1);
    CHECK(r.num_boundary_faces == 0);
    CHECK(r.num_duplicate_tets == 1);
  }
}
