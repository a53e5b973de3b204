// Built-in genus-0 shapes. Demo shapes: icosphere + a smooth injective deformation. Radial shapes
// use p(u) = r(u)·u with r > 0 (star-shaped about the origin, hence embedded); the banana bends an
// ellipsoid along a circle of radius larger than its thickness (embedded, not star-shaped).
// Thin-feature shapes (evaluation sets): built piece by piece, each piece a disc or an annulus
// glued along one boundary loop, so the result is a sphere by construction:
//   body + tubes  a cube-sphere (each cube face an N x N grid) projected on an ellipsoid, with
//                 rectangular holes in the grid; a tube (elliptic rings swept along a curve of
//                 piecewise-constant curvature, then a rounded cap) is glued to each hole's loop;
//   revolution    rings of a profile polyline (rho, z) from pole to pole (dumbbell, coin);
//   spiky star    radial r(u) on an icosphere with 12 sharp spikes (star-shaped);
//   calibration   a coarse CAD box: planar pieces triangulated with as few triangles as possible.
// Orientation is consistent by construction and outward (checked by the signed volume); the
// parameters keep tubes apart and their curvature radius above their width, so the surfaces are
// embedded (the tests and volmap-tetrahedralize check self-intersections exactly).
#include <volmap/core/error.hpp>
#include "support/shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <unordered_map>

