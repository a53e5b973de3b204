// Library-level regression tests for reader findings of the fuzzers (fuzz/) and the bad-input corpus
// (test_bad_inputs.cpp): each case is a small file that once made a reader hang, allocate far more
// than the file size justifies, or crash; now it must throw volmap::Error naming the file.
#include <doctest/doctest.h>

#include <volmap/core/error.hpp>
#include <volmap/io/io_surface.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

fs::path write_temp(const std::string& name, const std::string& content) {
  const fs::path p = fs::temp_directory_path() / ("volmap_bad_readers_" + std::to_string(getpid()) + "_" + name);
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

std::string surface_error(const fs::path& p) {
  try {
    volmap::read_surface(p.string());
  } catch (const volmap::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("PLY: a huge face list size in a tiny file is refused before allocating (fuzz_surface timeout)") {
  // Found by fuzz_surface: a list size of ~1e9 resized an int64 vector (8 GB) before reading it.
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n";
  const auto ascii = write_temp("list.ply", header + "999999999 0 1 2\n");
  const std::string e = surface_error(ascii);
  CHECK(e.find("list size") != std::string::npos);
  CHECK(e.find(ascii.filename().string()) != std::string::npos);
  CHECK(e.find(":13:") != std::string::npos);  // the face line
  fs::remove(ascii);

  std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  binary += std::string(36, '\0');                   // 3 vertices
  binary += std::string("\x00\xca\x9a\x3b", 4);      // list size 1e9 (little endian)
  binary += std::string(12, '\0');
  const auto bin = write_temp("list_bin.ply", binary);
  CHECK(surface_error(bin).find("list size") != std::string::npos);
  fs::remove(bin);

  // Still fine: a list that fits.
  const auto good = write_temp("good.ply", header + "3 0 1 2\n");
  CHECK(volmap::read_surface(good.string()).num_triangles() == 1);
  fs::remove(good);
}

TEST_CASE("PLY: a face list entry far outside the integer range is refused (fuzz_surface UBSan finding)") {
  // Found by fuzz_surface: float-typed list entries of 3.7e29 were cast to int64 (undefined behaviour).
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n";
  const auto huge = write_temp("entry.ply", header + "3 0 1 3.66667e+29\n");
  CHECK(surface_error(huge).find("not an integer id") != std::string::npos);
  fs::remove(huge);
  const auto fraction = write_temp("fraction.ply", header + "3 0 1 1.5\n");
  CHECK(surface_error(fraction).find("not an integer id") != std::string::npos);
  fs::remove(fraction);
  const auto nan = write_temp("nan.ply", header + "3 0 1 nan\n");
  CHECK(!surface_error(nan).empty());
  fs::remove(nan);
}
