// The surface mapper's steps on its OpenMesh working surface (white box: lib/surface/src headers),
// on Kuhn grids whose geometry is known exactly:
//  - split_edge: OpenMesh's 2-to-4 split at the exact midpoint, the next output id, a closed
//    consistently oriented surface afterwards; rings turn counter-clockwise seen from outside;
//  - the split replay: after arbitrary splits, the refined tets' boundary (from the TetMesh) is the
//    working surface's face set, vertex for vertex, also when the input has unused vertices;
//  - the embedded graph: arcs are simple paths between their nodes' vertices, disjoint except at
//    nodes, every arc edge labelled with its arc and direction, no chord left between graph vertices.
#include <doctest/doctest.h>
#include <volmap/predicates.hpp>
#include <volmap/surface/domain.hpp>
#include <volmap/testing/generate.hpp>

#include "arc_tracing.hpp"
#include "split_replay.hpp"
#include "working_surface.hpp"

#include <algorithm>
#include <array>
#include <set>
#include <vector>

using namespace volmap;
using namespace volmap::surface_detail;

namespace {

// A triangle as its rotation starting at the smallest id (orientation kept).
std::array<std::uint32_t, 3> canonical(std::array<std::uint32_t, 3> t) {
  while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  return t;
}

std::set<std::array<std::uint32_t, 3>> surface_faces(const WorkingSurface& s) {
  std::set<std::array<std::uint32_t, 3>> out;
  for (auto f : s.mesh.faces()) {
    const auto h = s.mesh.halfedge_handle(f);
    out.insert(canonical({s.vid_of(s.mesh.from_vertex_handle(h)), s.vid_of(s.mesh.to_vertex_handle(h)),
                          s.vid_of(s.mesh.to_vertex_handle(s.mesh.next_halfedge_handle(h)))}));
  }
  return out;
}

bool closed_and_consistent(const SurfaceMesh& m) {
  for (auto h : m.halfedges()) {
    if (m.is_boundary(h)) return false;
    const auto o = m.opposite_halfedge_handle(h);
    if (m.from_vertex_handle(h) != m.to_vertex_handle(o) || m.to_vertex_handle(h) != m.from_vertex_handle(o)) return false;
  }
  return static_cast<long>(m.n_vertices()) - static_cast<long>(m.n_edges()) + static_cast<long>(m.n_faces()) == 2;
}

}  // namespace

TEST_CASE("working surface: OpenMesh edge splits at exact midpoints with the next output ids, CCW rings") {
  const TetMeshData grid = generate_kuhn_grid(2, 2, 2);  // vertex (i,j,k) = i + 3 (j + 3 k)
  const SourceTetMesh source(grid);
  const BoundarySurface boundary = source.boundary_surface();
  WorkingSurface s(boundary, source.num_input_vertices());
  REQUIRE(closed_and_consistent(s.mesh));
  const std::size_t nv = s.mesh.n_vertices(), ne = s.mesh.n_edges(), nf = s.mesh.n_faces();
  // Vertex indices follow vids.
  for (auto v : s.mesh.vertices())
    if (v.idx() > 0) CHECK(s.vid_of(v) > s.vid_of(VertexHandle(v.idx() - 1)));
  // Split the edge between grid vertices 0 and 1: (0,0,0)-(1,0,0).
  VertexHandle a, b;
  for (auto v : s.mesh.vertices()) {
    if (s.vid_of(v) == 0) a = v;
    if (s.vid_of(v) == 1) b = v;
  }
  const auto h = s.mesh.find_halfedge(a, b);
  REQUIRE(h.is_valid());
  const VertexHandle m = s.split_edge(s.mesh.edge_handle(h));
  CHECK(s.mesh.n_vertices() == nv + 1);
  CHECK(s.mesh.n_edges() == ne + 3);
  CHECK(s.mesh.n_faces() == nf + 2);
  CHECK(closed_and_consistent(s.mesh));
  CHECK(s.vid_of(m) == grid.num_vertices());
  CHECK(s.point(m)[0] == 0.5);
  CHECK(s.point(m)[1] == 0.0);
  CHECK(s.point(m)[2] == 0.0);
  REQUIRE(s.splits.size() == 1);
  CHECK(std::set<std::uint32_t>{s.splits[0].a, s.splits[0].b} == std::set<std::uint32_t>{0, 1});
  CHECK(s.splits[0].m == grid.num_vertices());
  std::vector<VertexHandle> ring;
  s.ring(m, ring);
  CHECK(ring.size() == 4);
  CHECK(std::count(ring.begin(), ring.end(), a) == 1);
  CHECK(std::count(ring.begin(), ring.end(), b) == 1);
  // The centre of the top face, (1,1,2) = vid 22: its neighbours turn counter-clockwise seen from +z.
  VertexHandle top;
  for (auto v : s.mesh.vertices())
    if (s.vid_of(v) == 22) top = v;
  REQUIRE(top.is_valid());
  s.ring(top, ring);
  REQUIRE(ring.size() >= 4);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const double* p = s.point(top);
    const double* q = s.point(ring[i]);
    const double* r = s.point(ring[(i + 1) % ring.size()]);
    CHECK(orient2d(p, q, r) > 0);  // x, y of points on the plane z = 2
  }
}

