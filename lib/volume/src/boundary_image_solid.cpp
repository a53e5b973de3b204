// boundary_image_solid.cpp — chords against the solid bounded by the boundary image (conventions in
// boundary_image_solid.hpp).
#include <volmap/volume/boundary_image_solid.hpp>

#include <volmap/check/self_intersection.hpp>
#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <cmath>

namespace volmap {
namespace {

Box3 box_of(std::initializer_list<const double*> points) {
  Box3 b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = 1e300;
    b.hi[k] = -1e300;
  }
  for (const double* p : points)
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = std::min(b.lo[k], p[k]);
      b.hi[k] = std::max(b.hi[k], p[k]);
    }
  return b;
}

bool strictly_same_sign(int x, int y, int z) { return (x > 0 && y > 0 && z > 0) || (x < 0 && y < 0 && z < 0); }
bool weakly_same_sign(int x, int y, int z) {
  return (x >= 0 && y >= 0 && z >= 0) || (x <= 0 && y <= 0 && z <= 0);
}

// Ray directions: close to the axes (thin query boxes) and generic (no small rational slopes);
// ray 2k runs towards +axis k, ray 2k + 1 towards −axis k.
constexpr double kRays[6][3] = {{1, 1.37e-3, 2.71e-3},   {-1, 3.14e-3, -1.41e-3}, {2.23e-3, 1, 1.73e-3},
                                {-2.65e-3, -1, 1.12e-3}, {1.61e-3, -2.45e-3, 1},  {-1.29e-3, 3.33e-3, -1}};

}  // namespace

bool boundary_image_is_embedded(const TetMesh& mesh, const std::vector<double>& target_xyz) {
  std::vector<std::uint32_t> tris;
  for (HalfFaceId h : mesh.boundary_half_faces())
    for (VertexId v : mesh.half_face_vertices(h)) tris.push_back(v.idx());
  return find_self_intersections(target_xyz.data(), target_xyz.size() / 3, tris.data(), tris.size() / 3).clean();
}

BoundaryImageSolid::BoundaryImageSolid(const TetMesh& mesh, const std::vector<double>& target_xyz) : target_(target_xyz) {
  if (target_xyz.size() != 3 * std::size_t(mesh.num_vertex_slots()))
    throw Error(ErrorKind::BadInput, "", 0, "boundary image solid: inconsistent array sizes");
  std::vector<Box3> boxes;
  for (HalfFaceId h : mesh.boundary_half_faces()) {
    const auto f = mesh.half_face_vertices(h);
    const double *a = image(f[0].idx()), *b = image(f[1].idx()), *c = image(f[2].idx());
    if (collinear(a, b, c)) continue;  // no plane (an invalid surface map)
    tris_.push_back({f[0].idx(), f[1].idx(), f[2].idx()});
    boxes.push_back(box_of({a, b, c}));
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n) x /= len;
    planes_.push_back({n[0], n[1], n[2], n[0] * a[0] + n[1] * a[1] + n[2] * a[2]});
  }
  tree_ = build_box_tree(boxes);
  if (!tree_.nodes.empty()) {
    bounds_ = tree_.nodes[0].box;
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (bounds_.hi[k] - bounds_.lo[k]) * (bounds_.hi[k] - bounds_.lo[k]);
    reach_ = 2 * std::sqrt(d2) + 1;
    plane_tolerance_ = 1e-12 * std::sqrt(d2);
  }
}

// Beside: every point strictly on one side of f's plane beyond the tolerance (then nothing meets f).
// A point within the tolerance is an endpoint of a chord (a vertex of the image): the chord could
// meet f there only if that vertex lay on f, which an embedded image with f not at that vertex rules
// out, so the exact tests are spared for it too, unless every point is that close (a chord in f's plane).
bool BoundaryImageSolid::clearly_beside(std::uint32_t f, std::initializer_list<const double*> points) const {
  int above = 0, below = 0, near = 0;
  for (const double* p : points) {
    const double d = plane_distance(f, p);
    if (d > plane_tolerance_) ++above;
    else if (d < -plane_tolerance_) ++below;
    else ++near;
  }
  if (near == int(points.size())) return false;
  return above == 0 || below == 0;
}

