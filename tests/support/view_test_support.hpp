// Shared by tests/tools/test_view*.cpp: a small synthetic tet mesh (the library's Kuhn grid of the unit
// cube, VOLMAP-positive), a twisted copy with some tets pushed through
// their opposite face (inverted), a base64 decoder and HTML helpers.
#pragma once

#include <volmap/testing/generate.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/predicates.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace view_test {

// The library's Kuhn grid of the unit cube (volmap/generate.hpp): n^3 cubes, 6 VOLMAP-positive tets each.
inline volmap::TetMeshData grid_mesh(int n) { return volmap::generate_kuhn_unit_cube(std::size_t(n)); }

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