TEST_CASE("split replay: the refined tets' boundary is the working surface, with and without unused vertices") {
  for (bool spare : {false, true}) {
    CAPTURE(spare);
    TetMeshData grid = generate_kuhn_grid(3, 2, 2);
    if (spare) {  // an unused vertex at id 0: every id of the grid moves up by one
      grid.xyz.insert(grid.xyz.begin(), {0.5, 0.5, 0.5});
      grid.vertex_labels.insert(grid.vertex_labels.begin(), 7);
      for (auto& v : grid.tets) ++v;
    }
    SourceTetMesh source(grid);
    WorkingSurface s(source.boundary_surface(), source.num_input_vertices());
    // Split every third edge, then some edges made by those splits.
    std::vector<EdgeHandle> edges(s.mesh.edges().begin(), s.mesh.edges().end());
    for (std::size_t i = 0; i < edges.size(); i += 3) s.split_edge(edges[i]);
    const std::size_t after_first = s.mesh.n_edges();
    for (std::size_t i = edges.size(); i < after_first; i += 4) s.split_edge(EdgeHandle(static_cast<int>(i)));
    const auto refined = source.refine(s.splits);
    // A second replay starts again from the input (the first edited the TetMesh in place).
    const auto again = source.refine(s.splits);
    CHECK(again.mesh.tets == refined.mesh.tets);
    CHECK(again.mesh.xyz == refined.mesh.xyz);
    CHECK(refined.mesh.num_vertices() == grid.num_vertices() + s.splits.size());
    if (spare) {
      CHECK(refined.mesh.xyz[0] == 0.5);
      CHECK(refined.mesh.vertex_labels[0] == 7);
    }
    std::set<std::array<std::uint32_t, 3>> tet_faces;
    for (const auto& t : refined.boundary) tet_faces.insert(canonical(t));
    CHECK(tet_faces == surface_faces(s));
    const auto& xyz = refined.mesh.xyz;
    for (const EdgeSplit& sp : s.splits)
      for (int k = 0; k < 3; ++k) CHECK(xyz[3 * sp.m + k] == 0.5 * (xyz[3 * sp.a + k] + xyz[3 * sp.b + k]));
    const auto signs = orient3d_tets(refined.mesh.xyz.data(), refined.mesh.num_vertices(), refined.mesh.tets.data(),
                                     refined.mesh.num_tets(), nullptr);
    CHECK(signs.positive == refined.mesh.num_tets());
  }
}