std::uint32_t BoundaryImageSolid::touched_triangle(std::uint32_t a, std::uint32_t b) const {
  const double *pa = image(a), *pb = image(b);
  std::uint32_t touched = kNone;
  tree_.for_each_near_segment(pa, pb, plane_tolerance_, [&](std::uint32_t f) {
    if (touched != kNone) return;
    const auto& t = tris_[f];
    for (std::uint32_t v : t)
      if (v == a || v == b) return;
    if (clearly_beside(f, {pa, pb})) return;
    if (segment_intersects_triangle(pa, pb, image(t[0]), image(t[1]), image(t[2]))) touched = f;
  });
  return touched;
}

bool BoundaryImageSolid::triangle_touches_boundary(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  const std::uint32_t face[3] = {a, b, c};
  bool touches = false;
  tree_.for_each_overlapping(box_of({image(a), image(b), image(c)}), [&](std::uint32_t f) {
    if (!touches && !clearly_beside(f, {image(a), image(b), image(c)}))
      touches = triangle_pair_intersects(target_.data(), face, tris_[f].data());
  });
  return touches;
}

int BoundaryImageSolid::ray_crossing(const double* p, const double* q, std::uint32_t f) const {
  const double *x = image(tris_[f][0]), *y = image(tris_[f][1]), *z = image(tris_[f][2]);
  const int sp = orient3d(x, y, z, p), sq = orient3d(x, y, z, q);
  if (sq == 0) return 0;  // q lies beyond every triangle's box, so not on this triangle
  if (sp != 0 && sp == sq) return 0;
  const int o1 = orient3d(p, q, x, y), o2 = orient3d(p, q, y, z), o3 = orient3d(p, q, z, x);
  if (sp == 0) return weakly_same_sign(o1, o2, o3) ? -2 : 0;  // p in the plane: on the triangle or beside it
  if (strictly_same_sign(o1, o2, o3)) return 1;
  return weakly_same_sign(o1, o2, o3) ? -1 : 0;  // through an edge or a corner: ambiguous
}

bool BoundaryImageSolid::contains(const double* p) const {
  for (int k = 0; k < 3; ++k)
    if (!(p[k] >= bounds_.lo[k] && p[k] <= bounds_.hi[k])) return false;
  // The ray towards the nearest side of the bounds first (fewest candidate triangles).
  int order[6] = {0, 1, 2, 3, 4, 5};
  double distance[6];
  for (int r = 0; r < 6; ++r) distance[r] = (r % 2 ? p[r / 2] - bounds_.lo[r / 2] : bounds_.hi[r / 2] - p[r / 2]);
  std::sort(order, order + 6, [&](int x, int y) { return distance[x] < distance[y]; });
  for (int o : order) {
    const double* r = kRays[o];
    const double q[3] = {p[0] + reach_ * r[0], p[1] + reach_ * r[1], p[2] + reach_ * r[2]};
    int crossings = 0;
    bool grazes = false, on_boundary = false;
    tree_.for_each_overlapping(box_of({p, q}), [&](std::uint32_t f) {
      if (grazes || on_boundary) return;
      const int c = ray_crossing(p, q, f);
      if (c == 1) ++crossings;
      grazes = c == -1;
      on_boundary = c == -2;
    });
    if (on_boundary) return false;
    if (!grazes) return crossings % 2 == 1;
  }
  return false;
}

bool BoundaryImageSolid::segment_leaves(std::uint32_t a, std::uint32_t b) const {
  if (segment_touches_boundary(a, b)) return true;
  const double *pa = image(a), *pb = image(b);
  const double mid[3] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2])};
  return !contains(mid);
}

}  // namespace volmap
