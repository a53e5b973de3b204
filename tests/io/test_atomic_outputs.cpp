// Outputs and input vetting of lib/io: transactions commit all outputs or none (a failed rename
// restores what the earlier ones replaced), outputs never replace FIFOs, devices or directories, a
// symlinked destination keeps its link, output paths that name an input are refused, the signal
// registry removes temporary files, and text inputs are vetted as they arrive (NUL bytes, long
// lines, /dev/zero, a UTF-8 byte-order mark). STL is parsed here: counts, NaN corners, welding.
#include <doctest/doctest.h>

#include <volmap/core/error.hpp>
#include <volmap/io/atomic_file.hpp>
#include <volmap/io/io.hpp>
#include <volmap/io/io_surface.hpp>
#include <volmap/io/output_paths.hpp>
#include <volmap/io/temp_cleanup.hpp>

#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <filesystem>
#include <sys/stat.h>

namespace fs = std::filesystem;
using namespace volmap;

namespace {

struct Dir {
  fs::path path;
  explicit Dir(const std::string& tag) : path(volmap_test::scratch_dir("atomic_" + tag)) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Dir() { fs::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (const auto& e : fs::directory_iterator(path)) n.push_back(e.path().filename().string());
    std::sort(n.begin(), n.end());
    return n;
  }
};

ErrorKind kind_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.kind();
  }
  FAIL("no error");
  return ErrorKind::Failed;
}

}  // namespace

TEST_CASE("OutputTransaction: every output appears on commit, none before, none when one fails") {
  Dir d("tx");
  {
    OutputTransaction tx;
    write_text(tx.add(d / "a.txt"), "A");
    write_text(tx.add(d / "b.txt"), "B");
    // Before commit only hidden temporary files exist.
    for (const auto& n : d.names()) CHECK(n.find(".tmp.") != std::string::npos);
    tx.commit();
  }
  CHECK(d.names() == std::vector<std::string>{"a.txt", "b.txt"});
  CHECK(volmap_test::read_bytes(d / "a.txt") == "A");

  // The second rename fails (its destination became a directory after the transaction prepared it):
  // the first destination gets its old content back, a new one disappears, no temporary file stays.
  {
    OutputTransaction tx;
    write_text(tx.add(d / "a.txt"), "A2");
    write_text(tx.add(d / "new.txt"), "N");
    write_text(tx.add(d / "c.txt"), "C");
    fs::create_directories(d.path / "c.txt" / "blocker");
    CHECK_THROWS_AS(tx.commit(), Error);
  }
  CHECK(volmap_test::read_bytes(d / "a.txt") == "A");
  CHECK_FALSE(fs::exists(d / "new.txt"));
  CHECK(d.names() == std::vector<std::string>{"a.txt", "b.txt", "c.txt"});

  // A dropped output is not written; the others are.
  {
    OutputTransaction tx;
    AtomicOutput& kept = tx.add(d / "kept.txt");
    AtomicOutput& dropped = tx.add(d / "dropped.txt");
    write_text(kept, "K");
    dropped.drop();
    tx.commit();
  }
  CHECK(fs::exists(d / "kept.txt"));
  CHECK_FALSE(fs::exists(d / "dropped.txt"));
}

