// volmap-convert end to end (exit codes, --json, no partial output) and a third-party reader check:
// when Python's meshio is importable, files written by our VTK/VTU writers are read back by meshio
// and their counts and coordinates compared.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <volmap/io/io.hpp>

#include "meshio_support.hpp"
#include "test_support.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

using namespace volmap;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir() { return volmap_test::scratch_dir("io_tool"); }
std::string read_text(const fs::path& p) { return volmap_test::read_bytes(p); }
// Runs a shell command, returns its exit code; stdout goes to `out`.
int run(const std::string& command, std::string* out = nullptr) {
  const fs::path capture = scratch_dir() / "stdout.txt";
  const std::string full = command + " > '" + capture.string() + "' 2> '" + (scratch_dir() / "stderr.txt").string() + "'";
  const int status = std::system(full.c_str());
  if (out) *out = read_text(capture);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

}  // namespace

TEST_CASE("volmap-convert: conversions keep order, exit codes, --json, no partial output") {
  const fs::path tool = volmap_test::tool("volmap-convert");
  if (!fs::exists(tool)) {
    MESSAGE("skipped: " << tool << " not built");
    return;
  }
  VOLMAP_REQUIRE_DATA(bone, "volmap/G1/bone.mesh");
  const TetMeshData original = read_medit(bone.string());
  const fs::path d = scratch_dir();
  std::string out;
  CHECK(run(quoted(tool) + " " + quoted(bone) + " " + quoted(d / "a.vtu") + " --json", &out) == 0);
  const auto j = nlohmann::json::parse(out);
  CHECK(j["ok"] == true);
  CHECK(j["vertices"] == 2841);
  CHECK(j["tets"] == 8629);
  CHECK(run(quoted(tool) + " " + quoted(d / "a.vtu") + " " + quoted(d / "b.vtk") + " --binary") == 0);
  CHECK(run(quoted(tool) + " " + quoted(d / "b.vtk") + " " + quoted(d / "c.VTK")) == 0);
  CHECK(run(quoted(tool) + " " + quoted(d / "c.VTK") + " " + quoted(d / "d.vtu") + " --vtu-ascii") == 0);
  CHECK(run(quoted(tool) + " " + quoted(d / "d.vtu") + " " + quoted(d / "e.mesh")) == 0);
  const TetMeshData back = read_medit((d / "e.mesh").string());
  CHECK(back.xyz.size() == original.xyz.size());
  CHECK(std::memcmp(back.xyz.data(), original.xyz.data(), 8 * original.xyz.size()) == 0);
  CHECK(back.tets == original.tets);
  // The converted Medit text equals our own writer's output byte for byte.
  write_medit((d / "f.mesh").string(), original);
  CHECK(read_text(d / "e.mesh") == read_text(d / "f.mesh"));

  // Exit 2: usage, unknown extensions, missing/bad input; --json still prints one object.
  CHECK(run(quoted(tool)) == 2);
  CHECK(run(quoted(tool) + " " + quoted(bone) + " " + quoted(d / "x.obj")) == 2);
  CHECK_FALSE(fs::exists(d / "x.obj"));
  CHECK(run(quoted(tool) + " " + quoted(d / "missing.mesh") + " " + quoted(d / "y.vtu") + " --json", &out) == 2);
  CHECK(nlohmann::json::parse(out)["ok"] == false);
  CHECK_FALSE(fs::exists(d / "y.vtu"));
  { std::ofstream(d / "broken.mesh") << "MeshVersionFormatted 1\nDimension 3\nVertices\n2\n0 0 0 0\n"; }
  CHECK(run(quoted(tool) + " " + quoted(d / "broken.mesh") + " " + quoted(d / "z.vtk")) == 2);
  CHECK_FALSE(fs::exists(d / "z.vtk"));
  CHECK(read_text(d / "stderr.txt").find("broken.mesh:4") != std::string::npos);
  CHECK(run(quoted(tool) + " " + quoted(d) + " " + quoted(d / "w.vtk")) == 2);
  // A usage error stops parsing before --json is stored: the one object is still printed.
  CHECK(run(quoted(tool) + " " + quoted(bone) + " " + quoted(d / "v.vtk") + " --json --no-such-option", &out) == 2);
  CHECK(nlohmann::json::parse(out)["exit_code"] == 2);
  CHECK(run(quoted(tool) + " " + quoted(bone) + " --json", &out) == 2);
  CHECK(nlohmann::json::parse(out)["ok"] == false);
  CHECK(run(quoted(tool) + " --help") == 0);
}

