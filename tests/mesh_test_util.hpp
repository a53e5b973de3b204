// Shared helpers of the tet-mesh tests: brute-force oracles (std::map based, deliberately naive and
// independent of the library's counting-sort code) and a tiny Medit reader for the shared data.
#pragma once

#include <volmap/local_tables.hpp>
#include <volmap/mesh_data.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mesh_test {

using Triple = std::array<std::uint32_t, 3>;

inline Triple sorted_face(const std::vector<std::uint32_t>& tv, std::size_t h) {
  const std::uint32_t* p = &tv[4 * (h / 4)];
  Triple f;
  for (int k = 0; k < 3; ++k) f[k] = p[volmap::kTetFace[h % 4][k]];
  std::sort(f.begin(), f.end());
  return f;
}

// Every distinct face -> its half-faces.
inline std::map<Triple, std::vector<std::uint32_t>> brute_faces(const std::vector<std::uint32_t>& tv) {
  std::map<Triple, std::vector<std::uint32_t>> m;
  for (std::size_t h = 0; h < tv.size(); ++h)
    if (tv[4 * (h / 4)] != 0xFFFFFFFFu) m[sorted_face(tv, h)].push_back(std::uint32_t(h));
  return m;
}

// Every edge (sorted pair) -> sorted tets containing it.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> brute_edges(
    const std::vector<std::uint32_t>& tv) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> m;
  for (std::size_t t = 0; t < tv.size() / 4; ++t) {
    if (tv[4 * t] == 0xFFFFFFFFu) continue;
    for (int k = 0; k < 6; ++k) {
      std::uint32_t a = tv[4 * t + volmap::kTetEdge[k][0]], b = tv[4 * t + volmap::kTetEdge[k][1]];
      if (a > b) std::swap(a, b);
      m[{a, b}].push_back(std::uint32_t(t));
    }
  }
  return m;
}

inline int orient_tet(const std::vector<double>& xyz, const std::uint32_t* p) {
  return volmap::orient3d(&xyz[3 * std::size_t(p[0])], &xyz[3 * std::size_t(p[1])], &xyz[3 * std::size_t(p[2])],
                          &xyz[3 * std::size_t(p[3])]);
}

// Minimal Medit reader for tests only (Vertices / Tetrahedra blocks, '#' comments); the real reader
// lives in the IO module.
inline bool read_medit_for_test(const std::string& path, volmap::TetMeshData& d) {
  std::ifstream in(path);
  if (!in) return false;
  std::string tok;
  auto next = [&](std::string& s) {
    while (in >> s) {
      if (s[0] == '#') {
        std::string rest;
        std::getline(in, rest);
        continue;
      }
      return true;
    }
    return false;
  };
  while (next(tok)) {
    if (tok == "Vertices") {
      std::string n;
      next(n);
      const std::size_t nv = std::stoul(n);
      d.xyz.resize(3 * nv);
      d.vertex_labels.resize(nv);
      for (std::size_t v = 0; v < nv; ++v) {
        for (int c = 0; c < 3; ++c) { next(tok); d.xyz[3 * v + c] = std::stod(tok); }
        next(tok); d.vertex_labels[v] = std::stoi(tok);
      }
    } else if (tok == "Tetrahedra") {
      std::string n;
      next(n);
      const std::size_t nt = std::stoul(n);
      d.tets.resize(4 * nt);
      d.tet_labels.resize(nt);
      for (std::size_t t = 0; t < nt; ++t) {
        for (int c = 0; c < 4; ++c) { next(tok); d.tets[4 * t + c] = std::uint32_t(std::stoul(tok) - 1); }
        next(tok); d.tet_labels[t] = std::stoi(tok);
      }
    } else if (tok == "End") {
      break;
    }
  }
  return !d.tets.empty();
}

}  // namespace mesh_test
