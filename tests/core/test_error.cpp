// Errors carry file, line and reason; atomic outputs never leave partial files.
#include <doctest/doctest.h>
#include <volmap/io/atomic_file.hpp>
#include <volmap/core/error.hpp>

#include <filesystem>
#include <fstream>

TEST_CASE("Error formats file:line: reason") {
  volmap::Error e(volmap::ErrorKind::BadInput, "a.mesh", 12, "bad count");
  CHECK(std::string(e.what()) == "a.mesh:12: bad count");
  CHECK(e.line() == 12);
  CHECK(e.kind() == volmap::ErrorKind::BadInput);
  volmap::Error nofile(volmap::ErrorKind::Failed, "oops");
  CHECK(nofile.file().empty());
  CHECK(nofile.line() == 0);
  CHECK(std::string(nofile.what()) == "oops");
}

TEST_CASE("AtomicOutput: nothing appears without commit, content appears with it") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "volmap_test_atomic";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path dest = dir / "out.txt";
  {
    volmap::AtomicOutput out(dest.string());
    std::fputs("partial", out.file());
  }  // destroyed without commit
  CHECK_FALSE(fs::exists(dest));
  CHECK(fs::is_empty(dir));
  volmap::write_text_atomically(dest.string(), "hello\n");
  std::ifstream in(dest);
  std::string line;
  std::getline(in, line);
  CHECK(line == "hello");
  CHECK_THROWS_AS(volmap::AtomicOutput((dir / "missing" / "x.txt").string()), volmap::Error);
  fs::remove_all(dir);
}
