// Sphere maps (see surface_map.hpp; volmap-reference.md §4.3). A sphere map is judged like every
// map (§5): every image triangle must form a positive cone with the centroid k of the image points.
// The central projection of a star-shaped map keeps every cone positive about the sphere's centre c,
// but a thin triangle whose three points lie close to one great circle has its plane close to c,
// and k != c can lie on its wrong side. Such maps are balanced, in rounds until every cone is
// positive about k:
//  - fattening: each point of a cone that is not positive about k moves (within half its shortest
//    edge, on the sphere) to where the smallest distance from c and from k to its cones' planes is
//    largest (a 3-variable LP, small_lp.hpp), when every cone around it stays positive about c (exact);
//  - relaxation: each point moves to the projected mean of its neighbours when every cone around it
//    stays positive about c (exact), which fattens slivers and evens the density;
//  - re-centring: a projective automorphism of the ball (a hyperbolic translation in the Klein
//    model) maps a point q of the image's kernel to c; planes stay planes and points keep their side
//    of them, so the cones stay positive about c, while the points crowded around q's direction
//    spread out and k moves towards c.
// Every accepted step is verified exactly; the result is re-checked with check_surface_map.
// When balancing stalls (no fewer bad points in kStallSweeps rounds), the triangles still bad are
// large ones whose planes pass near c: the longest edge of each is split (in the source tets and at
// the midpoint of its image on the flat star-shaped map) and the map is projected and balanced
// again. The star-shaped maps tried: the cube map, then, when it adds more than 1 % to the tets or
// does not balance, the map onto a regular tetrahedron (4 nodes and 6 arcs: a coarse surface needs
// the fewest splits).
#include <volmap/core/error.hpp>
#include <volmap/core/small_lp.hpp>
#include <volmap/predicates.hpp>
#include <volmap/surface/surface_map.hpp>

#include "split_replay.hpp"
#include "working_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace volmap {
namespace {

using namespace surface_detail;

[[noreturn]] void fail(const std::string& reason) { throw Error(ErrorKind::Failed, "", 0, reason); }

// Balancing rounds before giving up (each: fatten the points of bad cones, maybe re-centre, one
// relaxation sweep), and how often the image is re-centred.
constexpr int kMaxSweeps = 2000;
constexpr int kSweepsPerRecentre = 5;
// Balancing has stalled when the number of points of bad triangles has not reached a new minimum
// for this many rounds; map_surface_to_sphere then splits the stuck triangles and balances again,
// within kMaxSweepsRefining rounds in all.
constexpr int kStallSweeps = 400;
constexpr int kMaxSweepsRefining = 2 * kMaxSweeps;

// max t subject to s[j] + a[j]*x + b[j]*y >= t for every j and |x|, |y| <= box, by the dense simplex
// of small_lp.hpp in shifted variables X = x + box, Y = y + box, T = t + t0 >= 0 (the origin feasible
// for t0 = max_j (|a[j]| + |b[j]|) box - s[j], at least 0). Returns {x, y, t}; staying put
// ({0, 0, min_j s[j]}) when the LP fails. Only ranks a move that is then verified exactly.
std::array<double, 3> max_min_margin(const std::vector<std::array<double, 3>>& rows, double box) {
  std::array<double, 3> stay{0, 0, std::numeric_limits<double>::infinity()};
  for (const auto& r : rows) stay[2] = std::min(stay[2], r[0]);
  if (rows.empty() || !(box > 0)) return stay;
  double t0 = 0, reach = 0;
  for (const auto& r : rows) {
    t0 = std::max(t0, (std::fabs(r[1]) + std::fabs(r[2])) * box - r[0]);
    reach = std::max(reach, std::fabs(r[0]) + (std::fabs(r[1]) + std::fabs(r[2])) * box);
  }
  // t - a x - b y <= s  <=>  -a X - b Y + T <= s + t0 - (a + b) box  (right side >= 0 by t0).
  std::vector<double> A, b;
  for (const auto& r : rows) {
    A.insert(A.end(), {-r[1], -r[2], 1.0});
    b.push_back(std::max(0.0, r[0] + t0 - (r[1] + r[2]) * box));
  }
  A.insert(A.end(), {1, 0, 0, 0, 1, 0, 0, 0, 1});
  b.insert(b.end(), {2 * box, 2 * box, t0 + reach});
  double z[3];
  if (!simplex_max(int(b.size()), 3, A, b, {0, 0, 1}, z)) return stay;
  const std::array<double, 3> opt{z[0] - box, z[1] - box, z[2] - t0};
  return opt[2] > stay[2] ? opt : stay;
}

// The image on the sphere as an OpenMesh surface: the boundary of the map's mesh with the image
// points as its points (vertex index order = vid order).
class SphereImage {
 public:
  SphereImage(const TetMeshData& mesh, const BoundaryMap& map, const Point3& centre, double radius);
  void write_back(BoundaryMap& map) const;

