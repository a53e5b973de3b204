// The registry of temporary output files and the signal handlers that empty it (temp_cleanup.hpp).
// Slot states: 0 free, 1 being written (skipped by the handler), 2 holds a path.
#include <volmap/io/temp_cleanup.hpp>

#include <atomic>
#include <csignal>
#include <cstring>
#include <pthread.h>
#include <unistd.h>

namespace volmap {
namespace {

constexpr int kSlots = 256;
constexpr std::size_t kPathBytes = 4096;

// Constant-initialised (all zero, in .bss): a dynamic initialiser would touch all 256 pages of the
// registry at the start of every tool.
struct Slot {
  std::atomic<int> state{0};
  char path[kPathBytes] = {};
};
Slot g_slots[kSlots];

std::atomic<int> g_commits_in_progress{0};
std::atomic<int> g_deferred_signal{0};
// What a handler is doing: 0 nothing, 1 deciding between deferring and dying, 2 dying (removing the
// temporary files, then the default action). A handler announces itself before it looks at
// g_commits_in_progress, and a CommitGuard counts itself before it looks at the state (both
// sequentially consistent), so at least one sees the other: either the handler defers, or the
// guard waits for its verdict and, when it is dying, never starts renaming files that are being
// removed (the handler may run on another thread than the one committing).
std::atomic<int> g_handler_state{0};

static_assert(std::atomic<int>::is_always_lock_free, "signal-safe registry needs lock-free atomics");

[[noreturn]] void die_of(int sig) {
  remove_registered_temp_files();
  std::signal(sig, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  std::raise(sig);
  _exit(128 + sig);  // not reached: the default action of these signals terminates
}

extern "C" void on_terminating_signal(int sig) {
  // Only one handler decides: a second signal while one is deciding or dying (on another thread, or
  // nested: SA_NODEFER) leaves it to that one instead of resetting its state.
  int idle = 0;
  if (!g_handler_state.compare_exchange_strong(idle, 1)) return;
  if (g_commits_in_progress.load() > 0) {
    g_deferred_signal.store(sig);
    g_handler_state.store(0);
    return;
  }
  g_handler_state.store(2);
  die_of(sig);
}

}  // namespace

int register_temp_file(const std::string& path) noexcept {
  if (path.size() + 1 > kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].state.store(2);
      return i;
    }
  }
  return -1;
}

void unregister_temp_file(int slot) noexcept {
  if (slot >= 0 && slot < kSlots) g_slots[slot].state.store(0);
}

void remove_registered_temp_files() noexcept {
  for (Slot& s : g_slots)
    if (s.state.load() == 2) ::unlink(s.path);
}

void install_temp_cleanup_on_signals() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction action {};
    action.sa_handler = on_terminating_signal;
    sigemptyset(&action.sa_mask);
    // SA_NODEFER: the handler's raise() must not wait behind the signal being handled.
    action.sa_flags = SA_RESTART | SA_NODEFER;
    sigaction(sig, &action, nullptr);
  }
}

CommitGuard::CommitGuard() {
  ++g_commits_in_progress;
  int state;
  while ((state = g_handler_state.load()) == 1) {
  }
  if (state == 2)
    for (;;) ::pause();  // the handler removes the outputs and ends the process
}

CommitGuard::~CommitGuard() {
  if (--g_commits_in_progress == 0)
    if (const int sig = g_deferred_signal.exchange(0)) die_of(sig);
}

}  // namespace volmap
