// libFuzzer target: rationals reader (the first byte picks the expected vertex count), then the
// writer and a re-read must give the same exact values.
#include "fuzz_common.hpp"

#include <volmap/io/io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t vertices = data[0] % 8;
  return volmap_fuzz::fuzz_reader(data + 1, size - 1, ".rat", [&](const std::string& path) {
    const auto values = volmap::read_rationals(path, vertices);
    const std::string copy = volmap_fuzz::scratch_path("_copy.rat");
    volmap::write_rationals(copy, values);
    if (volmap::read_rationals(copy, vertices) != values) __builtin_trap();
  });
}
