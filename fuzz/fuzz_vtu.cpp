// libFuzzer target: VTK XML .vtu reader (ascii, base64, appended raw).
#include "fuzz_common.hpp"

#include <volmap/io/io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return volmap_fuzz::fuzz_reader(data, size, ".vtu", [](const std::string& path) { volmap::read_vtu(path); });
}