  // All cones strictly positive about q (exact).
  bool valid_about(const double* q) const;
  Point3 centroid() const;
  // Moves every point to c + R (x - c) / |x - c|.
  void project();
  // Nudges the points of cones that rounding left non-positive about c by a few ulps.
  void repair_about_centre();
  // One Gauss-Seidel relaxation sweep guarded by positivity about c.
  void relax();
  // Re-centres on the point of the segment c -> k (k = centroid) nearest k inside the kernel.
  void recentre();
  // The points of the triangles that are not positive about k.
  std::vector<VertexHandle> points_of_bad_triangles(const double* k) const;
  // The triangles that are not positive about k, in the map's vertex ids.
  std::vector<std::array<std::uint32_t, 3>> bad_triangles(const double* k) const;
  // Moves v, within half its shortest edge, to where the smallest distance of its cones' planes
  // (through c and through k) is largest; kept only when every cone around it stays positive about
  // c (exact) and that smallest distance grew.
  void fatten(VertexHandle v, const double* k);

 private:
  BoundarySurface s_;
  Point3 c_;
  double radius_;

  double* at(VertexHandle v) { return s_.mesh.point(v).data(); }
  const double* at(VertexHandle v) const { return s_.mesh.point(v).data(); }
  bool positive(FaceHandle f, const double* q) const {
    const auto t = face_vertices(s_.mesh, f);
    return orient3d(at(t[0]), at(t[1]), at(t[2]), q) > 0;
  }
  bool positive_around(VertexHandle v) const;
  double smallest_margin(VertexHandle v, const double* k) const;
  void put_on_sphere(const double* d, double* out) const;
};

SphereImage::SphereImage(const TetMeshData& mesh, const BoundaryMap& map, const Point3& centre, double radius)
    : s_(SourceTetMesh(mesh).boundary_surface()), c_(centre), radius_(radius) {
  if (!s_.complete()) fail("the boundary surface of the map's mesh is not manifold");
  std::vector<std::int32_t> slot(mesh.num_vertices(), -1);
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map.vids[i] < slot.size()) slot[map.vids[i]] = static_cast<std::int32_t>(i);
  for (auto v : s_.mesh.vertices()) {
    const std::int32_t i = slot[s_.tet_vertex_of(v)];
    if (i < 0) fail("the map misses boundary vertex " + std::to_string(s_.tet_vertex_of(v)));
    s_.mesh.set_point(v, SurfaceMesh::Point(map.xyz[3 * i], map.xyz[3 * i + 1], map.xyz[3 * i + 2]));
  }
}

void SphereImage::write_back(BoundaryMap& map) const {
  std::vector<std::int32_t> slot(s_.surface_vertex.size(), -1);
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map.vids[i] < slot.size()) slot[map.vids[i]] = static_cast<std::int32_t>(i);
  for (auto v : s_.mesh.vertices()) {
    const std::int32_t i = slot[s_.tet_vertex_of(v)];
    for (int k = 0; k < 3; ++k) map.xyz[3 * i + k] = at(v)[k];
  }
}

bool SphereImage::valid_about(const double* q) const {
  for (auto f : s_.mesh.faces())
    if (!positive(f, q)) return false;
  return true;
}

bool SphereImage::positive_around(VertexHandle v) const {
  for (auto f : s_.mesh.vf_range(v))
    if (!positive(f, c_.data())) return false;
  return true;
}

Point3 SphereImage::centroid() const {  // the check's kernel (vertex index order = vid order)
  return compensated_centroid(s_.mesh.n_vertices(), [&](std::size_t i) { return at(VertexHandle(static_cast<int>(i))); });
}

void SphereImage::put_on_sphere(const double* d, double* out) const {
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int k = 0; k < 3; ++k) out[k] = c_[k] + radius_ * (d[k] / n);
}

