// Child processes with timeouts: posix_spawn (thread-safe, unlike fork in a threaded runner),
// a new process group per child so a timeout kills its whole tree, wait4 for exit status + rusage.
#include "support/process.hpp"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace volmap {

ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds,
                          const std::string& stdout_path, const std::string& stderr_path,
                          std::atomic<int>* running_pid, const std::vector<std::string>& extra_env) {
  ProcessResult result;
  if (argv.empty()) {
    result.spawn_error = "empty command";
    return result;
  }
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  // The child's environment: ours minus names overridden by extra_env, then extra_env. Built
  // per call (setenv in a threaded runner would race between workers).
  std::vector<char*> envp;
  for (char** e = environ; *e; ++e) {
    const char* eq = std::strchr(*e, '=');
    const std::size_t name_length = eq ? static_cast<std::size_t>(eq - *e) : std::strlen(*e);
    bool overridden = false;
    for (const auto& extra : extra_env)
      if (extra.size() > name_length && extra[name_length] == '=' && extra.compare(0, name_length, *e, name_length) == 0)
        overridden = true;
    if (!overridden) envp.push_back(*e);
  }
  for (const auto& extra : extra_env) envp.push_back(const_cast<char*>(extra.c_str()));
  envp.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  const std::string out = stdout_path.empty() ? "/dev/null" : stdout_path;
  const std::string err = stderr_path.empty() ? "/dev/null" : stderr_path;
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);

  const auto start = std::chrono::steady_clock::now();
  pid_t pid = -1;
  const int rc = argv[0].find('/') == std::string::npos
                     ? posix_spawnp(&pid, args[0], &actions, &attr, args.data(), envp.data())
                     : posix_spawn(&pid, args[0], &actions, &attr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    result.spawn_error = std::string("cannot start ") + argv[0] + ": " + std::strerror(rc);
    return result;
  }
  result.started = true;
  if (running_pid) running_pid->store(pid);

  int status = 0;
  rusage usage{};
  auto sleep_for = std::chrono::milliseconds(2);
  for (;;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) break;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (timeout_seconds > 0 && elapsed > timeout_seconds) {
      result.timed_out = true;
      kill(-pid, SIGKILL);  // the whole process group
      while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
      }
      break;
    }
    std::this_thread::sleep_for(sleep_for);
    if (sleep_for < std::chrono::milliseconds(50)) sleep_for *= 2;
  }
  if (running_pid) running_pid->store(0);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  result.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);  // 127: glibc's spawn could not exec the program
  } else if (WIFSIGNALED(status)) {
    result.term_signal = WTERMSIG(status);
  }
  return result;
}

}  // namespace volmap
