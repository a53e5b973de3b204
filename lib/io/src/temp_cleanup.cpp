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

struct Slot {
  std::atomic<int> state{0};
  char path[kPathBytes];
};
Slot g_slots[kSlots];

std::atomic<int> g_commits_in_progress{0};
std::atomic<int> g_deferred_signal{0};

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
  if (g_commits_in_progress.load() > 0) {
    g_deferred_signal.store(sig);
    return;
  }
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

CommitGuard::CommitGuard() { ++g_commits_in_progress; }

CommitGuard::~CommitGuard() {
  if (--g_commits_in_progress == 0)
    if (const int sig = g_deferred_signal.exchange(0)) die_of(sig);
}

}  // namespace volmap
