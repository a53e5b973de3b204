// tools/support/process.hpp — run a child process with a wall-clock timeout and measure it.
// Used by the benchmark runner to run candidate mappers that may hang or crash: the child gets its
// own process group (killed as a whole on timeout), stdout/stderr go to files, and the result
// records exit code, terminating signal, wall time and peak resident memory.
#pragma once

#include <atomic>
#include <string>
#include <vector>

namespace volmap {

struct ProcessResult {
  bool started = false;      // false when the executable could not be spawned
  std::string spawn_error;   // reason when !started
  int exit_code = -1;        // valid when the child exited normally
  int term_signal = 0;       // non-zero when the child was killed by a signal
  bool timed_out = false;    // true when we killed it at the deadline
  double seconds = 0.0;      // wall-clock time
  double peak_rss_mb = 0.0;  // ru_maxrss of the child
  double cpu_seconds = 0.0;  // user + system CPU time of the child (its waited-for descendants too)
};

// Runs argv[0] (searched in PATH when it has no '/') with argv; stdout and stderr are redirected to
// the given files ("" = /dev/null). timeout_seconds <= 0 means no limit. While the child runs, its
// pid (= its process group id) is stored in *running_pid when given (0 otherwise), so a signal
// handler can kill(-pid, SIGKILL) children of an interrupted runner. `extra_env` entries
// ("NAME=value") are added to (or override) the child's copy of this process's environment.
ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds,
                          const std::string& stdout_path = "", const std::string& stderr_path = "",
                          std::atomic<int>* running_pid = nullptr,
                          const std::vector<std::string>& extra_env = {});

}  // namespace volmap