namespace volmap {
namespace {

using Vec = std::array<double, 3>;

Vec normalized(const Vec& v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

// Unit icosphere: outward CCW triangles.
void icosphere(int subdivisions, std::vector<Vec>& points, std::vector<std::uint32_t>& tris) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
            {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : points) p = normalized(p);
  tris = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
          3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (int s = 0; s < subdivisions; ++s) {
    std::unordered_map<std::uint64_t, std::uint32_t> midpoint;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      const Vec& pa = points[a];
      const Vec& pb = points[b];
      points.push_back(normalized({pa[0] + pb[0], pa[1] + pb[1], pa[2] + pb[2]}));
      const auto id = static_cast<std::uint32_t>(points.size() - 1);
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<std::uint32_t> next;
    next.reserve(tris.size() * 4);
    for (std::size_t f = 0; f < tris.size(); f += 3) {
      const std::uint32_t a = tris[f], b = tris[f + 1], c = tris[f + 2];
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    tris.swap(next);
  }
}

Vec deform(const std::string& name, const Vec& u) {
  const double x = u[0], y = u[1], z = u[2];
  if (name == "ellipsoid") return {1.4 * x, 1.0 * y, 0.75 * z};
  if (name == "bumpy") {
    const double r = 1.0 + 0.12 * std::sin(5 * x) * std::sin(5 * y) * std::sin(5 * z) + 0.08 * std::cos(7 * z);
    return {r * x, r * y, r * z};
  }
  if (name == "peanut") {
    const double r = 0.75 + 0.45 * x * x;  // waist at x = 0, lobes along x
    return {1.3 * r * x, r * y, r * z};
  }
  if (name == "rounded_box") {  // superellipsoid |x|^6+|y|^6+|z|^6 = 1, radial projection
    const double s = std::pow(std::pow(std::abs(x), 6) + std::pow(std::abs(y), 6) + std::pow(std::abs(z), 6), 1.0 / 6);
    return {x / s, 0.8 * y / s, 0.6 * z / s};
  }
  if (name == "spiky") {
    double r = 0.8;
    const Vec tips[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& tip : tips) {
      const double c = u[0] * tip[0] + u[1] * tip[1] + u[2] * tip[2];
      if (c > 0) r += 0.5 * std::pow(c, 8);
    }
    return {r * x, r * y, r * z};
  }
  if (name == "banana") {  // ellipsoid (2.4, 0.55, 0.55) bent around a circle of radius 2.2
    const double ex = 2.4 * x, ey = 0.55 * y, ez = 0.55 * z;
    const double bend_radius = 2.2, angle = ex / bend_radius;
    return {(bend_radius - ey) * std::sin(angle), bend_radius - (bend_radius - ey) * std::cos(angle), ez};
  }
  throw Error(ErrorKind::BadInput, "unknown built-in shape '" + name + "'");
}


// ---------- thin-feature shapes --------------------------------------------------------------

Vec add(const Vec& a, const Vec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec scale(const Vec& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// v rotated by `angle` about the unit axis k (Rodrigues).
Vec rotate(const Vec& v, const Vec& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return add(add(scale(v, c), scale(cross(k, v), s)), scale(k, dot(k, v) * (1 - c)));
}

// A triangle list under construction; quads are split along their first diagonal.
struct Builder {
  std::vector<Vec> points;
  std::vector<std::uint32_t> tris;
  std::uint32_t add_point(const Vec& p) {
    points.push_back(p);
    return static_cast<std::uint32_t>(points.size() - 1);
  }
  void tri(std::uint32_t a, std::uint32_t b, std::uint32_t c) { tris.insert(tris.end(), {a, b, c}); }
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) { tri(a, b, c), tri(a, c, d); }
  // Triangle (a, b, c) turned so that its normal points along n (planar pieces of known normal).
  void tri_facing(std::uint32_t a, std::uint32_t b, std::uint32_t c, const Vec& n) {
    if (dot(cross(sub(points[b], points[a]), sub(points[c], points[a])), n) < 0) std::swap(b, c);
    tri(a, b, c);
  }
  // The band between two rings of equal size: `from` runs along the open boundary so far (its
  // edges from[j] -> from[j+1] are not yet used in that direction), `to` is the next ring.
  void band(const std::vector<std::uint32_t>& from, const std::vector<std::uint32_t>& to) {
    const std::size_t n = from.size();
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t k = (j + 1) % n;
      tri(from[k], from[j], to[j]);
      tri(from[k], to[j], to[k]);
    }
  }
  void fan(const std::vector<std::uint32_t>& ring, std::uint32_t tip) {
    for (std::size_t j = 0; j < ring.size(); ++j) tri(ring[(j + 1) % ring.size()], ring[j], tip);
  }
  SurfaceData surface() const {
    SurfaceData s;
    for (const auto& p : points) s.xyz.insert(s.xyz.end(), p.begin(), p.end());
    s.tris = tris;
    return s;
  }
};

// One arc of a tube's centre line: `length` at constant `curvature`, turning towards the direction
// at angle `towards` in the tube's (e1, e2) frame.
struct Arc {
  double length, curvature, towards;
};

struct Tube {
  int face;                 // cube face 0..5 = +x, -x, +y, -y, +z, -z
  int u0, v0, du, dv;       // hole: grid cells [u0, u0+du) x [v0, v0+dv) of that face
  double half_width;        // final semi-axis along e1 (the face's u direction)
  double half_thickness;    // final semi-axis along e2
  double taper;             // the semi-axes shrink by this fraction from root to tip
  std::vector<Arc> arcs;    // centre line after the root
};

struct BodySpec {
  Vec radii;   // ellipsoid semi-axes
  int grid;    // cells per cube-face side
  double ring_spacing;  // tube rings every ring_spacing x (perimeter / ring size)
  std::vector<Tube> tubes;
};

// Lattice point (i, j) of cube face f (0..grid each way) as a point of [-1, 1]^3, and the face's
// axes: the face normal is sign * e_axis, u runs along e_(axis+1), v along e_(axis+2).
Vec cube_point(int f, int i, int j, int grid) {
  const int axis = f / 2;
  const double sign = f % 2 == 0 ? 1.0 : -1.0;
  Vec c{};
  c[axis] = sign;
  c[(axis + 1) % 3] = 2.0 * i / grid - 1;
  c[(axis + 2) % 3] = 2.0 * j / grid - 1;
  return c;
}

Vec on_ellipsoid(const Vec& cube, const Vec& radii) {
  const Vec u = normalized(cube);
  return {u[0] * radii[0], u[1] * radii[1], u[2] * radii[2]};
}

// The body: every grid cell of every face except the holes' cells, outward (u x v = +normal on
// + faces). Vertices are shared across faces through their lattice coordinates.
std::vector<std::vector<std::uint32_t>> build_body(const BodySpec& spec, Builder& b) {
  const int n = spec.grid;
  std::map<std::array<int, 3>, std::uint32_t> ids;
  auto vertex = [&](int f, int i, int j) {
    const Vec c = cube_point(f, i, j, n);
    const std::array<int, 3> key{static_cast<int>(std::lround((c[0] + 1) * n)), static_cast<int>(std::lround((c[1] + 1) * n)),
                                 static_cast<int>(std::lround((c[2] + 1) * n))};
    auto it = ids.find(key);
    if (it != ids.end()) return it->second;
    const std::uint32_t id = b.add_point(on_ellipsoid(c, spec.radii));
    ids.emplace(key, id);
    return id;
  };
  auto in_hole = [&](int f, int i, int j) {
    for (const auto& t : spec.tubes)
      if (t.face == f && i >= t.u0 && i < t.u0 + t.du && j >= t.v0 && j < t.v0 + t.dv) return true;
    return false;
  };
  for (int f = 0; f < 6; ++f)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        if (in_hole(f, i, j)) continue;
        const std::uint32_t a = vertex(f, i, j), c = vertex(f, i + 1, j), d = vertex(f, i + 1, j + 1), e = vertex(f, i, j + 1);
        if (f % 2 == 0) b.quad(a, c, d, e);
        else b.quad(a, e, d, c);
      }
  // Each hole's loop, in the direction of the body's boundary edges (a -> b with no b -> a).
  std::map<std::uint32_t, std::uint32_t> next;
  {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (std::size_t k = 0; k < b.tris.size(); k += 3)
      for (int e = 0; e < 3; ++e) directed[{b.tris[k + e], b.tris[k + (e + 1) % 3]}] = 1;
    for (const auto& [edge, one] : directed)
      if (!directed.count({edge.second, edge.first})) next[edge.first] = edge.second;
  }
  std::vector<std::vector<std::uint32_t>> loops;
  for (const auto& t : spec.tubes) {
    std::vector<std::uint32_t> loop{vertex(t.face, t.u0, t.v0)};
    while (true) {
      const std::uint32_t v = next.at(loop.back());
      if (v == loop.front()) break;
      loop.push_back(v);
    }
    loops.push_back(loop);
  }
  return loops;
}

// Sweeps a tube from its hole's loop: rings of the loop's size whose semi-axes go from the loop's
// extent to the tube's over the first stretch, then a rounded cap and a tip vertex.
void build_tube(const BodySpec& spec, const Tube& t, const std::vector<std::uint32_t>& loop, Builder& b) {
  const int n = spec.grid;
  // Root frame: T along the ellipsoid normal at the hole's centre, e1 along the face's u axis.
  const Vec centre_cube = cube_point(t.face, 0, 0, n);
  Vec cc = centre_cube;
  const int axis = t.face / 2;
  cc[(axis + 1) % 3] = 2.0 * (t.u0 + 0.5 * t.du) / n - 1;
  cc[(axis + 2) % 3] = 2.0 * (t.v0 + 0.5 * t.dv) / n - 1;
  Vec position = on_ellipsoid(cc, spec.radii);
  const Vec& r = spec.radii;
  Vec tangent = normalized({position[0] / (r[0] * r[0]), position[1] / (r[1] * r[1]), position[2] / (r[2] * r[2])});
  Vec u_axis{};
  u_axis[(axis + 1) % 3] = 1;
  Vec e1 = normalized(sub(u_axis, scale(tangent, dot(u_axis, tangent))));
  Vec e2 = cross(tangent, e1);
  // The loop in that frame: its half extents and each vertex's angle on the unit square.
  double ext1 = 0, ext2 = 0;
  for (auto v : loop) {
    const Vec d = sub(b.points[v], position);
    ext1 = std::max(ext1, std::abs(dot(d, e1)));
    ext2 = std::max(ext2, std::abs(dot(d, e2)));
  }
  std::vector<double> angle;
  for (auto v : loop) {
    const Vec d = sub(b.points[v], position);
    angle.push_back(std::atan2(dot(d, e2) / ext2, dot(d, e1) / ext1));
  }
  const double length = [&] {
    double l = 0;
    for (const auto& a : t.arcs) l += a.length;
    return l;
  }();
  const double kPi = 3.14159265358979323846;
  const double perimeter = kPi * (t.half_width + t.half_thickness);
  const double spacing = spec.ring_spacing * 2 * perimeter / static_cast<double>(loop.size());
  const double root = 2 * std::max(ext1, ext2);  // stretch over which the loop's extent blends in
  auto semi_axes = [&](double s) {
    const double g = std::pow(std::max(0.0, 1 - s / root), 2);
    const double shrink = 1 - t.taper * s / length;
    return std::array<double, 2>{t.half_width * shrink + (ext1 - t.half_width * shrink) * g,
                                 t.half_thickness * shrink + (ext2 - t.half_thickness * shrink) * g};
  };
  auto ring_at = [&](double s, double cap_scale, double cap_offset) {
    const auto ab = semi_axes(s);
    std::vector<std::uint32_t> ring;
    const Vec centre = add(position, scale(tangent, cap_offset));
    for (double phi : angle)
      ring.push_back(b.add_point(add(centre, add(scale(e1, cap_scale * ab[0] * std::cos(phi)),
                                                 scale(e2, cap_scale * ab[1] * std::sin(phi))))));
    return ring;
  };
  std::vector<std::uint32_t> previous = loop;
  // March along the arcs in small steps, laying a ring every `spacing` of arc length.
  const double step = std::min(spacing, 0.25 / std::max(1e-9, [&] {
                                 double k = 0;
                                 for (const auto& a : t.arcs) k = std::max(k, a.curvature);
                                 return k;
                               }())) / 8;
  double s = 0, next_ring = spacing;
  for (const auto& arc : t.arcs) {
    const Vec bend = add(scale(e1, std::cos(arc.towards)), scale(e2, std::sin(arc.towards)));
    const Vec pivot = normalized(cross(tangent, bend));
    for (double done = 0; done < arc.length - 1e-12;) {
      const double ds = std::min(step, arc.length - done);
      position = add(position, scale(tangent, ds));
      if (arc.curvature > 0) {
        tangent = normalized(rotate(tangent, pivot, arc.curvature * ds));
        e1 = normalized(rotate(e1, pivot, arc.curvature * ds));
        e2 = cross(tangent, e1);
      }
      done += ds;
      s += ds;
      if (s >= next_ring - 1e-12) {
        const auto ring = ring_at(s, 1, 0);
        b.band(previous, ring);
        previous = ring;
        next_ring += spacing;
      }
    }
  }
  // Cap: two shrinking rings on a half ellipsoid, then the tip.
  const auto ab = semi_axes(length);
  const double cap = std::min(ab[0], ab[1]) * 0.5 + 0.5 * std::max(ab[0], ab[1]) * 0.2;
  for (double theta : {kPi / 6, kPi / 3}) {
    const auto ring = ring_at(length, std::cos(theta), cap * std::sin(theta));
    b.band(previous, ring);
    previous = ring;
  }
  b.fan(previous, b.add_point(add(position, scale(tangent, cap))));
}

SurfaceData body_with_tubes(const BodySpec& spec) {
  Builder b;
  const auto loops = build_body(spec, b);
  for (std::size_t k = 0; k < spec.tubes.size(); ++k) build_tube(spec, spec.tubes[k], loops[k], b);
  return b.surface();
}

// A surface of revolution about z: profile points (rho, z), first and last on the axis (rho = 0).
SurfaceData revolution(const std::vector<std::array<double, 2>>& profile, int around) {
  const double kPi = 3.14159265358979323846;
  Builder b;
  const std::uint32_t bottom = b.add_point({0, 0, profile.front()[1]});
  std::vector<std::uint32_t> previous;
  for (std::size_t i = 1; i + 1 < profile.size(); ++i) {
    std::vector<std::uint32_t> ring;
    for (int j = 0; j < around; ++j) {
      const double a = 2 * kPi * j / around;
      ring.push_back(b.add_point({profile[i][0] * std::cos(a), profile[i][0] * std::sin(a), profile[i][1]}));
    }
    if (previous.empty()) {
      for (int j = 0; j < around; ++j) b.tri(bottom, ring[(j + 1) % around], ring[j]);
    } else {
      for (int j = 0; j < around; ++j) b.quad(previous[j], previous[(j + 1) % around], ring[(j + 1) % around], ring[j]);
    }
    previous = ring;
  }
  b.fan(std::vector<std::uint32_t>(previous.rbegin(), previous.rend()), b.add_point({0, 0, profile.back()[1]}));
  return b.surface();
}

// Appends points of the curve f(t), t in [t0, t1], about every `spacing` of arc length (at least
// `min_pieces` pieces), excluding t0.
void sample_curve(std::vector<std::array<double, 2>>& out, const std::function<std::array<double, 2>(double)>& f,
                  double t0, double t1, double spacing, int min_pieces) {
  double length = 0;
  constexpr int kFine = 2000;
  for (int k = 0; k < kFine; ++k) {
    const auto a = f(t0 + (t1 - t0) * k / kFine), c = f(t0 + (t1 - t0) * (k + 1) / kFine);
    length += std::hypot(c[0] - a[0], c[1] - a[1]);
  }
  const int pieces = std::max(min_pieces, static_cast<int>(std::ceil(length / spacing)));
  for (int k = 1; k <= pieces; ++k) out.push_back(f(t0 + (t1 - t0) * k / pieces));
}

// Two balls of radius 1 centred at z = -+2 joined by a neck of radius `neck`.
SurfaceData dumbbell(double neck, double spacing, int around) {
  const double kPi = 3.14159265358979323846, d = 2;
  const double e = std::acos(neck);  // elevation where the ball's profile meets the neck
  std::vector<std::array<double, 2>> profile{{0, -d - 1}};
  sample_curve(profile, [&](double t) { return std::array<double, 2>{std::cos(t), -d + std::sin(t)}; }, -kPi / 2, e,
               spacing, 8);
  sample_curve(profile, [&](double t) { return std::array<double, 2>{neck, t}; }, -d + std::sin(e), d - std::sin(e),
               spacing, 4);
  sample_curve(profile, [&](double t) { return std::array<double, 2>{std::cos(t), d + std::sin(t)}; }, -e, kPi / 2,
               spacing, 8);
  profile.back()[0] = 0;
  return revolution(profile, around);
}

// A coin of radius 1 and thickness `thickness` with a half-round rim.
SurfaceData coin(double thickness, double spacing, int around) {
  const double kPi = 3.14159265358979323846, h = thickness / 2, flat = 1 - h;
  std::vector<std::array<double, 2>> profile{{0, -h}};
  sample_curve(profile, [&](double t) { return std::array<double, 2>{t, -h}; }, 0, flat, spacing, 4);
  sample_curve(profile, [&](double t) { return std::array<double, 2>{flat + h * std::cos(t), h * std::sin(t)}; },
               -kPi / 2, kPi / 2, spacing, 4);
  sample_curve(profile, [&](double t) { return std::array<double, 2>{flat - t, h}; }, 0, flat, spacing, 4);
  profile.back()[0] = 0;
  return revolution(profile, around);
}

// 12 spikes of length `reach` at the icosahedron's vertices; `sharpness` is the exponent of the
// spike profile cos^sharpness (larger = thinner).
SurfaceData spiky_star(double reach, double sharpness, int subdivisions) {
  std::vector<Vec> points;
  std::vector<std::uint32_t> tris;
  icosphere(0, points, tris);
  const std::vector<Vec> tips = points;
  icosphere(subdivisions, points, tris);
  SurfaceData s;
  for (const auto& u : points) {
    double r = 0.5;
    for (const auto& tip : tips) r += reach * std::pow(std::max(0.0, dot(u, tip)), sharpness);
    s.xyz.insert(s.xyz.end(), {r * u[0], r * u[1], r * u[2]});
  }
  s.tris = std::move(tris);
  return s;
}

// A 20 mm calibration cube, triangulated like a CAD export (few, long triangles): a raised bar on
// +x, a raised block on +z and a pocket in +y, each `relief` high (deep) and `bar` wide.
SurfaceData calibration_cube(double relief, double bar) {
  Builder b;
  std::map<std::array<double, 3>, std::uint32_t> ids;
  auto v = [&](const Vec& p) {
    auto it = ids.find(p);
    if (it != ids.end()) return it->second;
    const std::uint32_t id = b.add_point(p);
    ids.emplace(p, id);
    return id;
  };
  constexpr double L = 20;
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2;
    const double sign = f % 2 == 0 ? 1.0 : -1.0;
    Vec normal{}, du{}, dv{};
    normal[axis] = sign;
    du[(axis + 1) % 3] = 1;
    dv[(axis + 2) % 3] = 1;
    Vec base{};
    base[axis] = sign > 0 ? L : 0;
    auto at = [&](double x, double y, double lift) {
      return add(add(add(base, scale(du, x)), scale(dv, y)), scale(normal, lift));
    };
    const std::array<std::uint32_t, 4> outer{v(at(0, 0, 0)), v(at(L, 0, 0)), v(at(L, L, 0)), v(at(0, L, 0))};
    // Relief footprint [x0, x1] x [y0, y1] (none on the -x, -y, -z faces).
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0, lift = 0;
    if (f == 0) x0 = 3, x1 = 17, y0 = 10 - bar / 2, y1 = 10 + bar / 2, lift = relief;  // +x: bar
    if (f == 2) x0 = 6, x1 = 14, y0 = 6, y1 = 14, lift = -relief;                      // +y: pocket
    if (f == 4) x0 = 4, x1 = 4 + bar, y0 = 4, y1 = 16, lift = relief;                  // +z: block
    if (lift == 0) {
      b.tri_facing(outer[0], outer[1], outer[2], normal);
      b.tri_facing(outer[0], outer[2], outer[3], normal);
      continue;
    }
    const std::array<std::uint32_t, 4> inner{v(at(x0, y0, 0)), v(at(x1, y0, 0)), v(at(x1, y1, 0)), v(at(x0, y1, 0))};
    const std::array<std::uint32_t, 4> top{v(at(x0, y0, lift)), v(at(x1, y0, lift)), v(at(x1, y1, lift)),
                                           v(at(x0, y1, lift))};
    const Vec mid = at((x0 + x1) / 2, (y0 + y1) / 2, 0);
    for (int i = 0; i < 4; ++i) {
      const int k = (i + 1) % 4;
      b.tri_facing(outer[i], outer[k], inner[i], normal);
      b.tri_facing(inner[i], outer[k], inner[k], normal);
      // Wall: its normal points away from the footprint for a raised relief, towards it for a pocket.
      const Vec edge_mid = scale(add(b.points[inner[i]], b.points[inner[k]]), 0.5);
      const Vec wall = scale(sub(edge_mid, mid), lift > 0 ? 1.0 : -1.0);
      b.tri_facing(inner[i], inner[k], top[k], wall);
      b.tri_facing(inner[i], top[k], top[i], wall);
    }
    b.tri_facing(top[0], top[1], top[2], normal);
    b.tri_facing(top[0], top[2], top[3], normal);
  }
  return b.surface();
}

// Flips every triangle when the enclosed volume is negative (the constructions above are
// consistent; this fixes their global sense once).
SurfaceData outward(SurfaceData s) {
  double volume = 0;
  for (std::size_t f = 0; f < s.tris.size(); f += 3) {
    const double* a = &s.xyz[3 * s.tris[f]];
    const double* b = &s.xyz[3 * s.tris[f + 1]];
    const double* c = &s.xyz[3 * s.tris[f + 2]];
    volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  if (volume < 0)
    for (std::size_t f = 0; f < s.tris.size(); f += 3) std::swap(s.tris[f + 1], s.tris[f + 2]);
  return s;
}

// Tentacles: a ball with six tubes, one per cube face, each an S-curve in a plane through its
// face's axis (+-x in y = 0, +-y in z = 0, +-z in x = 0, each on its own side of the ball), so no
// two come near each other. `resolution` sets the grid (4 x resolution cells per face side).
BodySpec tentacles(double width, double curl, int resolution, double ring_spacing) {
  const int n = 4 * resolution, h = n / 2, k = std::max(1, resolution / 2);
  const double kHalfPi = 1.57079632679489662;
  BodySpec spec{{1, 1, 1}, n, ring_spacing, {}};
  for (int f = 0; f < 6; ++f)
    spec.tubes.push_back({f, h - k, h - k, 2 * k, 2 * k, width, width, 0.5,
                          {{0.4, 0, 0}, {1.6, curl, kHalfPi}, {1.2, curl, -kHalfPi}}});
  return spec;
}

// A four-legged creature: an elongated body, four legs with a knee (all bending the same way), a
// neck bending up and a long drooping tail.
BodySpec limbs(double width, int resolution, double ring_spacing) {
  const int n = 6 * resolution, k = std::max(1, resolution / 2), q = n / 4, h = n / 2;
  const double kHalfPi = 1.57079632679489662;
  BodySpec spec{{2, 1, 0.9}, n, ring_spacing, {}};
  for (int a : {q - k, n - q - k})  // -z face: u along x, v along y
    for (int c : {q - k, n - q - k})
      spec.tubes.push_back({5, a, c, 2 * k, 2 * k, width, width, 0.2, {{1.0, 0, 0}, {0.6, 1.2, kHalfPi}, {0.8, 0, 0}}});
  // +x face (u along y, v along z; e2 = +z): the neck. -x face (e2 = -z): the tail.
  spec.tubes.push_back({0, h - k, h + k, 2 * k, 2 * k, 1.5 * width, 1.5 * width, 0.1, {{0.6, 0, 0}, {0.8, 1.0, kHalfPi}}});
  spec.tubes.push_back({1, h - k, h - k, 2 * k, 2 * k, width, width, 0.7, {{2.5, 0.3, kHalfPi}}});
  return spec;
}

// A fish: an ellipsoid with a dorsal fin, two drooping pectoral fins and a widening tail fin, all
// `thickness` thick (tubes of flat elliptic section on holes two cells wide).
BodySpec fins(double thickness, int resolution) {
  const int n = 6 * resolution, h = n / 2, k = std::max(1, resolution / 2);
  const double kPi = 3.14159265358979323846;
  const double t = thickness / 2;
  BodySpec spec{{1.6, 0.6, 0.7}, n, 1.5, {}};
  spec.tubes.push_back({4, h - 3 * k, h - 1, 6 * k, 2, 0.5, t, 0.4, {{0.7, 0, 0}}});        // +z: u = x, v = y
  spec.tubes.push_back({2, h - 1, h, 2, 4 * k, t, 0.3, 0.5, {{0.6, 0.6, kPi}}});            // +y: u = z, v = x
  spec.tubes.push_back({3, h - 1, h, 2, 4 * k, t, 0.3, 0.5, {{0.6, 0.6, kPi}}});            // -y: u = z, v = x
  spec.tubes.push_back({1, h - 1, h - 2 * k, 2, 4 * k, t, 0.5, -0.5, {{0.8, 0, 0}}});       // -x: u = y, v = z
  return spec;
}

SurfaceData make_thin_shape(const std::string& name, int subdivisions) {
  const int res = 1 << std::max(0, subdivisions - 1);  // 4 at the default 3 subdivisions
  const int coarse = std::max(1, res / 2);
  if (name == "tentacles") return body_with_tubes(tentacles(0.12, 0.7, res, 1.0));
  if (name == "tentacles_thin") return body_with_tubes(tentacles(0.04, 1.0, res, 1.0));
  if (name == "tentacles_coarse") return body_with_tubes(tentacles(0.06, 1.0, coarse, 3.0));
  if (name == "limbs") return body_with_tubes(limbs(0.15, res, 1.0));
  if (name == "limbs_thin") return body_with_tubes(limbs(0.05, res, 1.0));
  if (name == "limbs_coarse") return body_with_tubes(limbs(0.08, coarse, 3.0));
  if (name == "fins") return body_with_tubes(fins(0.05, res));
  if (name == "fins_thin") return body_with_tubes(fins(0.015, res));
  if (name == "plate") return coin(0.1, 0.2 / res, 16 * res);
  if (name == "plate_thin") return coin(0.02, 0.2 / res, 16 * res);
  if (name == "spiky_star") return spiky_star(1.2, 40, subdivisions + 1);
  if (name == "spiky_star_long") return spiky_star(2.5, 300, subdivisions + 1);
  if (name == "dumbbell") return dumbbell(0.25, 0.4 / res, 8 * res);
  if (name == "dumbbell_thin") return dumbbell(0.06, 0.4 / res, 8 * res);
  if (name == "calibration_cube") return calibration_cube(1, 2);
  if (name == "calibration_cube_thin") return calibration_cube(0.2, 0.4);
  throw Error(ErrorKind::BadInput, "", 0, "unknown built-in shape '" + name + "'");
}

}  // namespace

const std::vector<std::string>& builtin_shape_names() {
  static const std::vector<std::string> kNames = {"ellipsoid", "bumpy", "peanut", "rounded_box", "spiky", "banana"};
  return kNames;
}

const std::vector<std::string>& thin_shape_names() {
  static const std::vector<std::string> kNames = {
      "tentacles", "tentacles_thin", "tentacles_coarse", "limbs", "limbs_thin", "limbs_coarse",
      "fins", "fins_thin", "plate", "plate_thin", "spiky_star", "spiky_star_long",
      "dumbbell", "dumbbell_thin", "calibration_cube", "calibration_cube_thin"};
  return kNames;
}

SurfaceData make_builtin_shape(const std::string& name, int subdivisions) {
  if (subdivisions < 0 || subdivisions > 7)
    throw Error(ErrorKind::BadInput, "subdivisions must be in [0, 7]");
  const auto& thin = thin_shape_names();
  if (std::find(thin.begin(), thin.end(), name) != thin.end()) {
    if (subdivisions < 1 || subdivisions > 5)
      throw Error(ErrorKind::BadInput, "subdivisions of a thin-feature shape must be in [1, 5]");
    return outward(make_thin_shape(name, subdivisions));
  }
  deform(name, {1, 0, 0});  // validates the name before any work
  std::vector<Vec> points;
  std::vector<std::uint32_t> tris;
  icosphere(subdivisions, points, tris);
  SurfaceData surface;
  surface.xyz.reserve(points.size() * 3);
  for (const auto& p : points) {
    const Vec q = deform(name, p);
    surface.xyz.insert(surface.xyz.end(), q.begin(), q.end());
  }
  surface.tris = std::move(tris);
  return surface;
}

}  // namespace volmap
