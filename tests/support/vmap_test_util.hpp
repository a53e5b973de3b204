// Helpers shared by the Tutte 3D / map-check / metrics tests: the unit-cube Kuhn grid of the library
// (6 VOLMAP-positive tets per cube) and a way to run a built tool and capture stdout.
#pragma once
#include <volmap/testing/generate.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/predicates.hpp>  // for the includers

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/wait.h>

namespace vmap_test {

// n×n×n cubes of side 1/n on [0,1]³: the library's Kuhn grid (volmap/generate.hpp), 6 VOLMAP-positive
// tets per cube, vertex (i,j,k) = i + (n+1)(j + (n+1)k) at (i/n, j/n, k/n).
inline volmap::TetMeshData kuhn_grid(int n) { return volmap::generate_kuhn_unit_cube(std::size_t(n)); }

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
