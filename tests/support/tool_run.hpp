// Running the built volmap-* executables from tests: a child process with stdout/stderr captured, an
// alarm, a memory cap (RLIMIT_AS outside ASan; ASan's max_allocation_size_mb inside), peak RSS and
// exit status from wait4; folder listings and fingerprints to prove a run changed nothing it
// should not; the small Kuhn-grid mesh and identity boundary map the tool suites start from.
#pragma once

#include <volmap/core/boundary_faces.hpp>
#include <volmap/testing/generate.hpp>

#include "test_support.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define VOLMAP_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VOLMAP_TEST_ASAN 1
#endif
#endif

namespace volmap_test {

// How much slower the tools run under the sanitizers, loaded by a parallel ctest: a test whose
// verdict depends on what a run reaches within --time-limit scales its limit by this.
#ifdef VOLMAP_TEST_ASAN
constexpr double kToolSlowdown = 4;
#else
constexpr double kToolSlowdown = 1;
#endif

struct RunResult {
  bool signaled = false;
  int signal = 0;
  int exit_code = -1;
  long peak_rss_kb = 0;
  double seconds = 0;
  std::string out, err;
};

// Runs `argv` with stdout/stderr captured in `scratch`, a `alarm_s` alarm and (outside ASan) a 3 GiB
// address-space limit. `on_started(pid)` (optional) runs in the parent once the child has exec'd the
// tool (a close-on-exec pipe tells), e.g. to send it a signal.
inline RunResult run_tool_process(const std::vector<std::string>& argv, const std::filesystem::path& scratch,
                                  unsigned alarm_s = 120, const std::function<void(pid_t)>& on_started = {}) {
  const std::filesystem::path out_path = scratch / "stdout.txt", err_path = scratch / "stderr.txt";
  timeval start{};
  gettimeofday(&start, nullptr);
  int exec_pipe[2] = {-1, -1};
  if (pipe2(exec_pipe, O_CLOEXEC) != 0) exec_pipe[0] = exec_pipe[1] = -1;
  const pid_t pid = fork();
  if (pid == 0) {
    if (exec_pipe[0] >= 0) close(exec_pipe[0]);
    const int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(err, 2);
    alarm(alarm_s);
#ifdef VOLMAP_TEST_ASAN
    std::string asan = std::getenv("ASAN_OPTIONS") ? std::getenv("ASAN_OPTIONS") : "";
    asan += std::string(asan.empty() ? "" : ":") + "max_allocation_size_mb=2048:allocator_may_return_null=0";
    setenv("ASAN_OPTIONS", asan.c_str(), 1);
#else
    const rlimit limit{3ul << 30, 3ul << 30};
    setrlimit(RLIMIT_AS, &limit);
#endif
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  if (exec_pipe[1] >= 0) close(exec_pipe[1]);
  if (exec_pipe[0] >= 0) {
    char byte;
    while (read(exec_pipe[0], &byte, 1) < 0 && errno == EINTR) {
    }  // EOF: the write end closed at exec (or the child died)
    close(exec_pipe[0]);
  }
  if (on_started) on_started(pid);
  RunResult r;
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  timeval end{};
  gettimeofday(&end, nullptr);
  r.seconds = double(end.tv_sec - start.tv_sec) + 1e-6 * double(end.tv_usec - start.tv_usec);
  r.peak_rss_kb = usage.ru_maxrss;
  if (WIFSIGNALED(status)) {
    r.signaled = true;
    r.signal = WTERMSIG(status);
  } else {
    r.exit_code = WEXITSTATUS(status);
  }
  r.out = read_bytes(out_path);
  r.err = read_bytes(err_path);
  std::filesystem::remove(out_path);
  std::filesystem::remove(err_path);
  return r;
}

// Everything under `dir` (recursively), as sorted relative paths (symlinks not followed).
inline std::vector<std::string> listing(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec))
    names.push_back(it->path().lexically_relative(dir).string());
  std::sort(names.begin(), names.end());
  return names;
}

// Names, types, sizes and a content hash of every regular file under `dir`: equal fingerprints mean
// nothing was added, removed, replaced or modified (FIFOs and devices are recorded by type).
inline std::string fingerprint(const std::filesystem::path& dir) {
  std::string fp;
  for (const std::string& name : listing(dir)) {
    const auto p = dir / name;
    struct stat st {};
    if (lstat(p.c_str(), &st) != 0) continue;
    fp += name + " " + std::to_string(st.st_mode & S_IFMT);
    if (S_ISREG(st.st_mode)) {
      const std::string bytes = read_bytes(p);
      std::uint64_t h = 1469598103934665603ull;  // FNV-1a
      for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
      fp += " " + std::to_string(bytes.size()) + " " + std::to_string(h);
    }
    fp += "\n";
  }
  return fp;
}

