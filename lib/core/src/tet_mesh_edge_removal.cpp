// TetMesh edge removal — the n -> 2n-4 flip of an interior edge (datastructure.md §4; conventions in
// tet_mesh.hpp). The ring of the edge (va, vb) is the cycle of the other two vertices of its tets,
// oriented so that (ring[i], ring[i+1], vb, va) keeps the orientation of the tet that holds them.
// For a triangle (p, q, r) of the ring polygon listed in ring order, (p, q, r, va) and (r, q, p, vb)
// then have the orientation of the ring tets (for a planar ring seen with vb above, both are
// positive exactly when va lies below and vb above the triangle's plane). The edit itself is one
// replace_cavity: the ring tets are the cavity, the 2(n-2) tets the fill.
#include <volmap/core/tet_mesh.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <map>
#include <string>
#include <utility>

namespace volmap {

namespace {

[[noreturn]] void refuse(const std::string& reason) { throw Error(ErrorKind::Failed, "", 0, "remove_edge: " + reason); }

// Parity of the permutation p of {0,1,2,3} (true = odd).
bool odd_permutation(const int p[4]) {
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j];
  return inversions % 2 == 1;
}

// The ring of an interior edge: vertices in rotation order and, for each position i, the tet
// holding (ring[i], ring[i+1]) with the edge.
struct EdgeRing {
  VertexId va, vb;
  std::vector<VertexId> vertices;
  std::vector<TetId> tets;
};

// Returns false for a boundary edge or a ring that is not one cycle (a corrupt mesh).
bool read_ring(const TetMesh& m, TetId t, int a, int b, EdgeRing& ring) {
  if (t.idx() >= m.num_tet_slots() || !m.tet_is_live(t) || a < 0 || a > 3 || b < 0 || b > 3 || a == b) return false;
  ring.va = m.tet_vertex(t, a);
  ring.vb = m.tet_vertex(t, b);
  std::map<std::uint32_t, std::pair<std::uint32_t, TetId>> next;  // x -> (y, tet) for each ring tet
  const bool closed = m.edge_star(t, a, b, [&](TetId s, int la, int lb) {
    int c = -1, d = -1;
    for (int i = 0; i < 4; ++i)
      if (i != la && i != lb) (c < 0 ? c : d) = i;
    const int perm[4] = {c, d, lb, la};
    if (odd_permutation(perm)) std::swap(c, d);
    next[m.tet_vertex(s, c).idx()] = {m.tet_vertex(s, d).idx(), s};
  });
  if (!closed || next.size() < 3) return false;
  ring.vertices.clear();
  ring.tets.clear();
  std::uint32_t x = next.begin()->first;
  for (std::size_t k = 0; k < next.size(); ++k) {
    const auto it = next.find(x);
    if (it == next.end()) return false;
    ring.vertices.push_back(VertexId(x));
    ring.tets.push_back(it->second.second);
    x = it->second.first;
  }
  return x == ring.vertices.front().idx();
}

// Is `triangles` a triangulation of the n-gon 0..n-1 (n-2 triangles i < j < k, every side used
// once, every diagonal twice, no two diagonals crossing)? Appends the diagonals to `diagonals`.
bool triangulates_polygon(std::size_t n, const std::vector<std::array<int, 3>>& triangles, std::vector<std::pair<int, int>>& diagonals) {
  if (triangles.size() + 2 != n) return false;
  std::map<std::pair<int, int>, int> uses;
  for (const auto& tri : triangles) {
    if (!(0 <= tri[0] && tri[0] < tri[1] && tri[1] < tri[2] && tri[2] < int(n))) return false;
    ++uses[{tri[0], tri[1]}];
    ++uses[{tri[1], tri[2]}];
    ++uses[{tri[0], tri[2]}];
  }
  for (const auto& [pq, count] : uses) {
    const bool side = pq.second == pq.first + 1 || (pq.first == 0 && pq.second == int(n) - 1);
    if (count != (side ? 1 : 2)) return false;
    if (!side) diagonals.push_back(pq);
  }
  if (uses.size() != n + diagonals.size()) return false;  // every side used
  for (const auto& [i, j] : diagonals)
    for (const auto& [k, l] : diagonals)
      if (i < k && k < j && j < l) return false;
  return true;
}

// The topological part of can_remove_edge / remove_edge; on success `ring` holds the ring.
bool removal_allowed(const TetMesh& m, TetId t, int a, int b, const std::vector<std::array<int, 3>>& triangles, EdgeRing& ring,
                     std::string* why) {
  auto no = [why](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (!read_ring(m, t, a, b, ring)) return no("the edge is not a live interior edge");
  std::vector<std::pair<int, int>> diagonals;
  if (!triangulates_polygon(ring.vertices.size(), triangles, diagonals))
    return no("the triangles do not triangulate the ring of " + std::to_string(ring.vertices.size()) + " vertices");
  for (const auto& [i, j] : diagonals)
    if (m.find_edge(ring.vertices[i], ring.vertices[j], nullptr, nullptr).is_valid())
      return no("edge (" + std::to_string(ring.vertices[i].idx()) + "," + std::to_string(ring.vertices[j].idx()) + ") already exists");
  return true;
}

}  // namespace

std::vector<VertexId> TetMesh::edge_ring(TetId t, int a, int b) const {
  EdgeRing ring;
  if (!read_ring(*this, t, a, b, ring)) refuse("the edge is not a live interior edge");
  return ring.vertices;
}

bool TetMesh::can_remove_edge(TetId t, int a, int b, const std::vector<std::array<int, 3>>& triangles, const double* xyz) const {
  EdgeRing ring;
  if (!removal_allowed(*this, t, a, b, triangles, ring, nullptr)) return false;
  if (!xyz) xyz = xyz_.data();
  auto P = [xyz](VertexId v) { return xyz + 3 * std::size_t(v.idx()); };
  const FpEnvironmentScope fp;
  for (const auto& tri : triangles) {
    const VertexId p = ring.vertices[tri[0]], q = ring.vertices[tri[1]], r = ring.vertices[tri[2]];
    if (fp.orient3d(P(p), P(q), P(r), P(ring.va)) <= 0 || fp.orient3d(P(r), P(q), P(p), P(ring.vb)) <= 0) return false;
  }
  return true;
}

std::vector<TetId> TetMesh::remove_edge(TetId t, int a, int b, const std::vector<std::array<int, 3>>& triangles) {
  EdgeRing ring;
  std::string why;
  if (!removal_allowed(*this, t, a, b, triangles, ring, &why)) refuse(why);
  std::vector<CavityTet> fill;
  fill.reserve(2 * triangles.size());
  for (const auto& tri : triangles) {
    const VertexId p = ring.vertices[tri[0]], q = ring.vertices[tri[1]], r = ring.vertices[tri[2]];
    const TetId parent = ring.tets[tri[0]];
    fill.push_back({{p, q, r, ring.va}, parent});
    fill.push_back({{r, q, p, ring.vb}, parent});
  }
  return replace_cavity(ring.tets, fill).tets;
}

}  // namespace volmap
