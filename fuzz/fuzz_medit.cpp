// libFuzzer target: Medit .mesh reader, then the writer and a re-read of what it wrote must agree.
#include "fuzz_common.hpp"

#include <volmap/io/io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return volmap_fuzz::fuzz_reader(data, size, ".mesh", [](const std::string& path) {
    const auto mesh = volmap::read_medit(path);
    const std::string copy = volmap_fuzz::scratch_path("_copy.mesh");
    volmap::write_medit(copy, mesh);
    const auto again = volmap::read_medit(copy);
    if (again.tets != mesh.tets || again.tet_labels != mesh.tet_labels || again.vertex_labels != mesh.vertex_labels)
      __builtin_trap();
    for (std::size_t i = 0; i < mesh.xyz.size(); ++i)
      if (!(again.xyz[i] == mesh.xyz[i])) __builtin_trap();  // bit-exact round trip (no NaN accepted)
  });
}
