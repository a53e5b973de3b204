// libFuzzer target: Gmsh .msh reader (MSH 2.2 and 4.1, ASCII and binary).
#include "fuzz_common.hpp"

#include <volmap/io/io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return volmap_fuzz::fuzz_reader(data, size, ".msh", [](const std::string& path) { volmap::read_msh(path); });
}
