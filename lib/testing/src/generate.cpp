// Kuhn-grid generator (conventions in generate.hpp). Orientation of each of the 6 Kuhn tets is
// fixed once with the exact orient3d on the unit cube and applied to every cube (translation
// invariant), so every output tet is positive.
#include <volmap/testing/generate.hpp>

#include <volmap/core/error.hpp>
#include <volmap/predicates.hpp>

#include <array>
#include <utility>

namespace volmap {

TetMeshData generate_kuhn_grid(std::size_t nx, std::size_t ny, std::size_t nz,
                               const std::function<bool(std::size_t, std::size_t, std::size_t)>& keep,
                               double spacing) {
  if (nx == 0 || ny == 0 || nz == 0) throw Error(ErrorKind::BadInput, "generate_kuhn_grid: empty grid");
  const std::size_t sx = nx + 1, sy = ny + 1, sz = nz + 1;
  if (6 * nx * ny * nz > (std::size_t(1) << 30)) throw Error(ErrorKind::BadInput, "generate_kuhn_grid: too many tets");
  // The 6 axis orders and their corner offsets (bit 0 = x, 1 = y, 2 = z).
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::array<std::array<int, 4>, 6> corners;
  for (int p = 0; p < 6; ++p) {
    int c = 0;
    corners[p][0] = 0;
    for (int s = 0; s < 3; ++s) {
      c |= 1 << perms[p][s];
      corners[p][s + 1] = c;
    }
    double pts[4][3];
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < 3; ++a) pts[k][a] = (corners[p][k] >> a) & 1;
    if (orient3d(pts[0], pts[1], pts[2], pts[3]) < 0) std::swap(corners[p][2], corners[p][3]);
  }
  auto vid = [&](std::size_t i, std::size_t j, std::size_t k) { return std::uint32_t(i + sx * (j + sy * k)); };
  TetMeshData d;
  d.tets.reserve(24 * nx * ny * nz);
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        if (keep && !keep(i, j, k)) continue;
        for (int p = 0; p < 6; ++p)
          for (int c : corners[p]) d.tets.push_back(vid(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)));
      }
  std::vector<std::uint32_t> remap(sx * sy * sz, 0xFFFFFFFFu);
  for (std::uint32_t v : d.tets) remap[v] = 0;
  std::uint32_t n = 0;
  d.xyz.reserve(3 * remap.size());
  for (std::size_t k = 0; k < sz; ++k)
    for (std::size_t j = 0; j < sy; ++j)
      for (std::size_t i = 0; i < sx; ++i) {
        std::uint32_t& r = remap[vid(i, j, k)];
        if (r == 0xFFFFFFFFu) continue;
        r = n++;
        d.xyz.push_back(double(i) * spacing);
        d.xyz.push_back(double(j) * spacing);
        d.xyz.push_back(double(k) * spacing);
      }
  for (std::uint32_t& v : d.tets) v = remap[v];
  d.vertex_labels.assign(n, 0);
  d.tet_labels.assign(d.tets.size() / 4, 0);
  return d;
}

TetMeshData generate_kuhn_grid(std::size_t nx, std::size_t ny, std::size_t nz, double spacing) {
  return generate_kuhn_grid(nx, ny, nz, nullptr, spacing);
}

TetMeshData generate_kuhn_unit_cube(std::size_t n) {
  TetMeshData d = generate_kuhn_grid(n, n, n);
  const double scale = double(n);
  for (double& c : d.xyz) c /= scale;  // integer / n: one rounding, exact 0 and 1
  return d;
}

}  // namespace volmap
