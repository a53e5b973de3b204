// volmap/io/temp_cleanup.hpp — the process-wide registry of temporary output files, emptied on
// SIGINT/SIGTERM/SIGHUP so an interrupted run leaves no temporary file behind.
// The registry is a fixed array of path slots with atomic states (no allocation, no locks), so
// remove_registered_temp_files() is async-signal-safe (it only calls unlink). AtomicOutput registers
// its temporary path before creating the file and unregisters it after the rename or removal.
// While an OutputTransaction renames its files, a signal is deferred (CommitGuard) and re-raised
// when the renames are done: a run is either interrupted before any output appears or after all.
// The library installs no handler by itself: tools call install_temp_cleanup_on_signals().
#pragma once

#include <string>

namespace volmap {

// Returns a slot id (or -1 when the registry is full: the file is then not cleaned up on signals).
int register_temp_file(const std::string& path) noexcept;
void unregister_temp_file(int slot) noexcept;
// Unlinks every registered file. Async-signal-safe.
void remove_registered_temp_files() noexcept;

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the registered files and then die of
// the same signal (default action re-raised). Idempotent.
void install_temp_cleanup_on_signals();

// While alive, the handlers above defer a signal instead of acting; the destructor acts on a deferred
// signal (cleanup, then the default action). A guard made while a handler (on any thread) is already
// removing the files and ending the process blocks until the process ends.
class CommitGuard {
 public:
  CommitGuard();
  ~CommitGuard();
  CommitGuard(const CommitGuard&) = delete;
  CommitGuard& operator=(const CommitGuard&) = delete;
};

}  // namespace volmap
