// feasibility.cpp — exact pre-checks of docs/mapping.md §3 on the source TetMesh (faces and edges from
// its half-face structure; lists sorted by vertex ids).
#include <volmap/volume/feasibility.hpp>

#include <volmap/core/error.hpp>
#include <volmap/volume/chord_rules.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>

namespace volmap {

FeasibilityReport analyze_feasibility(const TetMeshData& source, const std::vector<std::uint8_t>& locked,
                                      const std::vector<double>& target_xyz) {
  return analyze_feasibility(TetMesh(source), locked, target_xyz);
}

FeasibilityReport analyze_feasibility(const TetMesh& source, const std::vector<std::uint8_t>& locked,
                                      const std::vector<double>& target_xyz) {
  const std::size_t nv = source.num_vertex_slots(), nt = source.num_tet_slots();
  if (locked.size() != nv || target_xyz.size() != 3 * nv)
    throw Error(ErrorKind::BadInput, "", 0, "feasibility: inconsistent array sizes");
  if (source.num_free_tet_slots() != 0 || source.num_vertices() != nv)
    throw Error(ErrorKind::BadInput, "", 0, "feasibility: the mesh has tombstones (compact it first)");
  const std::vector<std::uint32_t>& tets = source.tet_vertex_array();
  FeasibilityReport report;
  const double* X = target_xyz.data();
  auto P = [X](std::uint32_t v) { return X + 3 * std::size_t(v); };

  const ChordRules rules(source, locked, target_xyz);

  // Boundary faces (outward) and the enclosed volume's sign.
  const Span<HalfFaceId> bfaces = source.boundary_half_faces();
  std::vector<std::array<std::uint32_t, 3>> btri(bfaces.size());
  for (std::size_t f = 0; f < bfaces.size(); ++f) {
    const auto fv = source.half_face_vertices(bfaces[f]);
    btri[f] = {fv[0].idx(), fv[1].idx(), fv[2].idx()};
  }
  static_assert(sizeof(btri[0]) == 3 * sizeof(std::uint32_t), "triangles are read as 3 ids each");
  report.boundary_volume_sign = enclosed_volume_sign(X, nv, btri.empty() ? nullptr : btri[0].data(), btri.size());

  // All edges as sorted pairs, each with whether it is on the boundary (its edge star is open).
  struct Edge {
    std::array<std::uint32_t, 2> v;
    bool on_boundary;
    bool operator<(const Edge& o) const { return v < o.v; }
  };
  std::vector<Edge> edges(source.num_edges());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto ends = source.edge_vertices(EdgeId(std::uint32_t(e)));
    edges[e].v = {std::min(ends[0].idx(), ends[1].idx()), std::max(ends[0].idx(), ends[1].idx())};
    edges[e].on_boundary = !source.edge_star(EdgeId(std::uint32_t(e)), [](TetId) {});
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::uint8_t> has_interior_neighbour(nv, 0), has_neighbour(nv, 0);
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const auto& e = edges[k].v;
    if (k > 0 && edges[k - 1].v == e) continue;  // a pinched edge: one entry per fan
    bool on_boundary = false;
    for (std::size_t j = k; j < edges.size() && edges[j].v == e; ++j) on_boundary = on_boundary || edges[j].on_boundary;
    has_neighbour[e[0]] = has_neighbour[e[1]] = 1;
    if (!locked[e[1]]) has_interior_neighbour[e[0]] = 1;
    if (!locked[e[0]]) has_interior_neighbour[e[1]] = 1;
    if (!locked[e[0]] || !locked[e[1]] || on_boundary) continue;
    report.chord_edges.push_back(e);
    if (rules.edge_blocks(e[0], e[1])) report.blocking_chord_edges.push_back(e);
  }
  for (std::size_t v = 0; v < nv; ++v)
    if (!locked[v] && has_neighbour[v] && !has_interior_neighbour[v]) report.fixed_link_vertices.push_back(std::uint32_t(v));

  // All-boundary tets with a fixed non-positive image.
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tv = &tets[4 * t];
    if (!(locked[tv[0]] && locked[tv[1]] && locked[tv[2]] && locked[tv[3]])) continue;
    ++report.all_boundary_tets;
    if (orient3d(P(tv[0]), P(tv[1]), P(tv[2]), P(tv[3])) <= 0) report.fixed_nonpositive_tets.push_back(std::uint32_t(t));
  }

  // Interior faces with three boundary vertices, once each (sorted), with the apexes on both sides.
  struct ChordFace {
    std::array<std::uint32_t, 3> key;
    std::uint32_t d, e;
    bool operator<(const ChordFace& o) const { return key < o.key; }
  };
  std::vector<ChordFace> faces;
  for (std::uint32_t h = 0; h < 4 * nt; ++h) {
    const HalfFaceId o = source.half_face_opposite(HalfFaceId(h));
    if (!o.is_valid() || o.idx() < h) continue;
    const auto fv = source.half_face_vertices(HalfFaceId(h));
    std::array<std::uint32_t, 3> k = {fv[0].idx(), fv[1].idx(), fv[2].idx()};
    if (!(locked[k[0]] && locked[k[1]] && locked[k[2]])) continue;
    std::sort(k.begin(), k.end());
    faces.push_back({k, source.half_face_apex(HalfFaceId(h)).idx(), source.half_face_apex(o).idx()});
  }
  std::sort(faces.begin(), faces.end());
  for (const ChordFace& f : faces) {
    const auto& k = f.key;
    report.chord_faces.push_back(k);
    bool blocking = rules.face_image_blocks(k[0], k[1], k[2]);
    if (!blocking && locked[f.d] && locked[f.e]) {
      const int sd = orient3d(P(k[0]), P(k[1]), P(k[2]), P(f.d));
      const int se = orient3d(P(k[0]), P(k[1]), P(k[2]), P(f.e));
      blocking = sd * se >= 0;
    }
    if (blocking) report.blocking_chord_faces.push_back(k);
  }
  return report;
}

}  // namespace volmap
