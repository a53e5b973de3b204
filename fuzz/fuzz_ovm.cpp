// libFuzzer target: OpenVolumeMesh .ovm (text) reader.
#include "fuzz_common.hpp"

#include <volmap/io/io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return volmap_fuzz::fuzz_reader(data, size, ".ovm", [](const std::string& path) { volmap::read_ovm(path); });
}
