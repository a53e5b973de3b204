// Atomic outputs (atomic_file.hpp): a temporary file beside the destination, renamed into place
// (rename is atomic on POSIX). Transactions keep hard-link backups of the destinations they replace
// until every rename has succeeded, so a failed rename can restore the earlier ones.
#include <volmap/io/atomic_file.hpp>
#include <volmap/io/temp_cleanup.hpp>
#include <volmap/core/error.hpp>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace volmap {
namespace {

namespace fs = std::filesystem;
std::atomic<unsigned> g_counter{0};

const char* file_type_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// The file a rename must replace: the destination itself, or what its symlink chain points to.
std::string resolve_target(const std::string& destination) {
  std::error_code ec;
  if (!fs::is_symlink(fs::symlink_status(destination, ec))) return destination;
  const fs::path resolved = fs::weakly_canonical(destination, ec);
  if (ec) throw_io(destination, "cannot resolve the symbolic link: " + ec.message());
  return resolved.string();
}

std::string temporary_name(const fs::path& target) {
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  return (dir / ("." + target.filename().string() + ".tmp." + std::to_string(::getpid()) + "." +
                 std::to_string(g_counter++)))
      .string();
}

}  // namespace

AtomicOutput::AtomicOutput(std::string destination) : destination_(std::move(destination)) {
  if (destination_.empty()) throw_io(destination_, "empty output path");
  target_ = resolve_target(destination_);
  struct stat st {};
  const bool exists = ::stat(target_.c_str(), &st) == 0;
  if (exists && !S_ISREG(st.st_mode))
    throw_io(destination_, std::string("is ") + file_type_name(st.st_mode) +
                               ": outputs replace only regular files or create new ones (refusing to write here)");
  const fs::path target(target_);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw_io(destination_, "output folder does not exist");
  if (target.filename().empty() || target.filename() == "." || target.filename() == "..")
    throw_io(destination_, "output path is a directory");
  temporary_ = temporary_name(target);
  registry_slot_ = register_temp_file(temporary_);
  const int fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int err = errno;
    unregister_temp_file(registry_slot_);
    registry_slot_ = -1;
    throw_io(destination_, std::string("cannot create output: ") + std::strerror(err));
  }
  if (exists) (void)::fchmod(fd, st.st_mode & 07777);  // a replaced file keeps its permissions
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int err = errno;
    ::close(fd);
    discard();
    throw_io(destination_, std::string("cannot create output: ") + std::strerror(err));
  }
}

AtomicOutput::~AtomicOutput() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  if (!committed_) discard();
}

void AtomicOutput::discard() {
  if (!temporary_.empty() && registry_slot_ != -2) ::unlink(temporary_.c_str());
  unregister_temp_file(registry_slot_);
  registry_slot_ = -2;  // removed (or renamed): nothing left to clean up
}

void AtomicOutput::drop() {
  if (committed_) return;
  if (file_) std::fclose(file_);
  file_ = nullptr;
  discard();
  dropped_ = true;
}

void AtomicOutput::finish() {
  if (!file_) return;
  bool ok = std::fflush(file_) == 0 && !std::ferror(file_);
  ok = (std::fclose(file_) == 0) && ok;
  file_ = nullptr;
  if (!ok) {
    discard();
    throw_io(destination_, "write failed (disk full?)");
  }
}

void AtomicOutput::commit() {
  if (committed_ || dropped_) return;
  finish();
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
    const int err = errno;
    discard();
    throw_io(destination_, std::string("cannot rename output into place: ") + std::strerror(err));
  }
  committed_ = true;
  unregister_temp_file(registry_slot_);
  registry_slot_ = -2;
}

AtomicOutput& OutputTransaction::add(const std::string& destination) {
  outputs_.push_back(std::make_unique<AtomicOutput>(destination));
  return *outputs_.back();
}

void OutputTransaction::commit() {
  std::vector<AtomicOutput*> outputs;  // the ones not dropped
  for (auto& out : outputs_)
    if (!out->dropped()) outputs.push_back(out.get());
  for (AtomicOutput* out : outputs) out->finish();
  CommitGuard no_signals_until_done;
  // Backups of the destinations about to be replaced (hard links: no copy). A destination that
  // exists but cannot be linked (e.g. a filesystem without hard links) cannot be restored: such
  // outputs are renamed last, after every restorable one has succeeded.
  const std::size_t n = outputs.size();
  std::vector<std::string> backups(n);
  std::vector<bool> existed(n, false);
  std::vector<std::size_t> order, unrestorable;
  for (std::size_t k = 0; k < n; ++k) {
    const std::string& target = outputs[k]->target();
    existed[k] = ::access(target.c_str(), F_OK) == 0;
    if (existed[k]) {
      const std::string backup = outputs[k]->temporary_path() + ".old";
      if (::link(target.c_str(), backup.c_str()) != 0) {
        unrestorable.push_back(k);
        continue;
      }
      backups[k] = backup;
    }
    order.push_back(k);
  }
  order.insert(order.end(), unrestorable.begin(), unrestorable.end());
  auto remove_backups = [&] {
    for (std::string& b : backups)
      if (!b.empty()) ::unlink(b.c_str()), b.clear();
  };
  std::size_t done = 0;
  try {
    for (; done < n; ++done) outputs[order[done]]->commit();
  } catch (...) {
    for (std::size_t i = 0; i < done; ++i) {  // undo: the earlier outputs go back to what they were
      const std::size_t k = order[i];
      const std::string& target = outputs[k]->target();
      if (!backups[k].empty()) {
        if (std::rename(backups[k].c_str(), target.c_str()) == 0) backups[k].clear();
      } else if (!existed[k]) {
        ::unlink(target.c_str());
      }
    }
    remove_backups();
    throw;
  }
  remove_backups();
}

void write_text(AtomicOutput& out, const std::string& content) {
  if (!content.empty() && std::fwrite(content.data(), 1, content.size(), out.file()) != content.size())
    throw_io(out.destination(), "write failed (disk full?)");
}

void write_text_atomically(const std::string& destination, const std::string& content) {
  AtomicOutput out(destination);
  write_text(out, content);
  out.commit();
}

}  // namespace volmap