void SphereImage::project() {
  for (auto v : s_.mesh.vertices()) {
    double* p = at(v);
    const double d[3] = {p[0] - c_[0], p[1] - c_[1], p[2] - c_[2]};
    if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0)) fail("a map point coincides with the sphere centre");
    put_on_sphere(d, p);
  }
}

void SphereImage::repair_about_centre() {
  for (auto f : s_.mesh.faces()) {
    if (positive(f, c_.data())) continue;
    for (auto v : face_vertices(s_.mesh, f)) {
      double* p = at(v);
      const Point3 orig{p[0], p[1], p[2]};
      bool fixed = positive_around(v);
      for (int step = 1; step <= 4 && !fixed; ++step)
        for (int dx = -1; dx <= 1 && !fixed; ++dx)
          for (int dy = -1; dy <= 1 && !fixed; ++dy)
            for (int dz = -1; dz <= 1 && !fixed; ++dz) {
              const int dir[3] = {dx, dy, dz};
              for (int k = 0; k < 3; ++k) {
                p[k] = orig[k];
                for (int r = 0; r < step; ++r)
                  if (dir[k]) p[k] = std::nextafter(p[k], dir[k] > 0 ? 1e300 : -1e300);
              }
              fixed = positive_around(v);
            }
      if (fixed) break;
      for (int k = 0; k < 3; ++k) p[k] = orig[k];
    }
  }
}

void SphereImage::relax() {
  for (auto v : s_.mesh.vertices()) {
    double mean[3] = {0, 0, 0};
    for (auto w : s_.mesh.vv_range(v))
      for (int j = 0; j < 3; ++j) mean[j] += at(w)[j] - c_[j];
    const double mn = std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
    if (!(mn > 0)) continue;
    double* p = at(v);
    const Point3 old{p[0], p[1], p[2]};
    // The full step, else a half and a quarter step (between the two directions), else none.
    for (double t = 1; t >= 0.25; t *= 0.5) {
      double d[3];
      for (int j = 0; j < 3; ++j) d[j] = (1 - t) * (old[j] - c_[j]) / radius_ + t * mean[j] / mn;
      if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 1e-12)) continue;
      put_on_sphere(d, p);
      if (positive_around(v)) break;
      for (int j = 0; j < 3; ++j) p[j] = old[j];
    }
  }
}

void SphereImage::recentre() {
  const Point3 k = centroid();
  // Unit-ball coordinates: a = (q - c) / R for the chosen q.
  double a[3] = {(k[0] - c_[0]) / radius_, (k[1] - c_[1]) / radius_, (k[2] - c_[2]) / radius_};
  for (int halving = 0;; ++halving) {
    if (halving == 20) return;
    const Point3 q{c_[0] + radius_ * a[0], c_[1] + radius_ * a[1], c_[2] + radius_ * a[2]};
    if (valid_about(q.data())) break;
    for (auto& x : a) x *= 0.5;
  }
  const double a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  if (!(a2 > 0) || !(a2 < 1)) return;
  // Klein-model translation taking a to 0: y -> (y_par - a + sqrt(1 - |a|^2) y_perp) / (1 - a.y),
  // with y_par the component of y along a. It maps the unit sphere onto itself and planes to planes.
  const double s = std::sqrt(1 - a2);
  std::vector<SurfaceMesh::Point> before(s_.mesh.points(), s_.mesh.points() + s_.mesh.n_vertices());
  for (auto v : s_.mesh.vertices()) {
    double* p = at(v);
    const double y[3] = {(p[0] - c_[0]) / radius_, (p[1] - c_[1]) / radius_, (p[2] - c_[2]) / radius_};
    const double ay = a[0] * y[0] + a[1] * y[1] + a[2] * y[2];
    const double par = ay / a2;  // y_par = par * a
    double z[3];
    for (int j = 0; j < 3; ++j) z[j] = (par * a[j] - a[j] + s * (y[j] - par * a[j])) / (1 - ay);
    put_on_sphere(z, p);
  }
  if (!valid_about(c_.data()))  // rounding broke a cone: keep the previous image
    for (auto v : s_.mesh.vertices()) s_.mesh.set_point(v, before[static_cast<std::size_t>(v.idx())]);
}

