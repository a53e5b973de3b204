// bad_tet_split.cpp — splitting the edges of non-positive tets (conventions in bad_tet_split.hpp).
#include <volmap/volume/bad_tet_split.hpp>

#include <volmap/core/local_tables.hpp>
#include <volmap/volume/chord_split.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <array>
#include <set>
#include <utility>
#include <vector>

namespace volmap {
namespace {

double squared_distance(const std::array<double, 3>& p, const std::array<double, 3>& q) {
  double d = 0;
  for (int i = 0; i < 3; ++i) d += (p[i] - q[i]) * (p[i] - q[i]);
  return d;
}

// The interior edges of the non-positive tets, longest target edge first.
std::vector<std::array<std::uint32_t, 2>> edges_to_split(const MapState& state, std::size_t& bad_tets) {
  const TetMesh& mesh = state.source;
  const std::vector<std::uint32_t> bad = nonpositive_tets(state.target_xyz(), mesh.tet_vertex_array());
  bad_tets = bad.size();
  std::set<std::array<std::uint32_t, 2>> seen;
  std::vector<std::pair<double, std::array<std::uint32_t, 2>>> edges;
  for (std::uint32_t t : bad) {
    const auto v = mesh.tet_vertices(TetId(t));
    for (const auto& e : kTetEdge) {
      std::array<std::uint32_t, 2> key = {v[e[0]].idx(), v[e[1]].idx()};
      if (key[0] > key[1]) std::swap(key[0], key[1]);
      if (!seen.insert(key).second) continue;
      if (!mesh.edge_star(TetId(t), e[0], e[1], [](TetId) {})) continue;  // an edge of ∂M
      edges.push_back({squared_distance(state.target[v[e[0]]], state.target[v[e[1]]]), key});
    }
  }
  std::stable_sort(edges.begin(), edges.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<std::array<std::uint32_t, 2>> out;
  for (const auto& e : edges) out.push_back(e.second);
  return out;
}

}  // namespace

BadTetSplitResult split_edges_of_nonpositive_tets(MapState& state, std::size_t max_edges) {
  state.require_compact();
  BadTetSplitResult r;
  r.tets_before = state.source.num_tets();
  std::vector<std::array<std::uint32_t, 2>> edges = edges_to_split(state, r.bad_tets);
  if (max_edges > 0 && edges.size() > max_edges) edges.resize(max_edges);
  for (const auto& e : edges) {
    const std::size_t slots = state.source.num_vertex_slots();
    const std::array<double, 3> a = state.target[VertexId(e[0])], b = state.target[VertexId(e[1])];
    const ChordSplitResult done = split_chords(state.source, {e}, {});
    r.edges_skipped += done.splits_refused;  // no exactly positive split point: the mesh is unchanged
    if (state.source.num_vertex_slots() == slots) continue;  // the edge was gone, or refused
    const VertexId w(std::uint32_t(state.source.num_vertex_slots() - 1));
    state.target[w] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
    state.locked[w] = 0;
    ++r.edges_split;
  }
  state.source.compact();
  r.tets_after = state.source.num_tets();
  return r;
}

}  // namespace volmap
