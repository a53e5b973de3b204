// libFuzzer target: boundary map reader + validation against a fixed one-tet mesh.
#include "fuzz_common.hpp"

#include <volmap/io/io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return volmap_fuzz::fuzz_reader(data, size, ".txt", [](const std::string& path) {
    const auto map = volmap::read_boundary_map(path);
    volmap::TetMeshData tet;
    tet.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    tet.vertex_labels = {0, 0, 0, 0};
    tet.tets = {0, 2, 1, 3};
    tet.tet_labels = {0};
    volmap::validate_boundary_map(map, tet, path);
  });
}