// The n³ Kuhn grid of [0,n]³ (6 VOLMAP-positive tets per cube) as Medit text, and its identity
// boundary map (every boundary vertex at its own position).
struct GridFixture {
  volmap::TetMeshData mesh;
  std::vector<bool> boundary;
};

inline GridFixture kuhn_grid_fixture(int n) {
  GridFixture g{volmap::generate_kuhn_grid(std::size_t(n), std::size_t(n), std::size_t(n)), {}};
  for (std::size_t v = 0; v < g.mesh.num_vertices(); ++v) {
    bool on_boundary = false;
    for (int a = 0; a < 3; ++a) on_boundary = on_boundary || g.mesh.xyz[3 * v + a] == 0 || g.mesh.xyz[3 * v + a] == n;
    g.boundary.push_back(on_boundary);
  }
  return g;
}

inline std::string medit_text(const volmap::TetMeshData& m) {
  std::ostringstream s;
  s.precision(17);
  s << "MeshVersionFormatted 1\nDimension 3\nVertices\n" << m.num_vertices() << "\n";
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    s << m.xyz[3 * v] << " " << m.xyz[3 * v + 1] << " " << m.xyz[3 * v + 2] << " 0\n";
  s << "Tetrahedra\n" << m.num_tets() << "\n";
  for (std::size_t t = 0; t < m.num_tets(); ++t)
    s << m.tets[4 * t] + 1 << " " << m.tets[4 * t + 1] + 1 << " " << m.tets[4 * t + 2] + 1 << " " << m.tets[4 * t + 3] + 1
      << " 0\n";
  s << "End\n";
  return s.str();
}

inline std::string identity_map_text(const GridFixture& g) {
  std::ostringstream s;
  s.precision(17);
  for (std::size_t v = 0; v < g.boundary.size(); ++v)
    if (g.boundary[v]) s << v << " " << g.mesh.xyz[3 * v] << " " << g.mesh.xyz[3 * v + 1] << " " << g.mesh.xyz[3 * v + 2] << "\n";
  return s.str();
}

// The identity boundary map of any mesh: every boundary vertex at its own position.
inline std::string boundary_identity_map_text(const volmap::TetMeshData& m) {
  std::ostringstream s;
  s.precision(17);
  for (std::uint32_t v : volmap::boundary_vertex_ids(m))
    s << v << " " << m.xyz[3 * v] << " " << m.xyz[3 * v + 1] << " " << m.xyz[3 * v + 2] << "\n";
  return s.str();
}

// A fresh scratch tree of a tool suite, <tmp>/volmap_<tag>_<pid>: inputs in in/, outputs in out/,
// the captured stdout/stderr of each run in scratch/. Removed when the suite ends.
struct ToolTree {
  std::filesystem::path root, in, out, scratch;
  explicit ToolTree(const std::string& tag) {
    root = std::filesystem::temp_directory_path() / ("volmap_" + tag + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(root);
    in = root / "in", out = root / "out", scratch = root / "scratch";
    for (const auto& d : {in, out, scratch}) std::filesystem::create_directories(d);
  }
  ~ToolTree() { std::filesystem::remove_all(root); }
  ToolTree(const ToolTree&) = delete;
  ToolTree& operator=(const ToolTree&) = delete;
  void clear_out() const {
    std::filesystem::remove_all(out);
    std::filesystem::create_directories(out);
  }
};

// A character device at `path` for a tool to be given as an OUTPUT, which it must refuse. As root a
// private null device node (mknod 1,3), so a tool that wrongly replaces it destroys only this node,
// never the machine's /dev/null; otherwise a symbolic link to /dev/null (which only root can replace).
inline std::string output_device_target(const std::filesystem::path& path) {
  if (geteuid() != 0 || mknod(path.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
    std::filesystem::create_symlink("/dev/null", path);
  return path.string();
}

// True when one of the '|'-separated alternatives occurs in `text` (an empty list matches).
inline bool names_one_of(const std::string& text, const std::string& alternatives) {
  if (alternatives.empty()) return true;
  std::size_t start = 0;
  while (true) {
    const std::size_t bar = alternatives.find('|', start);
    const std::string name = alternatives.substr(start, bar == std::string::npos ? std::string::npos : bar - start);
    if (text.find(name) != std::string::npos) return true;
    if (bar == std::string::npos) return false;
    start = bar + 1;
  }
}

}  // namespace volmap_test