std::vector<VertexHandle> SphereImage::points_of_bad_triangles(const double* k) const {
  std::vector<VertexHandle> out;
  for (auto f : s_.mesh.faces())
    if (!positive(f, k))
      for (auto v : face_vertices(s_.mesh, f)) out.push_back(v);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<std::array<std::uint32_t, 3>> SphereImage::bad_triangles(const double* k) const {
  std::vector<std::array<std::uint32_t, 3>> out;
  for (auto f : s_.mesh.faces())
    if (!positive(f, k)) {
      const auto t = face_vertices(s_.mesh, f);
      out.push_back({s_.tet_vertex_of(t[0]), s_.tet_vertex_of(t[1]), s_.tet_vertex_of(t[2])});
    }
  return out;
}

// The cone planes around v: for each face (v, x, y) and q in {c, k}, the plane through q, x, y with
// its unit normal N = (x - q) x (y - q) / |.|; v's cone is positive about q iff (v - q).N > 0.
template <class F>
void for_each_cone_plane(const SurfaceMesh& m, VertexHandle v, const double* c, const double* k, F&& f) {
  for (auto fh : m.vf_range(v)) {
    const auto t = face_vertices(m, fh);
    const int at_v = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const double* x = m.point(t[(at_v + 1) % 3]).data();
    const double* y = m.point(t[(at_v + 2) % 3]).data();
    for (const double* q : {c, k}) {
      const double u[3] = {x[0] - q[0], x[1] - q[1], x[2] - q[2]}, w[3] = {y[0] - q[0], y[1] - q[1], y[2] - q[2]};
      double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (nn > 0)
        for (auto& z : n) z /= nn;
      f(q, n, nn > 0, x);
    }
  }
}

// Smallest signed distance from c and from k to the cone planes around v (> 0 on the positive
// side), in doubles: a ranking, the exact predicate decides validity.
double SphereImage::smallest_margin(VertexHandle v, const double* k) const {
  const double* p = at(v);
  double best = std::numeric_limits<double>::infinity();
  for_each_cone_plane(s_.mesh, v, c_.data(), k, [&](const double* q, const double* n, bool ok, const double*) {
    best = std::min(best, ok ? (p[0] - q[0]) * n[0] + (p[1] - q[1]) * n[1] + (p[2] - q[2]) * n[2] : -1.0);
  });
  return best;
}

void SphereImage::fatten(VertexHandle v, const double* k) {
  double* p = at(v);
  const Point3 old{p[0], p[1], p[2]};
  // Tangent frame at v.
  const double r[3] = {(p[0] - c_[0]) / radius_, (p[1] - c_[1]) / radius_, (p[2] - c_[2]) / radius_};
  const double axis[3] = {std::fabs(r[0]) < 0.6 ? 1.0 : 0.0, std::fabs(r[0]) < 0.6 ? 0.0 : 1.0, 0.0};
  double e1[3] = {r[1] * axis[2] - r[2] * axis[1], r[2] * axis[0] - r[0] * axis[2], r[0] * axis[1] - r[1] * axis[0]};
  const double n1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (auto& x : e1) x /= n1;
  const double e2[3] = {r[1] * e1[2] - r[2] * e1[1], r[2] * e1[0] - r[0] * e1[2], r[0] * e1[1] - r[1] * e1[0]};
  // One row per cone plane: margin (v - q).N + x e1.N + y e2.N.
  std::vector<std::array<double, 3>> rows;
  bool degenerate = false;
  double shortest = std::numeric_limits<double>::infinity();
  for_each_cone_plane(s_.mesh, v, c_.data(), k, [&](const double* q, const double* n, bool ok, const double* x) {
    degenerate |= !ok;
    rows.push_back({(p[0] - q[0]) * n[0] + (p[1] - q[1]) * n[1] + (p[2] - q[2]) * n[2],
                    e1[0] * n[0] + e1[1] * n[1] + e1[2] * n[2], e2[0] * n[0] + e2[1] * n[1] + e2[2] * n[2]});
    const double dx = x[0] - p[0], dy = x[1] - p[1], dz = x[2] - p[2];
    shortest = std::min(shortest, std::sqrt(dx * dx + dy * dy + dz * dz));
  });
  if (degenerate) return;
  const double before = smallest_margin(v, k);
  const auto opt = max_min_margin(rows, 0.5 * shortest);
  if (!(opt[2] > before)) return;
  const double d[3] = {old[0] - c_[0] + opt[0] * e1[0] + opt[1] * e2[0], old[1] - c_[1] + opt[0] * e1[1] + opt[1] * e2[1],
                       old[2] - c_[2] + opt[0] * e1[2] + opt[1] * e2[2]};
  put_on_sphere(d, p);
  if (!positive_around(v) || !(smallest_margin(v, k) > before))
    for (int j = 0; j < 3; ++j) p[j] = old[j];
}

}  // namespace

