// volmap/io/atomic_file.hpp — outputs are written atomically: to a temporary file in the destination's
// folder, then renamed over the destination on commit(). An AtomicOutput destroyed without commit()
// removes its temporary file, so an interrupted or failed writer never leaves a partial output.
#pragma once

#include <cstdio>
#include <string>

namespace volmap {

class AtomicOutput {
 public:
  // Opens "<dir>/.<name>.tmp.<pid>.<n>" for writing; throws Error(Io) when the folder is missing or
  // not writable.
  explicit AtomicOutput(std::string destination);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  std::FILE* file() { return file_; }
  const std::string& destination() const { return destination_; }
  // Flushes, checks every write succeeded, closes and renames onto the destination. Throws Error(Io).
  void commit();

 private:
  std::string destination_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

// Convenience: write a whole string atomically.
void write_text_atomically(const std::string& destination, const std::string& content);

}  // namespace volmap
