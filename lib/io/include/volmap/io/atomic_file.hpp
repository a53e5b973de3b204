// volmap/io/atomic_file.hpp — outputs are written atomically: to a temporary file in the destination's
// folder, then renamed over the destination on commit(). An AtomicOutput destroyed without commit()
// removes its temporary file, so an interrupted or failed writer never leaves a partial output.
// Rules every output follows:
//   - the destination is a new path or an existing regular file (a symlink is followed: its target is
//     replaced, the link stays); a directory, FIFO, device or socket is refused, never replaced;
//   - the temporary file is created when the AtomicOutput is constructed, so a missing or read-only
//     folder is reported before any work is done;
//   - temporary files are listed in a process-wide registry that a signal handler can empty
//     (temp_cleanup.hpp): SIGINT/SIGTERM never leave one behind.
// OutputTransaction groups the outputs of one run: all of them are committed together or none is.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace volmap {

class AtomicOutput {
 public:
  // Creates "<dir>/.<name>.tmp.<pid>.<n>" beside the (symlink-resolved) destination. Throws Error(Io)
  // when the folder is missing or not writable, or the destination is not a regular file.
  explicit AtomicOutput(std::string destination);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  std::FILE* file() { return file_; }
  // The path as given (what messages name) and the file the rename will replace.
  const std::string& destination() const { return destination_; }
  const std::string& target() const { return target_; }
  const std::string& temporary_path() const { return temporary_; }
  // Flushes, checks every write succeeded and closes the temporary file (no rename). Throws Error(Io).
  void finish();
  // finish(), then renames onto the destination. Throws Error(Io).
  void commit();
  bool committed() const { return committed_; }
  // Gives the output up: the temporary file is removed and commit() (also a transaction's) does
  // nothing for it. For outputs prepared up front that the run turns out not to need.
  void drop();
  bool dropped() const { return dropped_; }

 private:
  void discard();  // removes the temporary file (idempotent)
  std::string destination_;
  std::string target_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
  int registry_slot_ = -1;
  bool committed_ = false;
  bool dropped_ = false;
};

// The outputs of one run, committed together. add() creates each temporary file at once (validating
// every output path before the work starts); commit() finishes all of them (dropped ones aside),
// then renames them into
// place with signals deferred; when a rename fails, the destinations already replaced are restored
// (from hard-link backups) or removed, so either every output appears or none does.
class OutputTransaction {
 public:
  OutputTransaction() = default;
  ~OutputTransaction() = default;
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  AtomicOutput& add(const std::string& destination);
  void commit();
  std::size_t size() const { return outputs_.size(); }

 private:
  std::vector<std::unique_ptr<AtomicOutput>> outputs_;
};

// Convenience: write a whole string atomically.
void write_text_atomically(const std::string& destination, const std::string& content);
// Writes a whole string into a prepared output (no commit).
void write_text(AtomicOutput& out, const std::string& content);

}  // namespace volmap
