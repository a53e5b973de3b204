// meshio (Debian python3-meshio) as the third-party reader the format tests compare against: finding
// a Python that has it (the pyenv shim on PATH may hide Debian's package, so /usr/bin/python3 is
// tried too; tests skip with a message when none is found) and a summary of what meshio read from a
// tet mesh file, checked against the mesh we wrote.
#pragma once

#include <doctest/doctest.h>
#include <volmap/core/mesh_data.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace volmap_test {

inline std::string meshio_python() {
  for (const char* py : {"python3", "/usr/bin/python3"}) {
    const int status = std::system((std::string(py) + " -c 'import meshio' > /dev/null 2>&1").c_str());
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return py;
  }
  return "";
}

// What meshio read: counts, vertex 0 and the last vertex, the first and the last tet, the Gmsh
// physical tag of the first and last tet and the sum of the point labels (-1 when absent).
struct MeshioSummary {
  std::size_t points = 0, tets = 0;
  double first[3] = {0, 0, 0}, last[3] = {0, 0, 0};
  std::uint32_t first_tet[4] = {0, 0, 0, 0}, last_tet[4] = {0, 0, 0, 0};
  long long first_physical = -1, last_physical = -1, label_sum = -1;
};

inline const char* const kMeshioSummaryScript =
    "import sys, meshio\n"
    "m = meshio.read(sys.argv[1])\n"
    "i = [k for k, c in enumerate(m.cells) if c.type == 'tetra']\n"
    "t = [m.cells[k].data for k in i]\n"
    "print(len(m.points), sum(len(x) for x in t))\n"
    "print(' '.join(repr(float(v)) for v in list(m.points[0]) + list(m.points[-1])))\n"
    "print(' '.join(str(int(v)) for v in t[0][0]), ' '.join(str(int(v)) for v in t[-1][-1]))\n"
    "p = m.cell_data.get('gmsh:physical')\n"
    "print(int(p[i[0]][0]) if p else -1, int(p[i[-1]][-1]) if p else -1,\n"
    "      int(sum(m.point_data['label'])) if 'label' in m.point_data else -1)\n";

// Runs the summary script (written into `scratch`) with `python` on `file`; false when it fails.
inline bool meshio_summary(const std::string& python, const std::string& scratch, const std::string& file,
                           MeshioSummary& s) {
  const std::string script = scratch + "/meshio_summary.py";
  { std::ofstream(script) << kMeshioSummaryScript; }
  std::FILE* pipe = popen((python + " '" + script + "' '" + file + "' 2>/dev/null").c_str(), "r");
  if (!pipe) return false;
  std::string out;
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  const int status = pclose(pipe);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return false;
  std::istringstream in(out);
  in >> s.points >> s.tets;
  for (double& v : s.first) in >> v;
  for (double& v : s.last) in >> v;
  for (auto& v : s.first_tet) in >> v;
  for (auto& v : s.last_tet) in >> v;
  in >> s.first_physical >> s.last_physical >> s.label_sum;
  return static_cast<bool>(in);
}

// Counts, vertex 0 and the last vertex bit for bit, first and last tet as we hold them.
inline void check_meshio_summary(const MeshioSummary& s, const volmap::TetMeshData& m) {
  CHECK(s.points == m.num_vertices());
  CHECK(s.tets == m.num_tets());
  if (s.points != m.num_vertices() || s.tets != m.num_tets() || m.num_tets() == 0) return;
  const std::size_t last = m.num_vertices() - 1;
  for (int k = 0; k < 3; ++k) {
    CHECK(s.first[k] == m.xyz[k]);
    CHECK(s.last[k] == m.xyz[3 * last + k]);
  }
  for (int k = 0; k < 4; ++k) {
    CHECK(s.first_tet[k] == m.tets[k]);
    CHECK(s.last_tet[k] == m.tets[m.tets.size() - 4 + k]);
  }
}

}  // namespace volmap_test
