// feasibility.cpp — exact pre-checks of docs/mapping.md §3 on flat arrays (sorting, no hashing).
#include <volmap/volume/feasibility.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace volmap {

FeasibilityReport analyze_feasibility(const TetMeshData& source, const std::vector<std::uint8_t>& on_boundary,
                                      const std::vector<double>& target_xyz) {
  const std::size_t nv = source.num_vertices(), nt = source.num_tets();
  if (on_boundary.size() != nv || target_xyz.size() != 3 * nv)
    throw Error(ErrorKind::BadInput, "", 0, "feasibility: inconsistent array sizes");
  FeasibilityReport report;
  const double* X = target_xyz.data();
  auto P = [X](std::uint32_t v) { return X + 3 * std::size_t(v); };

  // Domain scale from the boundary images.
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t v = 0; v < nv; ++v)
    if (on_boundary[v])
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], X[3 * v + i]);
        hi[i] = std::max(hi[i], X[3 * v + i]);
      }
  const double scale = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 0.0});
  const double tol = 1e-6 * scale;

  // Boundary faces and, per boundary vertex, its incident boundary triangles (CSR).
  const std::vector<std::uint64_t> bfaces = boundary_half_faces(source);
  std::vector<std::array<std::uint32_t, 3>> btri(bfaces.size());
  for (std::size_t f = 0; f < bfaces.size(); ++f) btri[f] = half_face_vertices(source, bfaces[f]);
  static_assert(sizeof(btri[0]) == 3 * sizeof(std::uint32_t), "triangles are read as 3 ids each");
  report.boundary_volume_sign = enclosed_volume_sign(X, nv, btri.empty() ? nullptr : btri[0].data(), btri.size());
  std::vector<std::uint32_t> tri_offset(nv + 1, 0), tri_list;
  for (const auto& t : btri)
    for (auto v : t) ++tri_offset[v + 1];
  for (std::size_t v = 0; v < nv; ++v) tri_offset[v + 1] += tri_offset[v];
  tri_list.resize(tri_offset[nv]);
  {
    std::vector<std::uint32_t> fill(tri_offset.begin(), tri_offset.end() - 1);
    for (std::size_t f = 0; f < btri.size(); ++f)
      for (auto v : btri[f]) tri_list[fill[v]++] = std::uint32_t(f);
  }
  // Are the points `others` (n of them) within tol of the plane of some boundary triangle at `a`?
  auto in_facet_plane_at = [&](std::uint32_t a, const std::uint32_t* others, int n) {
    for (std::uint32_t k = tri_offset[a]; k < tri_offset[a + 1]; ++k) {
      const auto& t = btri[tri_list[k]];
      const double* p0 = P(t[0]);
      const double* p1 = P(t[1]);
      const double* p2 = P(t[2]);
      double e1[3], e2[3], nrm[3];
      for (int i = 0; i < 3; ++i) {
        e1[i] = p1[i] - p0[i];
        e2[i] = p2[i] - p0[i];
      }
      nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
      nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
      nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
      const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
      if (!(len > 0)) continue;
      bool all = true;
      for (int j = 0; j < n && all; ++j) {
        const double* q = P(others[j]);
        const double d = ((q[0] - p0[0]) * nrm[0] + (q[1] - p0[1]) * nrm[1] + (q[2] - p0[2]) * nrm[2]) / len;
        all = std::abs(d) <= tol;
      }
      if (all) return true;
    }
    return false;
  };

  // Boundary edges (sorted pairs).
  std::vector<std::array<std::uint32_t, 2>> bedges;
  bedges.reserve(3 * btri.size());
  for (const auto& t : btri)
    for (int i = 0; i < 3; ++i) {
      std::uint32_t a = t[i], b = t[(i + 1) % 3];
      if (a > b) std::swap(a, b);
      bedges.push_back({a, b});
    }
  std::sort(bedges.begin(), bedges.end());
  bedges.erase(std::unique(bedges.begin(), bedges.end()), bedges.end());

  // All edges.
  std::vector<std::array<std::uint32_t, 2>> edges;
  edges.reserve(6 * nt);
  static const int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tv = &source.tets[4 * t];
    for (const auto& e : kEdge) {
      std::uint32_t a = tv[e[0]], b = tv[e[1]];
      if (a > b) std::swap(a, b);
      edges.push_back({a, b});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  std::vector<std::uint8_t> has_interior_neighbour(nv, 0), has_neighbour(nv, 0);
  for (const auto& e : edges) {
    has_neighbour[e[0]] = has_neighbour[e[1]] = 1;
    if (!on_boundary[e[1]]) has_interior_neighbour[e[0]] = 1;
    if (!on_boundary[e[0]]) has_interior_neighbour[e[1]] = 1;
    if (!on_boundary[e[0]] || !on_boundary[e[1]]) continue;
    if (std::binary_search(bedges.begin(), bedges.end(), e)) continue;
    report.chord_edges.push_back(e);
    const std::uint32_t other[1] = {e[1]};
    const std::uint32_t other2[1] = {e[0]};
    const bool coincident = points_equal(P(e[0]), P(e[1]));
    if (coincident || in_facet_plane_at(e[0], other, 1) || in_facet_plane_at(e[1], other2, 1))
      report.blocking_chord_edges.push_back(e);
  }
  for (std::size_t v = 0; v < nv; ++v)
    if (!on_boundary[v] && has_neighbour[v] && !has_interior_neighbour[v]) report.fixed_link_vertices.push_back(std::uint32_t(v));

  // All-boundary tets with a fixed non-positive image.
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tv = &source.tets[4 * t];
    if (!(on_boundary[tv[0]] && on_boundary[tv[1]] && on_boundary[tv[2]] && on_boundary[tv[3]])) continue;
    ++report.all_boundary_tets;
    if (orient3d(P(tv[0]), P(tv[1]), P(tv[2]), P(tv[3])) <= 0) report.fixed_nonpositive_tets.push_back(std::uint32_t(t));
  }

  // Interior faces with three boundary vertices: (sorted face, tet, local opposite vertex).
  struct FaceRec {
    std::array<std::uint32_t, 3> key;
    std::uint32_t tet;
    std::uint8_t local;
    bool operator<(const FaceRec& o) const { return std::tie(key, tet) < std::tie(o.key, o.tet); }
  };
  std::vector<FaceRec> faces;
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tv = &source.tets[4 * t];
    for (std::uint8_t i = 0; i < 4; ++i) {
      std::array<std::uint32_t, 3> k = {tv[kTetFace[i][0]], tv[kTetFace[i][1]], tv[kTetFace[i][2]]};
      if (!(on_boundary[k[0]] && on_boundary[k[1]] && on_boundary[k[2]])) continue;
      std::sort(k.begin(), k.end());
      faces.push_back({k, std::uint32_t(t), i});
    }
  }
  std::sort(faces.begin(), faces.end());
  for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
    if (faces[i].key != faces[i + 1].key) continue;
    const auto& k = faces[i].key;
    report.chord_faces.push_back(k);
    bool blocking = collinear(P(k[0]), P(k[1]), P(k[2]));
    if (!blocking) {
      const std::uint32_t others[2] = {k[1], k[2]};
      blocking = in_facet_plane_at(k[0], others, 2);
    }
    if (!blocking) {
      const std::uint32_t d = source.tets[4 * std::size_t(faces[i].tet) + faces[i].local];
      const std::uint32_t e = source.tets[4 * std::size_t(faces[i + 1].tet) + faces[i + 1].local];
      if (on_boundary[d] && on_boundary[e]) {
        const int sd = orient3d(P(k[0]), P(k[1]), P(k[2]), P(d));
        const int se = orient3d(P(k[0]), P(k[1]), P(k[2]), P(e));
        blocking = sd * se >= 0;
      }
    }
    if (blocking) report.blocking_chord_faces.push_back(k);
    ++i;
  }
  return report;
}

}  // namespace volmap
