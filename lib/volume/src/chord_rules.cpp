// chord_rules.cpp — the blocking rules of docs/mapping.md §3 (conventions in chord_rules.hpp).
#include <volmap/volume/chord_rules.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/radial_start.hpp>

#include <algorithm>
#include <cmath>

namespace volmap {

namespace {
std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) { return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b); }
}  // namespace

double tet_shape(const double* p0, const double* p1, const double* p2, const double* p3) {
  const double* p[4] = {p0, p1, p2, p3};
  double e[3][3], l2 = 0;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) e[k][i] = p[k][i] - p[3][i];
  const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b)
      for (int i = 0; i < 3; ++i) l2 += (p[a][i] - p[b][i]) * (p[a][i] - p[b][i]);
  return l2 > 0 ? det / (l2 * std::sqrt(l2)) : 0;
}

ChordRules::ChordRules(const TetMesh& mesh, const std::vector<std::uint8_t>& locked, const std::vector<double>& target_xyz)
    : locked_(locked), target_(target_xyz) {
  const std::size_t nv = mesh.num_vertex_slots();
  if (locked.size() != nv || target_xyz.size() != 3 * nv) throw Error(ErrorKind::BadInput, "", 0, "chord rules: inconsistent array sizes");
  // The tolerance: 1e-6 of the largest extent of the boundary image.
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t v = 0; v < nv; ++v)
    if (locked[v])
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], target_xyz[3 * v + i]);
        hi[i] = std::max(hi[i], target_xyz[3 * v + i]);
      }
  tol_ = 1e-6 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 0.0});
  // The plane of every boundary image triangle, listed at each of its corners.
  const Span<HalfFaceId> bfaces = mesh.boundary_half_faces();
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::array<double, 7>> planes;
  for (HalfFaceId h : bfaces) {
    const auto f = mesh.half_face_vertices(h);
    const double *p0 = image(f[0].idx()), *p1 = image(f[1].idx()), *p2 = image(f[2].idx());
    double e1[3], e2[3];
    for (int i = 0; i < 3; ++i) {
      e1[i] = p1[i] - p0[i];
      e2[i] = p2[i] - p0[i];
    }
    const double n0 = e1[1] * e2[2] - e1[2] * e2[1], n1 = e1[2] * e2[0] - e1[0] * e2[2], n2 = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = std::sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    if (!(len > 0)) continue;
    tris.push_back({f[0].idx(), f[1].idx(), f[2].idx()});
    planes.push_back({p0[0], p0[1], p0[2], n0, n1, n2, len});
  }
  offsets_.assign(nv + 1, 0);
  for (const auto& t : tris)
    for (std::uint32_t v : t) ++offsets_[v + 1];
  for (std::size_t v = 0; v < nv; ++v) offsets_[v + 1] += offsets_[v];
  planes_.resize(offsets_[nv]);
  std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t k = 0; k < tris.size(); ++k)
    for (std::uint32_t v : tris[k]) planes_[fill[v]++] = planes[k];
  if (!boundary_image_is_convex(mesh, target_) && boundary_image_is_embedded(mesh, target_)) {
    solid_ = std::make_unique<BoundaryImageSolid>(mesh, target_);
    for (HalfFaceId h : bfaces) {
      const auto f = mesh.half_face_vertices(h);
      for (int i = 0; i < 3; ++i) boundary_edges_.insert(edge_key(f[i].idx(), f[(i + 1) % 3].idx()));
    }
  }
}

bool ChordRules::in_facet_plane_at(std::uint32_t a, const std::uint32_t* others, int n) const {
  if (a + 1 >= offsets_.size()) return false;
  for (std::uint32_t k = offsets_[a]; k < offsets_[a + 1]; ++k) {
    const auto& pl = planes_[k];
    bool all = true;
    for (int j = 0; j < n && all; ++j) {
      const double* q = image(others[j]);
      const double d = ((q[0] - pl[0]) * pl[3] + (q[1] - pl[1]) * pl[4] + (q[2] - pl[2]) * pl[5]) / pl[6];
      all = std::abs(d) <= tol_;
    }
    if (all) return true;
  }
  return false;
}

bool ChordRules::edge_blocks(std::uint32_t a, std::uint32_t b) const {
  if (!locked(a) || !locked(b)) return false;
  if (points_equal(image(a), image(b)) || in_facet_plane_at(a, &b, 1) || in_facet_plane_at(b, &a, 1)) return true;
  return solid_ && edge_leaves(a, b);
}

bool ChordRules::edge_leaves(std::uint32_t a, std::uint32_t b) const {
  const std::uint64_t key = edge_key(a, b);
  const auto known = edge_leaves_.find(key);
  if (known != edge_leaves_.end()) return known->second;
  const bool leaves = solid_->segment_leaves(a, b);
  edge_leaves_.emplace(key, leaves);
  return leaves;
}

bool ChordRules::face_image_blocks(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  if (!locked(a) || !locked(b) || !locked(c)) return false;
  std::array<std::uint32_t, 3> k = {a, b, c};
  std::sort(k.begin(), k.end());
  if (collinear(image(k[0]), image(k[1]), image(k[2])) || in_facet_plane_at(k[0], &k[1], 2)) return true;
  if (!solid_) return false;
  bool on_boundary = false;  // an edge of the face is an edge of ∂M
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t x = k[i], y = k[(i + 1) % 3];
    if (boundary_edges_.count(edge_key(x, y)))
      on_boundary = true;
    else if (edge_leaves(x, y))
      return true;
  }
  if (solid_->triangle_touches_boundary(k[0], k[1], k[2])) return true;
  if (!on_boundary) return false;  // its boundary lies inside D and the face misses ∂D
  const double *p = image(k[0]), *q = image(k[1]), *r = image(k[2]);
  const double centroid[3] = {(p[0] + q[0] + r[0]) / 3, (p[1] + q[1] + r[1]) / 3, (p[2] + q[2] + r[2]) / 3};
  return !solid_->contains(centroid);
}

bool ChordRules::fixed_tet_nonpositive(const std::array<std::uint32_t, 4>& v) const {
  for (std::uint32_t x : v)
    if (!locked(x)) return false;
  return orient3d(image(v[0]), image(v[1]), image(v[2]), image(v[3])) <= 0;
}

}  // namespace volmap
