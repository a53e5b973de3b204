// libFuzzer target: triangle surfaces through read_surface, all four formats. The first byte picks
// the extension (.obj/.off/.stl/.ply), the rest is the file. A read must return a surface with ids in
// range and finite coordinates (read_surface's contract) or throw volmap::Error.
#include "fuzz_common.hpp"

#include <volmap/io/io_surface.hpp>

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[4] = {".obj", ".off", ".stl", ".ply"};
  const char* extension = kExtensions[data[0] & 3];
  return volmap_fuzz::fuzz_reader(data + 1, size - 1, extension, [](const std::string& path) {
    const auto surface = volmap::read_surface(path);
    if (surface.xyz.size() % 3 != 0 || surface.tris.size() % 3 != 0) __builtin_trap();
    for (const double c : surface.xyz)
      if (!std::isfinite(c)) __builtin_trap();
    for (const auto v : surface.tris)
      if (v >= surface.num_vertices()) __builtin_trap();
  });
}
