// Error formatting: "file:line: reason", "file: reason" or just "reason".
#include <volmap/core/error.hpp>

#include <utility>

namespace volmap {
namespace {
std::string format_error(const std::string& file, std::size_t line, const std::string& reason) {
  if (file.empty()) return reason;
  if (line == 0) return file + ": " + reason;
  return file + ":" + std::to_string(line) + ": " + reason;
}
}  // namespace

Error::Error(ErrorKind kind, std::string file, std::size_t line, std::string reason)
    : std::runtime_error(format_error(file, line, reason)),
      kind_(kind), file_(std::move(file)), line_(line), reason_(std::move(reason)) {}

Error::Error(ErrorKind kind, std::string reason) : Error(kind, std::string(), 0, std::move(reason)) {}

void throw_bad_input(const std::string& file, std::size_t line, const std::string& reason) {
  throw Error(ErrorKind::BadInput, file, line, reason);
}
void throw_io(const std::string& file, const std::string& reason) { throw Error(ErrorKind::Io, file, 0, reason); }

}  // namespace volmap
