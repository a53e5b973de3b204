// vertex_removal.cpp — docs/mapping.md §8 step 14 (conventions in vertex_removal.hpp). A star's
// link faces are the faces opposite v in the outward order of their tet (kTetFace), so the star's
// region lies on their positive side, as steiner_free_fill.hpp expects. The fill works on local ids
// (the link's vertices), mapped back when the star is replaced.
#include <volmap/volume/vertex_removal.hpp>

#include <volmap/core/error.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/volume/chord_rules.hpp>
#include <volmap/volume/steiner_free_fill.hpp>

#include "flat_array_edit.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace volmap {

namespace {

// The star of v as a fill problem on local ids.
struct LinkProblem {
  std::vector<TetId> star;
  std::vector<VertexId> vertices;  // local id -> mesh vertex
  std::vector<std::array<std::uint32_t, 3>> faces;
  std::vector<double> source, target;  // 3 per local id
  double worst_shape = std::numeric_limits<double>::infinity();  // flattest star tet, worse space
};

double shape_in_both(const double* s[4], const double* t[4]) {
  return std::min(tet_shape(s[0], s[1], s[2], s[3]), tet_shape(t[0], t[1], t[2], t[3]));
}

LinkProblem link_problem(const TetMesh& mesh, const PositionProperty& target, VertexId v) {
  LinkProblem p;
  mesh.vertex_star(v, p.star);
  auto local = [&](VertexId x) {
    const auto it = std::find(p.vertices.begin(), p.vertices.end(), x);
    if (it != p.vertices.end()) return std::uint32_t(it - p.vertices.begin());
    p.vertices.push_back(x);
    p.source.insert(p.source.end(), mesh.vertex_position(x), mesh.vertex_position(x) + 3);
    p.target.insert(p.target.end(), target[x].begin(), target[x].end());
    return std::uint32_t(p.vertices.size() - 1);
  };
  for (TetId t : p.star) {
    const auto tv = mesh.tet_vertices(t);
    const double* s[4];
    const double* g[4];
    for (int i = 0; i < 4; ++i) {
      s[i] = mesh.vertex_position(tv[i]);
      g[i] = target[tv[i]].data();
    }
    p.worst_shape = std::min(p.worst_shape, shape_in_both(s, g));
    const int i = mesh.tet_local_index(t, v);
    p.faces.push_back({local(tv[kTetFace[i][0]]), local(tv[kTetFace[i][1]]), local(tv[kTetFace[i][2]])});
  }
  return p;
}

// The fill's tets on mesh vertices, or empty when none beats the star (fewer tets, shape bound).
std::vector<CavityTet> better_fill(const LinkProblem& p, const VertexRemovalLimits& limits, const TimeBudget& clock) {
  SteinerFreeFillLimits l;
  l.max_nodes = limits.max_nodes_per_vertex;
  l.max_tets = p.star.size();
  l.time_limit_seconds = clock.option_seconds();
  const SteinerFreeFillResult r = fill_without_steiner_points(p.faces, p.source.data(), p.target.data(), p.vertices.size(), l);
  if (!r.found) return {};
  std::vector<CavityTet> fill;
  for (std::size_t k = 0; k < r.tets.size(); k += 4) {
    const double* s[4];
    const double* g[4];
    CavityTet c;
    for (int i = 0; i < 4; ++i) {
      s[i] = &p.source[3 * std::size_t(r.tets[k + i])];
      g[i] = &p.target[3 * std::size_t(r.tets[k + i])];
      c.v[i] = p.vertices[r.tets[k + i]];
    }
    if (shape_in_both(s, g) < kFixShapeRatio * p.worst_shape) return {};
    c.parent = p.star.front();
    fill.push_back(c);
  }
  return fill;
}

}  // namespace

VertexRemovalResult remove_added_vertices(TetMesh& mesh, PositionProperty& target, std::uint32_t first_removable,
                                          const VertexRemovalLimits& limits) {
  const TimeBudget clock(limits.time_limit_seconds);
  VertexRemovalResult res;
  res.tets_before = mesh.num_tets();
  for (int pass = 0; pass < limits.passes; ++pass) {
    const std::size_t removed_before = res.removed;
    for (std::uint32_t id = first_removable; id < mesh.num_vertex_slots() && !clock.expired(); ++id) {
      const VertexId v(id);
      if (!mesh.vertex_is_live(v) || mesh.vertex_is_boundary(v)) continue;
      ++res.tried;
      const LinkProblem p = link_problem(mesh, target, v);
      const std::vector<CavityTet> fill = better_fill(p, limits, clock);
      if (fill.empty()) continue;
      try {
        mesh.replace_cavity(p.star, fill);  // deletes v: the fill does not use it
        ++res.removed;
      } catch (const Error&) {  // refused (the star is not a ball): untouched
      }
    }
    if (res.removed == removed_before) break;
  }
  res.tets_after = mesh.num_tets();
  return res;
}

VertexRemovalResult remove_added_vertices(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                                          std::uint32_t first_removable, const VertexRemovalLimits& limits) {
  return edit_on_flat_arrays(
      source, locked, target_xyz, "remove_added_vertices",
      [&](TetMesh& mesh, PositionProperty& target, const VertexProperty<std::uint8_t>&) {
        return remove_added_vertices(mesh, target, first_removable, limits);
      },
      [](const VertexRemovalResult& r) { return r.removed > 0; });
}

}  // namespace volmap
