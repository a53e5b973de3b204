// anchor_volmap_metrics.hpp — BENCHMARK-ONLY anchor: VOLMAP's `metrics` program (VOLMAP/volmap.github.io
// metrics/, on cinolib), re-implemented here after its algorithm and memory layout so that the
// benchmarks can time volmap-metrics against it in the same run. Never used by the library.
// What it reproduces (volmap-reference.md §7, §8):
//   * cinolib read_MESH: fscanf token by token (keywords with %255s, numbers with %lf / %d); vertices
//     pushed into a vector of 3-double points, every tet into its own heap-allocated std::vector<uint>
//     (built, then pushed by copy), labels pushed and inserted into std::unordered_set<int>;
//   * orient3d (exact) and cinolib's unsigned volume of every output tet, then the inverted count;
//   * five passes over the tets, one per energy, each computing per tet J = F1·F0⁻¹ (Eigen inverse, a
//     plain triple-loop product) and Eigen::JacobiSVD with full U and V (cinolib mat3d::SVD), then the
//     energy, the clamp, min / max / volume-weighted E; one radius-ratio pass;
//   * each mesh in its own per-tet vertex order (the reference's quirk 5).
// One deliberate difference: where J is not finite the reference reads uninitialised singular values;
// here they are NaN (the energy then clamps to `upper`), so the anchor is deterministic.
// Its printed block must equal VOLMAP's oracle digits (checked by bench_volume_maps at start).
#pragma once

#include <volmap/predicates.hpp>

#include "../lib/check/src/metrics_tet.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