TEST_CASE("third-party reader: meshio reads our .vtu and .vtk files") {
  const std::string py = volmap_test::meshio_python();
  if (py.empty()) {
    MESSAGE("skipped: Python meshio not available");
    return;
  }
  VOLMAP_REQUIRE_DATA(pente, "tetmeshes/robustpolycube/pente.mesh");
  const TetMeshData m = read_medit(pente.string());
  const fs::path d = scratch_dir();
  write_vtu((d / "m.vtu").string(), m, {{"energy", std::vector<double>(m.num_tets(), 0.25)}});
  write_vtu((d / "ma.vtu").string(), m, {}, VtuEncoding::Ascii);
  write_vtk((d / "m.vtk").string(), m, false);
  write_vtk((d / "mb.vtk").string(), m, true);
  for (const char* name : {"m.vtu", "ma.vtu", "m.vtk", "mb.vtk"}) {
    const std::string file = name;
    CAPTURE(file);
    volmap_test::MeshioSummary s;
    REQUIRE(volmap_test::meshio_summary(py, d.string(), (d / name).string(), s));
    volmap_test::check_meshio_summary(s, m);
  }
}

TEST_CASE("third-party writer: files written by meshio are read back exactly") {
  const std::string py = volmap_test::meshio_python();
  if (py.empty()) {
    MESSAGE("skipped: Python meshio not available");
    return;
  }
  VOLMAP_REQUIRE_DATA(bone, "volmap/G1/bone.mesh");
  const TetMeshData m = read_medit(bone.string());
  const fs::path d = scratch_dir();
  write_vtu((d / "src.vtu").string(), m);
  const std::string script =
      "import sys, meshio\n"
      "m = meshio.read(sys.argv[1])\n"
      "d = sys.argv[2]\n"
      "meshio.write(d + '/mio_bin.vtu', m, binary=True, compression=None)\n"
      "meshio.write(d + '/mio_asc.vtu', m, binary=False)\n"
      "meshio.write(d + '/mio_zlib.vtu', m)\n"
      "meshio.write(d + '/mio_bin.vtk', m, binary=True)\n"
      "meshio.write(d + '/mio_asc.vtk', m, binary=False)\n"
      "meshio.write(d + '/mio.mesh', m)\n";
  { std::ofstream(d / "write.py") << script; }
  REQUIRE(run(py + " " + quoted(d / "write.py") + " " + quoted(d / "src.vtu") + " " + quoted(d)) == 0);
  // meshio's ascii .vtu prints 12 significant digits (lossy on its side): compared to 1e-10 below.
  for (const char* name : {"mio_bin.vtu", "mio_bin.vtk", "mio_asc.vtk", "mio.mesh"}) {
    const std::string file = name;
    CAPTURE(file);
    const TetMeshData r = read_tet_mesh((d / name).string());
    CHECK(r.xyz.size() == m.xyz.size());
    CHECK(std::memcmp(r.xyz.data(), m.xyz.data(), 8 * m.xyz.size()) == 0);
    CHECK(r.tets == m.tets);
  }
  const TetMeshData a = read_vtu((d / "mio_asc.vtu").string());
  REQUIRE(a.xyz.size() == m.xyz.size());
  std::size_t far = 0;
  for (std::size_t i = 0; i < m.xyz.size(); ++i) far += std::fabs(a.xyz[i] - m.xyz[i]) > 1e-10 * (1 + std::fabs(m.xyz[i]));
  CHECK(far == 0);
  CHECK(a.tets == m.tets);
  // meshio compresses .vtu with zlib by default: rejected as Unsupported, not misread.
  try {
    read_vtu((d / "mio_zlib.vtu").string());
    FAIL("compressed vtu accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Unsupported);
  }
}
