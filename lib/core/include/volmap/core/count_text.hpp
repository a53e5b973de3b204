// volmap/core/count_text.hpp — counts in messages meant for people: digits grouped by thousands
// ("6,059"), and "1 tet" / "2 tets" agreement.
#pragma once

#include <cstddef>
#include <string>

namespace volmap {

inline std::string grouped(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// "1 tet", "6,059 tets" (plural: the noun with an "s", unless given).
inline std::string count_of(std::size_t n, const std::string& noun, const std::string& plural = "") {
  return grouped(n) + " " + (n == 1 ? noun : (plural.empty() ? noun + "s" : plural));
}

}  // namespace volmap
