// tetgen_child.cpp — TetGen in a forked child (conventions in tetgen_child.hpp).
#include "tetgen_child.hpp"

#include <volmap/core/error.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/predicates.hpp>

#include <tetgen.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace volmap {
namespace {

std::string tetgen_reason(int code) {
  switch (code) {
    case 1: return "TetGen ran out of memory";
    case 2: return "TetGen internal error";
    case 3: return "TetGen detected a self-intersection of the surface";
    case 4: return "TetGen detected a very small input feature (tolerance)";
    case 5: return "TetGen detected two very close input facets";
    case 10: return "TetGen detected an input error";
    default: return "TetGen failed with code " + std::to_string(code);
  }
}

// The child: runs TetGen and writes to `fd` a header {error code, points, tets}, then the points
// (3 doubles each) and the 0-based tet ids (4 int32 each). Never returns.
[[noreturn]] void tetgen_child(int fd, std::string switches, tetgenio& in) {
  const int null_fd = open("/dev/null", O_WRONLY);
  if (null_fd >= 0) dup2(null_fd, 1), dup2(null_fd, 2);
  auto write_all = [fd](const void* data, std::size_t bytes) {
    const char* p = static_cast<const char*>(data);
    while (bytes > 0) {
      const ssize_t w = write(fd, p, bytes);
      if (w <= 0) _exit(99);
      p += w;
      bytes -= static_cast<std::size_t>(w);
    }
  };
  tetgenio out;
  std::int64_t header[3] = {0, 0, 0};
  try {
    tetrahedralize(&switches[0], &in, &out);
  } catch (int code) {
    header[0] = code;
  } catch (...) {
    header[0] = 2;
  }
  if (header[0] != 0) {
    write_all(header, sizeof header);
    _exit(3);
  }
  header[1] = out.numberofpoints;
  header[2] = out.numberofcorners == 4 ? out.numberoftetrahedra : 0;
  write_all(header, sizeof header);
  write_all(out.pointlist, sizeof(REAL) * 3 * static_cast<std::size_t>(header[1]));
  for (std::int64_t i = 0; i < 4 * header[2]; ++i) {
    const std::int32_t id = out.tetrahedronlist[i] - out.firstnumber;
    write_all(&id, sizeof id);
  }
  _exit(0);
}

// Reads the child's pipe until the child closes it; false when `time_limit_seconds` (> 0) passed
// first. Closes `fd` either way.
bool read_until_closed(int fd, double time_limit_seconds, std::vector<char>& bytes) {
  const TimeBudget budget(time_limit_seconds);
  char buffer[1 << 16];
  for (;;) {
    if (budget.limited()) {
      pollfd p{fd, POLLIN, 0};
      const int ready = budget.expired() ? 0 : poll(&p, 1, int(std::ceil(std::min(budget.remaining(), 3600.0) * 1000)));
      if (ready < 0 && errno == EINTR) continue;
      if (ready == 0) {
        close(fd);
        return false;
      }
    }
    const ssize_t r = read(fd, buffer, sizeof buffer);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    bytes.insert(bytes.end(), buffer, buffer + r);
  }
  close(fd);
  return true;
}

// The child's bytes as a mesh, each tet checked exactly and turned VOLMAP-positive (TetGen's are all
// negative in that convention).
TetMeshData decode_child_output(const std::vector<char>& bytes, bool crashed) {
  std::int64_t header[3] = {-1, 0, 0};
  if (bytes.size() >= sizeof header) std::memcpy(header, bytes.data(), sizeof header);
  if (header[0] > 0) throw Error(ErrorKind::Failed, tetgen_reason(static_cast<int>(header[0])));
  if (crashed || header[0] < 0)
    throw Error(ErrorKind::Failed, "TetGen aborted on this surface (libtet aborts while cleaning up after an internal "
                "error; its fixed tolerances reject near-degenerate or badly scaled features)");
  const std::size_t np = static_cast<std::size_t>(header[1]), ntet = static_cast<std::size_t>(header[2]);
  if (ntet == 0) throw Error(ErrorKind::Failed, "TetGen produced no tetrahedra");
  if (bytes.size() != sizeof header + 24 * np + 16 * ntet)
    throw Error(ErrorKind::Failed, "TetGen's output was truncated");
  TetMeshData m;
  m.xyz.resize(3 * np);
  std::memcpy(m.xyz.data(), bytes.data() + sizeof header, 24 * np);
  m.vertex_labels.assign(np, 0);
  m.tets.resize(4 * ntet);
  m.tet_labels.assign(ntet, 0);
  const char* ids = bytes.data() + sizeof header + 24 * np;
  for (std::size_t t = 0; t < ntet; ++t) {
    std::uint32_t* q = &m.tets[4 * t];
    for (int k = 0; k < 4; ++k) {
      std::int32_t id;
      std::memcpy(&id, ids + 4 * (4 * t + k), 4);
      if (id < 0 || static_cast<std::size_t>(id) >= np)
        throw Error(ErrorKind::Failed, "TetGen returned a bad vertex id");
      q[k] = static_cast<std::uint32_t>(id);
    }
    const int sgn = orient3d(&m.xyz[3 * q[0]], &m.xyz[3 * q[1]], &m.xyz[3 * q[2]], &m.xyz[3 * q[3]]);
    if (sgn == 0) throw Error(ErrorKind::Failed, "TetGen produced a degenerate tet " + std::to_string(t));
    if (sgn < 0) std::swap(q[0], q[1]);  // odd permutation: VOLMAP-positive
  }
  return m;
}

}  // namespace

// Debian's libtet frees its pools twice when it throws an error (terminatetetgen() frees, then the
// unwinding destructor frees again), which crashes the whole process on bad input (typically
// self-intersecting surfaces). So TetGen runs in a child that sends its result through a pipe; a
// crash or an error code becomes Error(Failed) here.
TetMeshData run_tetgen_in_child(const std::string& switches, tetgenio& in, double time_limit_seconds) {
  int fds[2];
  if (pipe(fds) != 0) throw Error(ErrorKind::Failed, "cannot create a pipe for TetGen");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw Error(ErrorKind::Failed, "cannot fork for TetGen");
  }
  if (pid == 0) {
    close(fds[0]);
    tetgen_child(fds[1], switches, in);
  }
  close(fds[1]);
  std::vector<char> bytes;
  const bool finished = read_until_closed(fds[0], time_limit_seconds, bytes);
  if (!finished) kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!finished) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.3g", time_limit_seconds);
    throw Error(ErrorKind::Failed, std::string("TetGen did not finish within ") + limit + " s (stopped)");
  }
  return decode_child_output(bytes, WIFSIGNALED(status));
}

}  // namespace volmap
