// Robustness: every prefix and many single-byte mutations of small valid files in each format must
// either parse or throw volmap::Error — never crash, hang or throw anything else. Deterministic.
#include <doctest/doctest.h>
#include "test_support.hpp"
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>
#include <volmap/io/io_surface.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <unistd.h>

using namespace volmap;
namespace fs = std::filesystem;

namespace {
fs::path scratch_dir() { return volmap_test::scratch_dir("io_fuzz"); }
std::string slurp(const std::string& p) { return volmap_test::read_bytes(p); }
TetMeshData small_mesh() {
  TetMeshData m;
  m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  m.tets = {0, 1, 2, 3, 4, 1, 3, 2};
  m.vertex_labels = {0, 1, 0, 0, 2};
  m.tet_labels = {3, 4};
  return m;
}
// Returns the number of inputs that parsed; fails the test on any non-volmap exception.
std::size_t hammer(const std::string& name, const std::string& bytes, const std::function<void(const std::string&)>& read) {
  const std::string p = (scratch_dir() / name).string();
  std::size_t parsed = 0;
  auto attempt = [&](const std::string& content) {
    { std::ofstream(p, std::ios::binary | std::ios::trunc) << content; }
    try {
      read(p);
      ++parsed;
    } catch (const Error&) {
    } catch (const std::exception& e) {
      FAIL_CHECK("non-volmap exception: " << e.what());
    }
  };
  for (std::size_t n = 0; n <= bytes.size(); ++n) attempt(bytes.substr(0, n));
  std::uint64_t state = 12345;
  const char replacements[] = {'\0', '\n', ' ', '-', '9', 'e', '.', '#', 'x', '\xff', '/', '<', '"'};
  for (int k = 0; k < 300; ++k) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    std::string m = bytes;
    if (m.empty()) break;
    m[(state >> 33) % m.size()] = replacements[(state >> 17) % sizeof replacements];
    attempt(m);
  }
  return parsed;
}
}  // namespace

TEST_CASE("fuzz: truncated and mutated tet mesh files never crash") {
  const TetMeshData m = small_mesh();
  const fs::path d = scratch_dir();
  write_medit((d / "s.mesh").string(), m);
  write_vtk((d / "a.vtk").string(), m, false);
  write_vtk((d / "b.vtk").string(), m, true);
  write_vtu((d / "r.vtu").string(), m, {{"e", {0.5, 1.5}}});
  write_vtu((d / "t.vtu").string(), m, {}, VtuEncoding::Ascii);
  write_msh((d / "a.msh").string(), m, MshEncoding::Ascii);
  write_msh((d / "b.msh").string(), m, MshEncoding::Binary);
  volmap_test::write_bytes(d / "t.ovm",
                           "OVM ASCII\nVertices\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nEdges\n6\n0 1\n1 2\n0 2\n0 3\n1 3\n2 3\n"
                           "Faces\n4\n3 0 2 5\n3 6 9 1\n3 4 10 7\n3 8 11 3\nPolyhedra\n1\n4 0 2 4 6\n");
  for (const char* f : {"s.mesh", "a.vtk", "b.vtk", "r.vtu", "t.vtu", "a.msh", "b.msh", "t.ovm"}) {
    const std::string file = f;
    CAPTURE(file);
    const std::string bytes = slurp((d / f).string());
    const std::string ext = fs::path(f).extension().string();
    const std::size_t parsed = hammer(std::string("fuzz") + ext, bytes, [](const std::string& p) { read_tet_mesh(p); });
    CHECK(parsed >= 1);  // at least the full file
  }
}

TEST_CASE("fuzz: maps, rationals and surfaces never crash") {
  const fs::path d = scratch_dir();
  hammer("fuzz_map.txt", "0 1 2 3\n1 0.5 -0 +1e2\n2 1 1 1\n", [](const std::string& p) { read_boundary_map(p); });
  hammer("fuzz_rat.txt", "1/3\n-2\n6064708513608651/140737488355328\n", [](const std::string& p) { read_rationals(p, 1); });
  SurfaceData s;
  s.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  s.tris = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  for (const char* ext : {".off", ".obj", ".ply"}) {
    write_surface((d / (std::string("s") + ext)).string(), s);
    hammer(std::string("fuzz_s") + ext, slurp((d / (std::string("s") + ext)).string()), [](const std::string& p) { read_surface(p); });
  }
}
