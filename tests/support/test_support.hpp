// Helpers shared by tests: where the real data lives (../shared/data, read in place, never copied),
// where the built tools are, and per-process scratch folders (removed when the test process exits
// normally). Tests that need data call data_file() and skip when it is empty.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace volmap_test {

// Root of ../shared/data, overridable with the VOLMAP_DATA environment variable. Empty when absent.
inline std::filesystem::path data_root() {
  const char* env = std::getenv("VOLMAP_DATA");
  std::filesystem::path root = env && *env ? std::filesystem::path(env) : std::filesystem::path(VOLMAP_DATA_DIR);
  std::error_code ec;
  return std::filesystem::is_directory(root, ec) ? root : std::filesystem::path();
}

// Full path of a data file relative to the data root, or empty when the data (or the file) is absent.
inline std::filesystem::path data_file(const std::string& relative) {
  const auto root = data_root();
  if (root.empty()) return {};
  auto p = root / relative;
  std::error_code ec;
  return std::filesystem::exists(p, ec) ? p : std::filesystem::path();
}

// Path of a built tool (build/bin/volmap-*), or of the tool in VOLMAP_TOOL_DIR when that is set (to
// run the tool suites against other binaries, e.g. a build of main, and see which tests they fail).
inline std::filesystem::path tool(const std::string& name) {
  const char* env = std::getenv("VOLMAP_TOOL_DIR");
  return std::filesystem::path(env && *env ? env : VOLMAP_BIN_DIR) / name;
}

// The scratch folders of this process, removed when it exits normally: every ctest run used to
// leave its folders behind (1.1 GB in /tmp after a few days of runs). A crash skips the removal, so
// the files of a crashing test stay for a look; VOLMAP_KEEP_TEST_FILES=1 keeps them always.
class ScratchFolders {
 public:
  static ScratchFolders& instance() {
    static ScratchFolders folders;
    return folders;
  }
  void add(const std::filesystem::path& dir) {
    std::lock_guard<std::mutex> lock(mutex_);
    dirs_.push_back(dir);
  }
  ~ScratchFolders() {
    const char* keep = std::getenv("VOLMAP_KEEP_TEST_FILES");
    if (keep && *keep && std::string(keep) != "0") return;
    for (const auto& dir : dirs_) {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  }

 private:
  ScratchFolders() = default;
  std::mutex mutex_;
  std::vector<std::filesystem::path> dirs_;
};

// A per-process scratch folder for a test file's generated inputs: <tmp>/volmap_test_<tag>_<pid>,
// created when missing (its content is kept between calls in one process) and removed at exit.
inline std::filesystem::path scratch_dir(const std::string& tag) {
  auto d = std::filesystem::temp_directory_path() / ("volmap_test_" + tag + "_" + std::to_string(::getpid()));
  if (!std::filesystem::exists(d)) ScratchFolders::instance().add(d);
  std::filesystem::create_directories(d);
  return d;
}

// The same folder emptied first.
inline std::filesystem::path fresh_scratch_dir(const std::string& tag) {
  const auto d = scratch_dir(tag);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// Writes `bytes` to `path` (binary) and returns the path as a string.
inline std::string write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}

// A whole file as bytes ("" when it cannot be read).
inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace volmap_test

// Skip the current test case with a visible message when the shared data is missing.
#define VOLMAP_REQUIRE_DATA(path_var, relative)                                      \
  const auto path_var = volmap_test::data_file(relative);                            \
  if (path_var.empty()) {                                                            \
    MESSAGE("skipped: ../shared/data/" << (relative) << " is absent");               \
    return;                                                                          \
  }
