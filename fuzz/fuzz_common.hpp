// Shared helpers of the libFuzzer targets: the file readers take paths, so each input is written to
// a per-process scratch file in /dev/shm (or /tmp) first. A target passes when the reader either
// returns or throws volmap::Error; any other exception, crash or sanitizer report is a finding.
#pragma once

#include <volmap/core/error.hpp>

#include <cstdint>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace volmap_fuzz {

inline std::string scratch_path(const char* extension) {
  static const std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
  return dir + "/volmap_fuzz_" + std::to_string(::getpid()) + extension;
}

inline std::string write_scratch(const std::uint8_t* data, std::size_t size, const char* extension) {
  const std::string path = scratch_path(extension);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) __builtin_trap();
  if (size) std::fwrite(data, 1, size, f);
  std::fclose(f);
  return path;
}

// Runs `read` on the input written with `extension`; volmap::Error is the expected rejection.
template <class Read>
int fuzz_reader(const std::uint8_t* data, std::size_t size, const char* extension, Read read) {
  const std::string path = write_scratch(data, size, extension);
  try {
    read(path);
  } catch (const volmap::Error&) {
  }
  return 0;
}

}  // namespace volmap_fuzz
