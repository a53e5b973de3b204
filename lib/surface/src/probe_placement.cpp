// probe_placement.cpp — other placements of a domain's node probes (domain.hpp): the 24 rotations
// and the pulls towards the centre. Conventions: the probes live in the input's bounding box
// normalised to [0,1]³; a rotation R of the cube about its centre moves probe fraction f to
// 0.5 + R(f − 0.5), and a bbox corner (reference numbering) to the corner there; a pull by s moves f
// to 0.5 + s(f − 0.5) (a corner probe becomes the fraction of its corners' mean). Rotation 0 is the
// identity; the others are the proper signed permutation matrices in a fixed order (permutation of
// the axes, then signs), so that an index names the same rotation on every run.
#include <volmap/surface/domain.hpp>
#include <volmap/core/error.hpp>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace volmap {
namespace {

using Matrix = std::array<std::array<int, 3>, 3>;

// The 24 proper rotations of the cube, identity first.
std::array<Matrix, kNumProbeRotations> cube_rotations() {
  std::array<Matrix, kNumProbeRotations> out{};
  const int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  std::size_t n = 0;
  for (const auto& p : perms)
    for (int signs = 0; signs < 8; ++signs) {
      Matrix m{};
      for (int r = 0; r < 3; ++r) m[r][p[r]] = (signs >> r & 1) ? -1 : 1;
      const int det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                      m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
      if (det == 1) out[n++] = m;
    }
  return out;
}

int rotated_corner(const Matrix& m, int c) {
  int bits[3];
  for (int r = 0; r < 3; ++r) {
    int x = 0;  // R(2·bit − 1) in {−1, 1}
    for (int k = 0; k < 3; ++k) x += m[r][k] * (2 * kBboxCornerBits[c][k] - 1);
    bits[r] = x > 0 ? 1 : 0;
  }
  for (int k = 0; k < 8; ++k)
    if (kBboxCornerBits[k][0] == bits[0] && kBboxCornerBits[k][1] == bits[1] && kBboxCornerBits[k][2] == bits[2]) return k;
  return c;  // unreachable: every sign pattern is a corner
}

}  // namespace

Domain with_rotated_probes(const Domain& domain, int rotation) {
  if (rotation < 0 || rotation >= kNumProbeRotations)
    throw Error(ErrorKind::BadInput, "", 0, "probe rotation out of range: " + std::to_string(rotation));
  if (rotation == 0) return domain;
  static const std::array<Matrix, kNumProbeRotations> rotations = cube_rotations();
  const Matrix& m = rotations[std::size_t(rotation)];
  Domain d = domain;
  for (std::size_t node = 0; node < d.num_nodes(); ++node) {
    for (int& c : d.probe_corners[node]) c = rotated_corner(m, c);
    std::array<double, 3>& f = d.probe_fraction[node];
    if (std::isnan(f[0])) continue;
    std::array<double, 3> g{};
    for (int r = 0; r < 3; ++r) {
      double x = 0;
      for (int k = 0; k < 3; ++k) x += m[r][k] * (f[std::size_t(k)] - 0.5);
      g[std::size_t(r)] = 0.5 + x;
    }
    f = g;
  }
  return d;
}

Domain with_pulled_probes(const Domain& domain, double scale) {
  if (!(scale > 0 && scale <= 1))
    throw Error(ErrorKind::BadInput, "", 0, "probe pull out of (0, 1]: " + std::to_string(scale));
  if (scale == 1) return domain;
  Domain d = domain;
  for (std::size_t node = 0; node < d.num_nodes(); ++node) {
    std::array<double, 3>& f = d.probe_fraction[node];
    std::vector<int>& corners = d.probe_corners[node];
    if (!corners.empty()) {
      f = {0, 0, 0};
      for (int c : corners)
        for (int k = 0; k < 3; ++k) f[std::size_t(k)] += kBboxCornerBits[c][k];
      for (double& x : f) x /= double(corners.size());
      corners.clear();
    }
    if (std::isnan(f[0])) continue;
    for (double& x : f) x = 0.5 + scale * (x - 0.5);
  }
  return d;
}

}  // namespace volmap
