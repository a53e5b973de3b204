// libFuzzer target: custom domain files (volmap/domain.hpp read_custom_domain). A domain that is
// accepted must be consistent: one target per node, arcs between existing nodes, faces whose arc
// lists match their node lists, and an Euler characteristic of 2.
#include "fuzz_common.hpp"

#include <volmap/surface/domain.hpp>

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return volmap_fuzz::fuzz_reader(data, size, ".txt", [](const std::string& path) {
    const auto domain = volmap::read_custom_domain(path);
    const int n = static_cast<int>(domain.num_nodes());
    for (const auto& t : domain.targets)
      for (const double c : t)
        if (!std::isfinite(c)) __builtin_trap();
    for (const auto& a : domain.arcs)
      if (a.from < 0 || a.from >= n || a.to < 0 || a.to >= n || a.from == a.to) __builtin_trap();
    for (const auto& f : domain.faces) {
      if (f.nodes.size() < 3 || f.arcs.size() != f.nodes.size()) __builtin_trap();
      for (const int v : f.nodes)
        if (v < 0 || v >= n) __builtin_trap();
      for (const int a : f.arcs)
        if (a < 0 || a >= static_cast<int>(domain.arcs.size())) __builtin_trap();
    }
    if (n - static_cast<long>(domain.arcs.size()) + static_cast<long>(domain.faces.size()) != 2) __builtin_trap();
  });
}