namespace {

// Projects and balances `in`; returns the sphere map, or nothing with `stuck` holding the triangles
// still inverted about the centroid when balancing stalls (no new minimum of bad points in
// `stall_sweeps` rounds) or runs out of rounds. `sweeps`: in, at most this many rounds; out, the
// rounds used.
std::optional<SurfaceMapResult> balanced_projection(const SurfaceMapResult& in, const Point3& centre, double radius,
                                                    std::vector<std::array<std::uint32_t, 3>>& stuck, int& sweeps,
                                                    int stall_sweeps) {
  const int budget = sweeps;
  SurfaceMapResult out = in;
  SphereImage image(out.mesh, out.map, centre, radius);
  image.project();
  image.repair_about_centre();
  if (!image.valid_about(centre.data()))
    fail("the projected sphere map has cones that are not positive about the centre");
  std::size_t fewest = std::numeric_limits<std::size_t>::max();
  for (int sweep = 0, last_new_minimum = 0;; ++sweep) {
    sweeps = sweep;
    const Point3 k = image.centroid();
    const std::vector<VertexHandle> bad = image.points_of_bad_triangles(k.data());
    if (bad.empty()) break;
    if (bad.size() < fewest) {
      fewest = bad.size();
      last_new_minimum = sweep;
    }
    if (sweep >= budget || sweep - last_new_minimum >= stall_sweeps) {
      stuck = image.bad_triangles(k.data());
      return std::nullopt;
    }
    for (auto v : bad) image.fatten(v, k.data());
    if (sweep % kSweepsPerRecentre == 0) image.recentre();
    image.relax();
  }
  image.write_back(out.map);
  SurfaceMapCheckOptions opt;
  opt.sphere_radius = radius;
  opt.sphere_centre = centre;
  out.check = check_surface_map(out.mesh, out.map, nullptr, opt);
  if (!out.check.ok) fail("the sphere map fails the exact check: " + out.check.reason);
  return out;
}

// `in` with the longest edge (on the star-shaped image) of every `stuck` triangle split at its
// midpoint, in the source and in the image (the midpoint of a segment in a flat face stays in it).
// New vertices are appended in split order; every new tet is checked exactly (SourceTetMesh).
SurfaceMapResult split_longest_edges(const SurfaceMapResult& in, const std::vector<std::array<std::uint32_t, 3>>& stuck) {
  std::vector<std::int32_t> slot(in.mesh.num_vertices(), -1);
  for (std::size_t i = 0; i < in.map.size(); ++i) slot[in.map.vids[i]] = static_cast<std::int32_t>(i);
  auto image = [&](std::uint32_t v) { return &in.map.xyz[3 * static_cast<std::size_t>(slot[v])]; };
  auto length2 = [&](std::uint32_t a, std::uint32_t b) {
    double l = 0;
    for (int k = 0; k < 3; ++k) l += (image(a)[k] - image(b)[k]) * (image(a)[k] - image(b)[k]);
    return l;
  };
  std::vector<std::array<std::uint32_t, 2>> edges;
  for (const auto& t : stuck) {
    int longest = 0;
    for (int i = 1; i < 3; ++i)
      if (length2(t[i], t[(i + 1) % 3]) > length2(t[longest], t[(longest + 1) % 3])) longest = i;
    edges.push_back({std::min(t[longest], t[(longest + 1) % 3]), std::max(t[longest], t[(longest + 1) % 3])});
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  SurfaceMapResult out = in;
  std::vector<EdgeSplit> splits;
  const auto first_new = static_cast<std::uint32_t>(in.mesh.num_vertices());
  for (const auto& e : edges) {
    EdgeSplit sp{e[0], e[1], first_new + static_cast<std::uint32_t>(splits.size()), {}};
    for (int k = 0; k < 3; ++k) {
      sp.p[k] = 0.5 * (in.mesh.xyz[3 * e[0] + k] + in.mesh.xyz[3 * e[1] + k]);
      out.map.xyz.push_back(0.5 * (image(e[0])[k] + image(e[1])[k]));
    }
    out.map.vids.push_back(sp.m);
    splits.push_back(sp);
  }
  if (!out.map.source_lines.empty()) out.map.source_lines.resize(out.map.size(), 0);
  SourceTetMesh source(in.mesh);
  out.mesh = source.refine(splits).mesh;
  out.added_vertices += splits.size();
  return out;
}

// Projects `star_shaped` and balances it; when balancing stalls, splits the stuck triangles' longest
// edges and balances again, within kMaxSweepsRefining rounds in all.
SurfaceMapResult project_refining(SurfaceMapResult star_shaped, const Point3& centre, double radius) {
  std::vector<std::array<std::uint32_t, 3>> stuck;
  std::size_t splits = 0;
  for (int left = kMaxSweepsRefining;;) {
    int sweeps = left;
    if (auto r = balanced_projection(star_shaped, centre, radius, stuck, sweeps, kStallSweeps)) {
      if (splits) r->attempt += ", " + std::to_string(splits) + " balancing splits";
      return *std::move(r);
    }
    left -= std::max(sweeps, 1);
    if (left <= 0)
      fail("the sphere map stays inverted about the centroid of its points (" + std::to_string(stuck.size()) +
           " triangles) after " + std::to_string(kMaxSweepsRefining) + " rounds of balancing and " +
           std::to_string(splits) + " splits");
    const std::size_t before = star_shaped.added_vertices;
    star_shaped = split_longest_edges(star_shaped, stuck);
    splits += star_shaped.added_vertices - before;
  }
}

}  // namespace

SurfaceMapResult project_to_sphere(const SurfaceMapResult& in, const Point3& centre, double radius) {
  std::vector<std::array<std::uint32_t, 3>> stuck;
  int sweeps = kMaxSweeps;
  if (auto r = balanced_projection(in, centre, radius, stuck, sweeps, kMaxSweeps)) return *std::move(r);
  fail("the sphere map stays inverted about the centroid of its points (" + std::to_string(stuck.size()) +
       " triangles) after " + std::to_string(kMaxSweeps) + " balancing rounds");
}

namespace {

// The regular tetrahedron on the alternate corners 0, 2, 5, 7 of the cube [0,100]³ (probes: the
// same corners of the input's bounding box), centred on the cube's centre like the cube itself: the
// star-shaped map with the fewest nodes and arcs, so the fewest splits on a coarse surface.
const Domain& sphere_tetrahedron() {
  static const Domain d = parse_custom_domain(
      "n 0\nn 2\nn 5\nn 7\n"
      "nm 0 0 0\nnm 100 0 100\nnm 0 100 100\nnm 100 100 0\n"
      "a 0 1\na 0 2\na 0 3\na 1 2\na 1 3\na 2 3\n",
      "the sphere map's regular tetrahedron");
  return d;
}

}  // namespace

SurfaceMapResult map_surface_to_sphere(const TetMeshData& mesh, const Point3& centre, double radius,
                                       const SurfaceMapOptions& options) {
  const Domain cube = builtin_domain("cube");
  std::string lean_failure;
  if (!options.reference_chord_splits) {
    std::optional<SurfaceMapResult> best;
    auto project = [&](const Domain& domain, const char* label) {
      try {
        SurfaceMapResult r = project_refining(map_surface_to_domain(mesh, domain, options), centre, radius);
        r.attempt = std::string(label) + ", " + r.attempt;
        if (!best || r.mesh.num_tets() < best->mesh.num_tets()) best = std::move(r);
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::Failed) throw;
        lean_failure += (lean_failure.empty() ? "" : "; ") + std::string(label) + ": " + e.reason();
      }
    };
    project(cube, "cube map");
    if (best && adds_at_most(*best, mesh.num_tets(), kPlacementSearchGrowth)) return *std::move(best);
    project(sphere_tetrahedron(), "regular tetrahedron map");
    if (best) return *std::move(best);
  }
  SurfaceMapOptions reference = options;
  reference.reference_chord_splits = true;
  try {
    return project_to_sphere(map_surface_to_domain(mesh, cube, reference), centre, radius);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Failed || lean_failure.empty()) throw;
    throw Error(ErrorKind::Failed, "", 0, lean_failure + "; cube map with the reference's chord splits: " + e.reason());
  }
}

}  // namespace volmap
