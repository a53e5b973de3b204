// edge_removal_fewer_tets.cpp — docs/mapping.md §8 step 14c (conventions in
// edge_removal_fewer_tets.hpp). TetMesh::can_flip_3_2 decides the topology and the exact source
// signs; the map's signs (exact) and the shape bound are checked here on the same two new tets:
// t with vb replaced by z and t with va replaced by z, z the ring vertex t lacks.
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
  DegreeThreeFlips(TetMesh& mesh, const PositionProperty& target) : mesh_(mesh), target_(target) {}

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

  bool positive_in_map(const std::array<VertexId, 4>& v) const {
    return fp_.orient3d(target_[v[0]].data(), target_[v[1]].data(), target_[v[2]].data(), target_[v[3]].data()) > 0;
  }

  bool admissible(TetId t, int a, int b) const {
    if (!mesh_.can_flip_3_2(t, a, b)) return false;  // topology, degree 3, both source signs
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
    return positive_in_map(lower) && positive_in_map(upper) && std::min(shape(lower), shape(upper)) >= kFixShapeRatio * worst;
  }

  TetMesh& mesh_;
  const PositionProperty& target_;
  const FpEnvironmentScope fp_;
};

}  // namespace

EdgeRemovalResult remove_degree3_edges(TetMesh& mesh, const PositionProperty& target, const EdgeRemovalLimits& limits) {
  const TimeBudget clock(limits.time_limit_seconds);
  EdgeRemovalResult res;
  res.tets_before = mesh.num_tets();
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
