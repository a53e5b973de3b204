// Helpers shared by the Tutte 3D / map-check / metrics tests: small meshes built in memory, a Kuhn
// grid generator (6 VOLMAP-positive tets per cube) and a way to run a built tool and capture stdout.
#pragma once
#include <volmap/mesh_data.hpp>
#include <volmap/predicates.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/wait.h>

namespace vmap_test {

// n×n×n cubes of side 1/n on [0,1]³, Kuhn subdivision (6 tets around the main diagonal per cube),
// each tet ordered so that exact orient3d > 0 (VOLMAP-positive). Vertex (i,j,k) = i + (n+1)(j + (n+1)k).
inline volmap::TetMeshData kuhn_grid(int n) {
  volmap::TetMeshData m;
  const int s = n + 1;
  m.xyz.reserve(3 * s * s * s);
  for (int k = 0; k < s; ++k)
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) {
        m.xyz.push_back(double(i) / n);
        m.xyz.push_back(double(j) / n);
        m.xyz.push_back(double(k) / n);
      }
  auto id = [s](int i, int j, int k) { return std::uint32_t(i + s * (j + s * k)); };
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<std::uint32_t, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int step = 0; step < 3; ++step) {
            ++c[p[step]];
            t[step + 1] = id(c[0], c[1], c[2]);
          }
          // Orientation depends on the permutation's parity only.
          if (volmap::orient3d(&m.xyz[3 * t[0]], &m.xyz[3 * t[1]], &m.xyz[3 * t[2]], &m.xyz[3 * t[3]]) < 0) {
            std::swap(t[0], t[1]);
          }
          m.tets.insert(m.tets.end(), t.begin(), t.end());
        }
  m.vertex_labels.assign(m.num_vertices(), 0);
  m.tet_labels.assign(m.num_tets(), 0);
  return m;
}

// Runs a shell command, returns {exit code, stdout}.
struct RunResult {
  int code = -1;
  std::string out;
};
inline RunResult run(const std::string& command) {
  RunResult r;
  FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) r.out.append(buffer, n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

}  // namespace vmap_test
