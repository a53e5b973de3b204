// edge_removal_fewer_tets.cpp — docs/mapping.md §8 step 14c (conventions in
// edge_removal_fewer_tets.hpp). TetMesh::can_flip_3_2 decides the topology and the exact signs,
// once on the source and once on the map's positions (the PositionProperty's 3 doubles per vertex
// slot, contiguous); the shape bound is checked here on the same two new tets (t with vb replaced
// by z, t with va replaced by z; z the ring vertex t lacks). A flip adds no vertex, so the
// property's storage never moves.
#include <volmap/volume/edge_removal_fewer_tets.hpp>

#include <volmap/core/time_budget.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/chord_rules.hpp>

#include "flat_array_edit.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace volmap {

namespace {

class DegreeThreeFlips {
 public:
  DegreeThreeFlips(TetMesh& mesh, const PositionProperty& target)
      : mesh_(mesh), target_(target), target_xyz_(target.data().front().data()) {}

  // Flips the first admissible degree-3 interior edge of t; true when one was flipped.
  bool flip_an_edge(TetId t) {
    for (const auto& e : kTetEdge)
      if (admissible(t, e[0], e[1])) {
        mesh_.flip_3_2(t, e[0], e[1]);
        return true;
      }
    return false;
  }

 private:
  double shape(const std::array<VertexId, 4>& v) const {
    const double* s[4];
    const double* g[4];
    for (int i = 0; i < 4; ++i) {
      s[i] = mesh_.vertex_position(v[i]);
      g[i] = target_[v[i]].data();
    }
    return std::min(tet_shape(s[0], s[1], s[2], s[3]), tet_shape(g[0], g[1], g[2], g[3]));
  }

  bool admissible(TetId t, int a, int b) const {
    // Topology, degree 3 and both source signs; then both map signs (exact).
    if (!mesh_.can_flip_3_2(t, a, b) || !mesh_.can_flip_3_2(t, a, b, target_xyz_)) return false;
    double worst = std::numeric_limits<double>::infinity();
    VertexId z;
    const auto tv = mesh_.tet_vertices(t);
    mesh_.edge_star(t, a, b, [&](TetId s) {
      worst = std::min(worst, shape(mesh_.tet_vertices(s)));
      for (VertexId v : mesh_.tet_vertices(s))
        if (std::find(tv.begin(), tv.end(), v) == tv.end()) z = v;
    });
    std::array<VertexId, 4> lower = tv, upper = tv;
    lower[std::size_t(b)] = z;
    upper[std::size_t(a)] = z;
    return std::min(shape(lower), shape(upper)) >= kFixShapeRatio * worst;
  }

  TetMesh& mesh_;
  const PositionProperty& target_;
  const double* target_xyz_;
};

}  // namespace

EdgeRemovalResult remove_degree3_edges(TetMesh& mesh, const PositionProperty& target, const EdgeRemovalLimits& limits) {
  const TimeBudget clock(limits.time_limit_seconds);
  const FpEnvironmentScope fp;
  EdgeRemovalResult res;
  res.tets_before = mesh.num_tets();
  if (mesh.num_vertex_slots() == 0) return res;
  DegreeThreeFlips flips(mesh, target);
  for (int pass = 0; pass < limits.passes && !clock.expired(); ++pass) {
    const std::size_t before = res.flips;
    // flip_3_2 reuses one of the three slots and leaves a tombstone: the slot count never grows.
    for (std::uint32_t t = 0; t < mesh.num_tet_slots() && !clock.expired(); ++t)
      if (mesh.tet_is_live(TetId(t)) && flips.flip_an_edge(TetId(t))) ++res.flips;
    if (res.flips == before) break;
  }
  res.tets_after = mesh.num_tets();
  return res;
}

EdgeRemovalResult remove_degree3_edges(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                                       const EdgeRemovalLimits& limits) {
  return edit_on_flat_arrays(
      source, locked, target_xyz, "remove_degree3_edges",
      [&](TetMesh& mesh, PositionProperty& target, const VertexProperty<std::uint8_t>&) {
        return remove_degree3_edges(mesh, target, limits);
      },
      [](const EdgeRemovalResult& r) { return r.flips > 0; });
}

}  // namespace volmap
