// radial_start.cpp — the radial start of radial_start.hpp (docs/mapping.md §2 "Radial start").
// A free vertex's Tutte point u (in the sphere picture, centre at the origin) is located in the cone
// of the boundary triangle whose cone coordinates (u = α ŝa + β ŝb + γ ŝc) are all >= 0, by a walk
// over the boundary triangles from the triangle of the previous vertex: the walk leaves a triangle
// across the edge opposite its most negative coordinate. A walk that does not arrive within its step
// limit falls back to the triangle with the largest smallest coordinate over all triangles.
#include <volmap/volume/radial_start.hpp>

#include <volmap/predicates.hpp>
#include <volmap/volume/kernel_lp.hpp>
#include <volmap/volume/tutte3d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace volmap {

namespace {

// A reflex bend below this (about half a degree) does not count: VOLMAP's own G1 maps, written with
// 6 decimals, bend the tet and pyramid faces by up to 0.002, and our maps onto slanted domain faces
// sit a few ulps off the planes. The star domain's reflex edges bend by tens of degrees.
constexpr double kReflexTolerance = 1e-2;

double det3(const double* a, const double* b, const double* c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// The boundary surface as triangles of vertex ids (outward order) with their neighbours across the
// edge opposite each corner.
struct BoundaryTriangles {
  std::vector<std::array<std::uint32_t, 3>> tri;
  std::vector<std::array<std::uint32_t, 3>> across;  // across[f][i]: the triangle across the edge opposite corner i

  explicit BoundaryTriangles(const TetMesh& mesh) {
    for (HalfFaceId h : mesh.boundary_half_faces()) {
      const auto v = mesh.half_face_vertices(h);
      tri.push_back({v[0].idx(), v[1].idx(), v[2].idx()});
    }
    // Each edge (a,b), a < b, with its triangle and corner; the two uses of a manifold edge sort together.
    std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> edges;
    edges.reserve(3 * tri.size());
    for (std::uint32_t f = 0; f < tri.size(); ++f)
      for (std::uint32_t i = 0; i < 3; ++i) {
        const std::uint32_t a = tri[f][(i + 1) % 3], b = tri[f][(i + 2) % 3];
        edges.emplace_back(std::min(a, b), std::max(a, b), 3 * f + i);
      }
    std::sort(edges.begin(), edges.end());
    across.assign(tri.size(), {kInvalidIndex, kInvalidIndex, kInvalidIndex});
    for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
      if (std::get<0>(edges[k]) != std::get<0>(edges[k + 1]) || std::get<1>(edges[k]) != std::get<1>(edges[k + 1])) continue;
      const std::uint32_t p = std::get<2>(edges[k]), q = std::get<2>(edges[k + 1]);
      across[p / 3][p % 3] = q / 3;
      across[q / 3][q % 3] = p / 3;
      ++k;
    }
  }
};

// Cone coordinates of u in triangle f of the sphere picture s; false when the cone is degenerate.
bool cone_coordinates(const BoundaryTriangles& b, const std::vector<double>& s, std::uint32_t f, const double* u, double* w) {
  const double* a = &s[3 * std::size_t(b.tri[f][0])];
  const double* bb = &s[3 * std::size_t(b.tri[f][1])];
  const double* c = &s[3 * std::size_t(b.tri[f][2])];
  const double d = det3(a, bb, c);
  if (!(std::abs(d) > 0)) return false;
  w[0] = det3(u, bb, c) / d;
  w[1] = det3(a, u, c) / d;
  w[2] = det3(a, bb, u) / d;
  return std::isfinite(w[0]) && std::isfinite(w[1]) && std::isfinite(w[2]);
}

// The triangle whose cone holds u (coordinates in w), walking from `start`.
std::uint32_t locate(const BoundaryTriangles& b, const std::vector<double>& s, std::uint32_t start, const double* u, double* w,
                     std::size_t max_steps, bool* searched) {
  *searched = false;
  std::uint32_t f = start;
  for (std::size_t step = 0; step < max_steps && f != kInvalidIndex; ++step) {
    if (!cone_coordinates(b, s, f, u, w)) break;
    const int worst = int(std::min_element(w, w + 3) - w);
    if (w[worst] >= 0) return f;
    f = b.across[f][worst];
  }
  *searched = true;
  std::uint32_t best = 0;
  double best_min = -std::numeric_limits<double>::infinity();
  double bw[3] = {0, 0, 0};
  for (std::uint32_t g = 0; g < b.tri.size(); ++g) {
    double gw[3];
    if (!cone_coordinates(b, s, g, u, gw)) continue;
    const double m = std::min({gw[0], gw[1], gw[2]});
    if (m > best_min) {
      best_min = m;
      best = g;
      std::copy(gw, gw + 3, bw);
    }
  }
  std::copy(bw, bw + 3, w);
  return best;
}

bool locked_are_the_boundary(const TetMesh& mesh, const std::vector<std::uint8_t>& locked) {
  if (locked.size() != mesh.num_vertices()) return false;
  for (std::uint32_t v = 0; v < mesh.num_vertices(); ++v)
    if ((locked[v] != 0) != mesh.vertex_is_boundary(VertexId(v))) return false;
  return true;
}

}  // namespace

