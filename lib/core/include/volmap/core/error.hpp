// volmap/core/error.hpp — the one error type of the library.
// The library never prints, exits or asserts on bad input: it throws volmap::Error carrying the
// file (or "" when not file-related), the 1-based line (0 when unknown) and a one-line reason.
// Errors about arrays, options or algorithms that know no file use Error(kind, reason); a tool that
// knows which file the arrays came from re-throws them naming it.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace volmap {

enum class ErrorKind {
  BadInput,  // malformed or inconsistent input (tools: exit 2)
  Io,        // cannot open / read / write a path (tools: exit 2)
  Unsupported,  // valid input outside what we handle (tools: exit 2)
  Failed     // an algorithm ran but could not produce a result (tools: exit 1)
};

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, std::string file, std::size_t line, std::string reason);
  // An error that names no file (file "" and line 0).
  Error(ErrorKind kind, std::string reason);
  ErrorKind kind() const { return kind_; }
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  const std::string& reason() const { return reason_; }

 private:
  ErrorKind kind_;
  std::string file_;
  std::size_t line_;
  std::string reason_;
};

// Shorthands: throw a BadInput error at file:line.
[[noreturn]] void throw_bad_input(const std::string& file, std::size_t line, const std::string& reason);
[[noreturn]] void throw_io(const std::string& file, const std::string& reason);

}  // namespace volmap