// Whether graph vertices u and w lie on one straight line of the domain: the targets of the nodes of
// every arc through u and every arc through w, compared by exact orientation on the target points.
static bool on_one_domain_line(const Domain& d, const EmbeddedGraph& g, VertexHandle u, VertexHandle w) {
  auto arcs_through = [&](VertexHandle v) {
    std::vector<int> arcs;
    for (std::size_t a = 0; a < g.arc_path.size(); ++a)
      if (std::find(g.arc_path[a].begin(), g.arc_path[a].end(), v) != g.arc_path[a].end()) arcs.push_back(int(a));
    return arcs;
  };
  for (int a : arcs_through(u))
    for (int b : arcs_through(w)) {
      const Point3 p = d.targets[d.arcs[a].from], q = d.targets[d.arcs[a].to];
      bool line = true;
      for (int node : {d.arcs[b].from, d.arcs[b].to}) {
        const Point3 r = d.targets[node];
        const double cx = (q[1] - p[1]) * (r[2] - p[2]) - (q[2] - p[2]) * (r[1] - p[1]);
        const double cy = (q[2] - p[2]) * (r[0] - p[0]) - (q[0] - p[0]) * (r[2] - p[2]);
        const double cz = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
        line = line && cx == 0 && cy == 0 && cz == 0;  // small integer targets: exact in doubles
      }
      if (line) return true;
    }
  return false;
}

TEST_CASE("embedded domain graph: simple disjoint arcs between their nodes, labelled edges, chords by the rule") {
  const TetMeshData grid = generate_kuhn_grid(4, 4, 4);
  const SourceTetMesh source(grid);
  for (const ChordSplitRule rule : {ChordSplitRule::AfterEveryArc, ChordSplitRule::OnlyAlongOneLine})
  for (const char* name : {"cube", "octa", "star"}) {
    CAPTURE(name);
    CAPTURE(int(rule));
    const Domain d = builtin_domain(name);
    WorkingSurface s(source.boundary_surface(), source.num_input_vertices());
    const EmbeddedGraph g = embed_domain_graph(s, d, spanning_tree_first_order(d), rule, {0, 0, 0}, {4, 4, 4});
    REQUIRE_NOTHROW(check_rotations(s, d, g));
    std::vector<int> uses(s.mesh.n_vertices(), 0);
    for (std::size_t a = 0; a < d.arcs.size(); ++a) {
      const auto& p = g.arc_path[a];
      REQUIRE(p.size() >= 2);
      CHECK(p.front() == g.node_vertex[d.arcs[a].from]);
      CHECK(p.back() == g.node_vertex[d.arcs[a].to]);
      for (std::size_t i = 1; i + 1 < p.size(); ++i) ++uses[p[i].idx()];
      for (std::size_t i = 0; i + 1 < p.size(); ++i) {
        const auto h = s.mesh.find_halfedge(p[i], p[i + 1]);
        REQUIRE(h.is_valid());
        const int label = s.mesh.property(s.arc_label, s.mesh.edge_handle(h));
        CHECK((label - 1) / 2 == static_cast<int>(a));
        CHECK((h.idx() & 1) == (label - 1) % 2);  // h runs from -> to
      }
    }
    for (auto v : g.node_vertex) CHECK(uses[v.idx()] == 0);
    for (auto u : uses) CHECK(u <= 1);
    std::size_t graph_edges = 0, labelled = 0, chords = 0;
    for (auto e : s.mesh.edges()) {
      const auto h = s.mesh.halfedge_handle(e, 0);
      const VertexHandle u = s.mesh.from_vertex_handle(h), w = s.mesh.to_vertex_handle(h);
      const bool both = s.is_on_graph(u) && s.is_on_graph(w);
      graph_edges += both;
      labelled += s.is_arc_edge(e);
      if (!both || s.is_arc_edge(e)) continue;
      ++chords;
      CHECK(rule == ChordSplitRule::OnlyAlongOneLine);    // the reference's rule leaves no chord
      CHECK_FALSE(on_one_domain_line(d, g, u, w));        // the lean rule: none along one line
    }
    CHECK(graph_edges == labelled + chords);
    // The lean rule splits at most what the reference's does.
    if (rule == ChordSplitRule::OnlyAlongOneLine) {
      WorkingSurface r(source.boundary_surface(), source.num_input_vertices());
      embed_domain_graph(r, d, spanning_tree_first_order(d), ChordSplitRule::AfterEveryArc, {0, 0, 0}, {4, 4, 4});
      CHECK(s.splits.size() <= r.splits.size());
    }
  }
}