bool boundary_image_is_convex(const TetMesh& mesh, const std::vector<double>& x) {
  const BoundaryTriangles surface(mesh);
  auto at = [&](std::uint32_t v) { return &x[3 * std::size_t(v)]; };
  for (std::uint32_t f = 0; f < surface.tri.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = surface.across[f][i];
      if (g == kInvalidIndex || g < f) continue;  // each shared edge once
      const auto& t = surface.tri[f];
      std::uint32_t far = kInvalidIndex;
      for (std::uint32_t w : surface.tri[g])
        if (w != t[(i + 1) % 3] && w != t[(i + 2) % 3]) far = w;
      if (far == kInvalidIndex) continue;
      // Distance of the far vertex outside t's plane, against the edges' scale.
      const double* a = at(t[0]);
      const double e1[3] = {at(t[1])[0] - a[0], at(t[1])[1] - a[1], at(t[1])[2] - a[2]};
      const double e2[3] = {at(t[2])[0] - a[0], at(t[2])[1] - a[1], at(t[2])[2] - a[2]};
      const double q[3] = {at(far)[0] - a[0], at(far)[1] - a[1], at(far)[2] - a[2]};
      const double n[3] = {e2[1] * e1[2] - e2[2] * e1[1], e2[2] * e1[0] - e2[0] * e1[2], e2[0] * e1[1] - e2[1] * e1[0]};  // inward
      const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double scale = std::sqrt(std::max({e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2], e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2],
                                               q[0] * q[0] + q[1] * q[1] + q[2] * q[2]}));
      if (!(nn > 0)) continue;
      if ((n[0] * q[0] + n[1] * q[1] + n[2] * q[2]) / nn < -kReflexTolerance * scale) return false;
    }
  return true;
}

RadialStartResult place_by_radial_tutte(const TetMesh& mesh, const std::vector<std::uint8_t>& locked, std::vector<double>& x) {
  RadialStartResult r;
  const std::size_t nv = mesh.num_vertices();
  if (x.size() != 3 * nv || !locked_are_the_boundary(mesh, locked)) return r;
  const BoundaryTriangles surface(mesh);
  if (surface.tri.empty()) return r;

  // c: a strict kernel point of the boundary image, exactly verified.
  std::vector<double> triangles;
  triangles.reserve(9 * surface.tri.size());
  for (const auto& t : surface.tri)
    for (std::uint32_t v : t) triangles.insert(triangles.end(), &x[3 * std::size_t(v)], &x[3 * std::size_t(v)] + 3);
  double c[3];
  if (!strict_kernel_point(triangles, c)) return r;
  r.centre = {c[0], c[1], c[2]};

  // The sphere picture: boundary vertices projected from c onto the unit sphere; Tutte inside.
  std::vector<double> s(3 * nv, 0.0);
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (!locked[v]) continue;
    const double d[3] = {x[3 * v] - c[0], x[3 * v + 1] - c[1], x[3 * v + 2] - c[2]};
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);  // > 0: c is strictly inside
    for (int k = 0; k < 3; ++k) s[3 * v + k] = d[k] / n;
  }
  std::vector<double> y = s;
  solve_uniform_laplacian(nv, unique_tet_edges(mesh), locked, y);

  // Back through the cone maps.
  const std::size_t max_steps = 64 + 4 * std::size_t(std::sqrt(double(surface.tri.size())));
  std::uint32_t face = 0;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (locked[v]) continue;
    const double* u = &y[3 * std::size_t(v)];
    if (!(u[0] * u[0] + u[1] * u[1] + u[2] * u[2] > 0)) {
      std::copy(c, c + 3, &x[3 * std::size_t(v)]);
      continue;
    }
    double w[3];
    bool searched = false;
    face = locate(surface, s, face, u, w, max_steps, &searched);
    r.located_by_search += searched;
    for (int k = 0; k < 3; ++k) {
      double p = c[k];
      for (int i = 0; i < 3; ++i) p += w[i] * (x[3 * std::size_t(surface.tri[face][i]) + k] - c[k]);
      x[3 * std::size_t(v) + k] = p;
    }
  }
  r.placed = true;
  return r;
}

}  // namespace volmap
