// Shared by tests/test_view*.cpp: a small synthetic tet mesh (Freudenthal split of an n^3 grid,
// VOLMAP-positive after exact orientation fix-up), a twisted copy with some tets pushed through
// their opposite face (inverted), a base64 decoder and HTML helpers.
#pragma once

#include <volmap/mesh_data.hpp>
#include <volmap/predicates.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace view_test {

inline volmap::TetMeshData grid_mesh(int n) {
  volmap::TetMeshData m;
  auto vid = [n](int i, int j, int k) { return std::uint32_t((i * (n + 1) + j) * (n + 1) + k); };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        m.xyz.push_back(double(i) / n);
        m.xyz.push_back(double(j) / n);
        m.xyz.push_back(double(k) / n);
      }
  // Freudenthal / Kuhn: 6 tets per cube along the main diagonal, conforming across cubes.
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<std::uint32_t, 4> t;
          t[0] = vid(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            c[p[s]] += 1;
            t[s + 1] = vid(c[0], c[1], c[2]);
          }
          const double* a = &m.xyz[3 * t[0]];
          const double* b = &m.xyz[3 * t[1]];
          const double* cc = &m.xyz[3 * t[2]];
          const double* d = &m.xyz[3 * t[3]];
          if (volmap::orient3d(a, b, cc, d) < 0) std::swap(t[0], t[1]);
          m.tets.insert(m.tets.end(), t.begin(), t.end());
        }
  m.vertex_labels.assign(m.num_vertices(), 0);
  m.tet_labels.assign(m.num_tets(), 0);
  return m;
}

// Scaled by 100 (like the VOLMAP domains) and twisted about z; interior vertices near the centre are
// pushed so that a few tets invert.
inline volmap::TetMeshData twisted(const volmap::TetMeshData& in, bool invert_some) {
  volmap::TetMeshData out = in;
  for (std::size_t v = 0; v < in.num_vertices(); ++v) {
    const double x = in.xyz[3 * v] - 0.5, y = in.xyz[3 * v + 1] - 0.5, z = in.xyz[3 * v + 2];
    const double a = 0.8 * z;
    out.xyz[3 * v] = 100 * (std::cos(a) * x - std::sin(a) * y);
    out.xyz[3 * v + 1] = 100 * (std::sin(a) * x + std::cos(a) * y);
    out.xyz[3 * v + 2] = 100 * z * z;
  }
  if (invert_some) {
    // Move the vertex nearest the centre far along +x: its incident tets on one side invert.
    std::size_t best = 0;
    double bd = 1e300;
    for (std::size_t v = 0; v < in.num_vertices(); ++v) {
      const double dx = in.xyz[3 * v] - 0.5, dy = in.xyz[3 * v + 1] - 0.5, dz = in.xyz[3 * v + 2] - 0.5;
      const double d = dx * dx + dy * dy + dz * dz;
      if (d < bd) { bd = d; best = v; }
    }
    out.xyz[3 * best] += 40;
  }
  return out;
}

inline std::string base64_decode(const std::string& s) {
  auto val = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  unsigned buf = 0;
  int bits = 0;
  for (char c : s) {
    const int v = val(c);
    if (v < 0) continue;
    buf = (buf << 6) | unsigned(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += char((buf >> bits) & 0xff);
    }
  }
  return out;
}

// Text between the first `open` and the following `close` (empty when absent).
inline std::string between(const std::string& s, const std::string& open, const std::string& close) {
  const auto a = s.find(open);
  if (a == std::string::npos) return {};
  const auto b = s.find(close, a + open.size());
  if (b == std::string::npos) return {};
  return s.substr(a + open.size(), b - a - open.size());
}

inline std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Counts src=/href= attributes whose value starts with http:// or https:// (external loads).
inline int external_references(const std::string& html) {
  int n = 0;
  for (const char* attr : {"src=", "href=", "SRC=", "HREF="}) {
    for (std::size_t p = html.find(attr); p != std::string::npos; p = html.find(attr, p + 1)) {
      std::size_t q = p + std::string(attr).size();
      if (q < html.size() && (html[q] == '"' || html[q] == '\'')) ++q;
      if (html.compare(q, 7, "http://") == 0 || html.compare(q, 8, "https://") == 0 || html.compare(q, 2, "//") == 0) ++n;
    }
  }
  return n;
}

}  // namespace view_test