namespace anchor {

using Point = std::array<double, 3>;  // cinolib vec3d

struct VolmapMesh {
  std::vector<Point> verts;
  std::vector<std::vector<unsigned>> polys;
};

// cinolib read_MESH(filename, verts, polys): labels are read into locals and dropped on return.
inline bool read_mesh_like_cinolib(const char* path, VolmapMesh& mesh) {
  std::FILE* f = std::fopen(path, "r");
  if (!f) return false;
  std::vector<int> vert_labels, poly_labels;
  std::unordered_set<int> v_unique, p_unique;
  auto seek = [&](const char* keyword) {
    char s[256] = {0};
    do {
      if (std::fscanf(f, "%255s", s) != 1) return false;
    } while (std::strcmp(s, keyword) != 0);
    return true;
  };
  int version = 0, dim = 0, nv = 0, nc = 0;
  bool ok = seek("MeshVersionFormatted") && std::fscanf(f, "%d", &version) == 1 && seek("Dimension") &&
            std::fscanf(f, "%d", &dim) == 1 && seek("Vertices") && std::fscanf(f, "%d", &nv) == 1;
  for (int i = 0; ok && i < nv; ++i) {
    double x, y, z;
    int l;
    ok = std::fscanf(f, "%lf", &x) == 1 && std::fscanf(f, "%lf", &y) == 1 && std::fscanf(f, "%lf", &z) == 1 &&
         std::fscanf(f, "%d", &l) == 1;
    mesh.verts.push_back({x, y, z});
    vert_labels.push_back(l);
    v_unique.insert(l);
  }
  char word[64];
  while (ok && std::fscanf(f, "%63s", word) == 1) {
    if (std::strcmp(word, "End") == 0) break;
    if (std::strcmp(word, "Tetrahedra") != 0) continue;
    ok = std::fscanf(f, "%d", &nc) == 1;
    for (int i = 0; ok && i < nc; ++i) {
      int l;
      std::vector<unsigned> tet(4);
      for (unsigned& id : tet) ok = ok && std::fscanf(f, "%u", &id) == 1;
      ok = ok && std::fscanf(f, "%d", &l) == 1;
      for (unsigned& id : tet) id -= 1;
      mesh.polys.push_back(tet);
      poly_labels.push_back(l);
      p_unique.insert(l);
    }
  }
  std::fclose(f);
  return ok;
}

struct VolmapMetrics {
  std::size_t num_tets = 0, inverted = 0;
  float inverted_percent = 0;
  double energy[5][3] = {};  // conformal, dirichlet, symdir, arap, mips3d: min, max, E
  double trr[3] = {};
};

namespace detail {

using volmap::metrics_detail::RowMat3;

// cinolib mat3d({a1−a0, a2−a0, a3−a0}) (columns), f1·f0.inverse(), then SVD.
inline void singular_values(const Point* a[4], const Point* b[4], double s[3]) {
  RowMat3 f0, f1;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      f0(r, c) = (*a[c + 1])[r] - (*a[0])[r];
      f1(r, c) = (*b[c + 1])[r] - (*b[0])[r];
    }
  const RowMat3 j = volmap::metrics_detail::compat_jacobian(f0, f1);  // VOLMAP's arithmetic, shared
  if (!j.allFinite()) {  // the reference reads uninitialised values here (Eigen 3.4 returns early): NaN instead
    s[0] = s[1] = s[2] = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const Eigen::JacobiSVD<RowMat3> svd(j, Eigen::ComputeFullU | Eigen::ComputeFullV);
  RowMat3 u = svd.matrixU(), v = svd.matrixV();  // cinolib copies U, S, V back into its own matrices
  (void)u;
  (void)v;
  for (int k = 0; k < 3; ++k) s[k] = svd.singularValues()[k];
}

inline double energy_of(int e, const double s[3]) {
  const double a = s[0], b = s[1], c = s[2];
  switch (e) {
    case 0: return (a * a + b * b + c * c) / (3 * std::pow(a * b * c, 2. / 3.));
    case 1: return a * a + b * b + c * c;
    case 2: return a * a + b * b + c * c + 1 / (a * a) + 1 / (b * b) + 1 / (c * c);
    case 3: return std::pow(a - 1, 2) + std::pow(b - 1, 2) + std::pow(c - 1, 2);
    default: return 1. / 8. * (a / b + b / a) * (c / a + a / c) * (b / c + c / b);
  }
}

inline double unsigned_volume(const Point& p0, const Point& p1, const Point& p2, const Point& p3) {
  const double l0[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double l2[3] = {p0[0] - p2[0], p0[1] - p2[1], p0[2] - p2[2]};
  const double l3[3] = {p3[0] - p0[0], p3[1] - p0[1], p3[2] - p0[2]};
  const double cr[3] = {l2[1] * l0[2] - l2[2] * l0[1], l2[2] * l0[0] - l2[0] * l0[2], l2[0] * l0[1] - l2[1] * l0[0]};
  return std::fabs((cr[0] * l3[0] + cr[1] * l3[1] + cr[2] * l3[2]) / 6.0);
}

inline double radius_ratio(const Point& p0, const Point& p1, const Point& p2, const Point& p3) {
  auto sub = [](const Point& a, const Point& b) { return Point{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto cross = [](const Point& a, const Point& b) {
    return Point{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  auto dot = [](const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const Point l0 = sub(p1, p0), l1 = sub(p2, p1), l2 = sub(p0, p2), l3 = sub(p3, p0), l4 = sub(p3, p1);
  const Point c20 = cross(l2, l0), c30 = cross(l3, l0), c41 = cross(l4, l1), c32 = cross(l3, l2);
  const double n3 = dot(l3, l3), n2 = dot(l2, l2), n0 = dot(l0, l0);
  Point num;
  for (int k = 0; k < 3; ++k) num[k] = n3 * c20[k] + n2 * c30[k] + n0 * c32[k];
  const double area =
      (std::sqrt(dot(c20, c20)) + std::sqrt(dot(c30, c30)) + std::sqrt(dot(c41, c41)) + std::sqrt(dot(c32, c32))) * 0.5;
  const double volume = dot(c20, l3) / 6.0;
  if (std::fabs(volume) < std::numeric_limits<double>::min()) return std::numeric_limits<double>::max();
  return std::sqrt(dot(num, num)) * area / (108.0 * volume * volume);
}

}  // namespace detail

// VOLMAP's main(): orientation + volumes, inverted count, five energy passes, radius ratio.
inline VolmapMetrics volmap_metrics(const VolmapMesh& orig, const VolmapMesh& map, double upper) {
  VolmapMetrics r;
  const std::size_t nt = map.polys.size();
  r.num_tets = nt;
  std::vector<double> orients(nt), volumes(nt);
  double total_volume = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tet = map.polys[t];
    orients[t] = volmap::orient3d(map.verts[tet[0]].data(), map.verts[tet[1]].data(), map.verts[tet[2]].data(),
                                  map.verts[tet[3]].data());
  }
  for (std::size_t t = 0; t < nt; ++t) {
    if (orients[t] <= 0) continue;
    const auto& tet = map.polys[t];
    volumes[t] = detail::unsigned_volume(map.verts[tet[0]], map.verts[tet[1]], map.verts[tet[2]], map.verts[tet[3]]);
    total_volume += volumes[t];
  }
  for (std::size_t t = 0; t < nt; ++t) r.inverted += orients[t] <= 0;
  r.inverted_percent = float(r.inverted) / float(nt) * 100.0f;
  static constexpr double kLower[5] = {1.0, 3.0, 6.0, 0.0, 1.0};
  for (int e = 0; e < 5; ++e) {
    double E = 0, mn = upper, mx = kLower[e];
    for (std::size_t t = 0; t < orig.polys.size(); ++t) {
      if (orients[t] <= 0) continue;
      const auto& o = orig.polys[t];
      const auto& m = map.polys[t];
      const Point* a[4] = {&orig.verts[o[0]], &orig.verts[o[1]], &orig.verts[o[2]], &orig.verts[o[3]]};
      const Point* b[4] = {&map.verts[m[0]], &map.verts[m[1]], &map.verts[m[2]], &map.verts[m[3]]};
      double s[3];
      detail::singular_values(a, b, s);
      double d = detail::energy_of(e, s);
      if (std::isinf(d) || std::isnan(d)) d = upper;
      d = std::clamp(d, kLower[e], upper);
      mn = std::min(mn, d);
      mx = std::max(mx, d);
      E += d * volumes[t];
    }
    r.energy[e][0] = mn;
    r.energy[e][1] = mx;
    r.energy[e][2] = E / total_volume;
  }
  double mn = std::numeric_limits<double>::infinity(), mx = -mn, avg = 0;
  for (const auto& tet : map.polys) {
    const double trr = -detail::radius_ratio(map.verts[tet[0]], map.verts[tet[1]], map.verts[tet[2]], map.verts[tet[3]]);
    mn = std::min(mn, trr);
    mx = std::max(mx, trr);
    avg += trr;
  }
  r.trr[0] = mn;
  r.trr[1] = mx;
  r.trr[2] = avg / double(nt);
  return r;
}

// VOLMAP's printValuesOnScreen.
inline std::string format_volmap(const VolmapMetrics& r) {
  std::ostringstream s;
  static const char* kNames[5] = {"Conformal", "Dirichlet", "Sym. Dirichlet", "Arap", "Mips3d"};
  s << "Num tets: " << r.num_tets << "\nNum inv. tets: " << r.inverted << " (" << r.inverted_percent << "%)\n";
  for (int e = 0; e < 5; ++e)
    s << kNames[e] << " (min/max/E): " << r.energy[e][0] << " / " << r.energy[e][1] << " / " << r.energy[e][2] << "\n";
  s << "Tet Radius Ratio: (min/max/avg): " << r.trr[0] << " / " << r.trr[1] << " /: " << r.trr[2] << "\n";
  return s.str();
}

}  // namespace anchor
