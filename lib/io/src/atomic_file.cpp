// Atomic outputs: temp file in the same folder + fsync-free rename (rename is atomic on POSIX).
#include <volmap/io/atomic_file.hpp>
#include <volmap/core/error.hpp>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace volmap {
namespace {
std::atomic<unsigned> g_counter{0};
}

AtomicOutput::AtomicOutput(std::string destination) : destination_(std::move(destination)) {
  namespace fs = std::filesystem;
  fs::path dest(destination_);
  fs::path dir = dest.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw_io(destination_, "output folder does not exist");
  if (fs::is_directory(dest, ec)) throw_io(destination_, "output path is a directory");
  temporary_ = (dir / ("." + dest.filename().string() + ".tmp." + std::to_string(::getpid()) + "." +
                       std::to_string(g_counter++)))
                   .string();
  file_ = std::fopen(temporary_.c_str(), "wb");
  if (!file_) throw_io(destination_, std::string("cannot create output: ") + std::strerror(errno));
}

AtomicOutput::~AtomicOutput() {
  if (file_) std::fclose(file_);
  if (!committed_) std::remove(temporary_.c_str());
}

void AtomicOutput::commit() {
  if (committed_) return;
  bool ok = std::fflush(file_) == 0 && !std::ferror(file_);
  ok = (std::fclose(file_) == 0) && ok;
  file_ = nullptr;
  if (!ok) {
    std::remove(temporary_.c_str());
    throw_io(destination_, "write failed (disk full?)");
  }
  if (std::rename(temporary_.c_str(), destination_.c_str()) != 0) {
    const int err = errno;
    std::remove(temporary_.c_str());
    throw_io(destination_, std::string("cannot rename output into place: ") + std::strerror(err));
  }
  committed_ = true;
}

void write_text_atomically(const std::string& destination, const std::string& content) {
  AtomicOutput out(destination);
  if (!content.empty()) std::fwrite(content.data(), 1, content.size(), out.file());
  out.commit();
}

}  // namespace volmap
