// libFuzzer target: building the half-face TetMesh from arbitrary TetMeshData. The bytes give a
// vertex count (1 byte) and then tets as 4 one-byte ids each (ids may exceed the vertex count on
// purpose); coordinates are a fixed small grid (topology is what is being fuzzed). The constructor
// must either throw volmap::Error or produce a mesh whose check_invariants() passes and whose
// to_data() gives the input arrays back.
#include <volmap/core/error.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  volmap::TetMeshData mesh;
  const std::size_t num_vertices = data[0] % 64;
  for (std::size_t v = 0; v < num_vertices; ++v) {
    mesh.xyz.push_back(double(v % 4));
    mesh.xyz.push_back(double((v / 4) % 4));
    mesh.xyz.push_back(double(v / 16));
  }
  mesh.vertex_labels.assign(num_vertices, 0);
  // Odd sizes leave a partial tet on purpose (sizes not a multiple of 4 must be refused).
  for (std::size_t i = 1; i < size; ++i) mesh.tets.push_back(data[i] % 72);
  mesh.tet_labels.assign(mesh.tets.size() / 4, 0);
  try {
    const volmap::TetMesh tet_mesh(mesh);
    const auto report = tet_mesh.check_invariants();
    if (!report.ok) __builtin_trap();
    // Without edits the flat arrays come back unchanged.
    const auto back = tet_mesh.to_data();
    if (back.tets != mesh.tets || back.xyz != mesh.xyz) __builtin_trap();
  } catch (const volmap::Error&) {
  }
  return 0;
}
