// Built-in genus-0 shapes: icosphere + a smooth injective deformation. Radial shapes use
// p(u) = r(u)·u with r > 0 (star-shaped about the origin, hence embedded); the banana bends an
// ellipsoid along a circle of radius larger than its thickness (embedded, not star-shaped).
#include <volmap/core/error.hpp>
#include "support/shapes.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
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

}  // namespace

const std::vector<std::string>& builtin_shape_names() {
  static const std::vector<std::string> kNames = {"ellipsoid", "bumpy", "peanut", "rounded_box", "spiky", "banana"};
  return kNames;
}

SurfaceData make_builtin_shape(const std::string& name, int subdivisions) {
  if (subdivisions < 0 || subdivisions > 7)
    throw Error(ErrorKind::BadInput, "subdivisions must be in [0, 7]");
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