TEST_CASE("AtomicOutput: FIFOs, devices and directories are refused, symlinks keep pointing") {
  Dir d("targets");
  REQUIRE(mkfifo((d / "fifo").c_str(), 0644) == 0);
  CHECK(kind_of([&] { AtomicOutput out(d / "fifo"); }) == ErrorKind::Io);
  CHECK(fs::is_fifo(d / "fifo"));
  CHECK(kind_of([&] { AtomicOutput out("/dev/null"); }) == ErrorKind::Io);
  fs::create_symlink("/dev/null", d / "null.txt");
  CHECK(kind_of([&] { AtomicOutput out(d / "null.txt"); }) == ErrorKind::Io);
  CHECK(kind_of([&] { AtomicOutput out(d.path.string()); }) == ErrorKind::Io);
  // A symlink to a regular file: the file is replaced, the link stays a link.
  volmap_test::write_bytes(d.path / "target.txt", "old");
  fs::create_symlink("target.txt", d / "link.txt");
  write_text_atomically(d / "link.txt", "new");
  CHECK(fs::is_symlink(d / "link.txt"));
  CHECK(volmap_test::read_bytes(d / "target.txt") == "new");
  // A replaced file keeps its permissions.
  fs::permissions(d / "target.txt", fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  write_text_atomically(d / "target.txt", "newer");
  CHECK((fs::status(d / "target.txt").permissions() & fs::perms::all) ==
        (fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read));
}

TEST_CASE("check_output_path: an output naming an input or another output is refused") {
  Dir d("paths");
  volmap_test::write_bytes(d.path / "in.mesh", "x");
  fs::create_hard_link(d / "in.mesh", d / "hard.mesh");
  fs::create_symlink("in.mesh", d / "soft.mesh");
  const std::vector<NamedPath> inputs = {{d / "in.mesh", "input mesh"}};
  CHECK_THROWS_AS(check_output_path({d / "in.mesh", "output"}, inputs, {}), Error);
  CHECK_THROWS_AS(check_output_path({d / "hard.mesh", "output"}, inputs, {}), Error);
  CHECK_THROWS_AS(check_output_path({d / "soft.mesh", "output"}, inputs, {}), Error);
  CHECK_THROWS_AS(check_output_path({(d.path / "." / "in.mesh").string(), "output"}, inputs, {}), Error);
  // Two outputs that do not exist yet but name the same path.
  CHECK_THROWS_AS(check_output_path({(d.path / "sub" / ".." / "new.mesh").string(), "b"}, inputs, {{d / "new.mesh", "a"}}),
                  Error);
  CHECK_NOTHROW(check_output_path({d / "other.mesh", "output"}, inputs, {{d / "new.mesh", "a"}}));
  try {
    check_output_path({d / "in.mesh", "--fix output"}, inputs, {});
  } catch (const Error& e) {
    CHECK(e.file() == d / "in.mesh");
    CHECK(std::string(e.what()).find("same file as the input mesh") != std::string::npos);
  }
}

TEST_CASE("temporary files: registered paths are removed by the cleanup the signal handlers run") {
  Dir d("registry");
  {
    AtomicOutput out(d / "x.txt");
    CHECK(fs::exists(out.temporary_path()));
    remove_registered_temp_files();  // what SIGINT/SIGTERM do before dying
    CHECK_FALSE(fs::exists(out.temporary_path()));
  }
  const int slot = register_temp_file(d / "manual.tmp");
  volmap_test::write_bytes(d.path / "manual.tmp", "x");
  unregister_temp_file(slot);
  remove_registered_temp_files();
  CHECK(fs::exists(d / "manual.tmp"));  // unregistered: left alone
}

TEST_CASE("text inputs are vetted as they arrive: NUL bytes, long lines, streams, byte-order marks") {
  Dir d("vetting");
  const std::string nul = volmap_test::write_bytes(d.path / "nul.txt", std::string("0 1 2 3\n\0\0", 10));
  CHECK(kind_of([&] { read_boundary_map(nul); }) == ErrorKind::BadInput);
  const auto t0 = std::chrono::steady_clock::now();
  CHECK(kind_of([&] { read_boundary_map("/dev/zero"); }) == ErrorKind::BadInput);
  CHECK(kind_of([&] { read_text_file("/dev/zero"); }) == ErrorKind::BadInput);
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(2));
  const std::string long_line = volmap_test::write_bytes(d.path / "long.txt", "0 " + std::string(100000, '1') + " 2 3\n");
  try {
    read_boundary_map(long_line);
    FAIL("accepted");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("line longer than") != std::string::npos);
    CHECK(e.line() == 1);
  }
  CHECK(read_text_file(volmap_test::write_bytes(d.path / "bom.txt", "\xEF\xBB\xBFhello")) == "hello");
  const std::string bom_map = volmap_test::write_bytes(d.path / "bom_map.txt", "\xEF\xBB\xBF" "0 1 2 3\n");
  CHECK(read_boundary_map(bom_map).size() == 1);
  // A binary format: its text header is vetted (/dev/zero as .vtk is refused at once).
  fs::create_symlink("/dev/zero", d / "zero.vtk");
  CHECK(kind_of([&] { read_tet_mesh(d / "zero.vtk"); }) == ErrorKind::BadInput);
}

TEST_CASE("STL: binary count against size, non-finite corners, ASCII, welding in first-appearance order") {
  Dir d("stl");
  auto binary = [](std::uint32_t count, const std::vector<std::array<float, 9>>& tris) {
    std::string b(80, ' ');
    b.append(reinterpret_cast<const char*>(&count), 4);
    for (const auto& t : tris) {
      const float normal[3] = {0, 0, 0};
      b.append(reinterpret_cast<const char*>(normal), 12);
      b.append(reinterpret_cast<const char*>(t.data()), 36);
      b.append(2, '\0');
    }
    return b;
  };
  const std::array<float, 9> t0 = {0, 0, 0, 1, 0, 0, 0, 1, 0}, t1 = {1, 0, 0, 0, 0, 0, 0, 0, 1};
  const SurfaceData s = read_surface(volmap_test::write_bytes(d.path / "ok.stl", binary(2, {t0, t1})));
  CHECK(s.num_vertices() == 4);
  CHECK(s.tris == std::vector<std::uint32_t>{0, 1, 2, 1, 0, 3});
  try {
    read_surface(volmap_test::write_bytes(d.path / "short.stl", binary(3, {t0, t1})));
    FAIL("accepted");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("announces 3 triangles") != std::string::npos);
  }
  std::array<float, 9> poisoned = t1;
  poisoned[4] = std::nanf("");
  CHECK(kind_of([&] { read_surface(volmap_test::write_bytes(d.path / "nan.stl", binary(2, {t0, poisoned}))); }) ==
        ErrorKind::BadInput);
  const SurfaceData a = read_surface(volmap_test::write_bytes(
      d.path / "a.stl", "\xEF\xBB\xBFsolid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                        "endloop\nendfacet\nendsolid x\n"));
  CHECK(a.num_triangles() == 1);
  // write -> read keeps the triangles (float by format).
  write_surface(d / "rt.stl", s);
  const SurfaceData r = read_surface(d / "rt.stl");
  CHECK(r.tris == s.tris);
  CHECK(r.xyz == s.xyz);
}
