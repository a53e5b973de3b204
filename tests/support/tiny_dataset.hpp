// A tiny VOLMAP-layout dataset for runner and workflow tests: a unit cube cut into the 6 Kuhn tets
// around its diagonal (every tet VOLMAP-positive, every vertex on the boundary) with the identity
// boundary map, so the identity map (a copy of the input) is a valid volume map.
#pragma once

#include <doctest/doctest.h>
#include <volmap/predicates.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>

namespace volmap_test {

inline void write_file(const std::filesystem::path& p, const std::string& text, bool executable = false) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
  if (executable) ::chmod(p.c_str(), 0755);
}

// A unit cube cut into the 6 Kuhn tets around the diagonal 0-7, every tet VOLMAP-positive, as a
// Medit file, plus the identity boundary map (every vertex is on the boundary).
inline void write_cube_case(const std::filesystem::path& root, const std::string& group, const std::string& name, const std::string& dom) {
  const double v[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  const int paths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
  std::string mesh = "MeshVersionFormatted 1\nDimension 3\nVertices\n8\n";
  for (auto& p : v) mesh += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + " 0\n";
  mesh += "Tetrahedra\n6\n";
  for (auto& pth : paths) {
    int t[4] = {0, pth[0], pth[1], 7};
    if (volmap::orient3d(v[t[0]], v[t[1]], v[t[2]], v[t[3]]) < 0) std::swap(t[0], t[1]);
    REQUIRE(volmap::orient3d(v[t[0]], v[t[1]], v[t[2]], v[t[3]]) > 0);
    mesh += std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + " " +
            std::to_string(t[3] + 1) + " 0\n";
  }
  mesh += "End\n";
  write_file(root / group / (name + ".mesh"), mesh);
  std::string map;
  for (int i = 0; i < 8; ++i)
    map += std::to_string(i) + " " + std::to_string(v[i][0]) + " " + std::to_string(v[i][1]) + " " +
           std::to_string(v[i][2]) + "\n";
  write_file(root / (group + "_" + dom) / (name + "_" + dom + ".txt"), map);
}


}  // namespace volmap_test
