// Shared text IO helpers (see io_text.hpp): file loading, strict number parsing, buffered writing.
#include "io_text.hpp"

#include <cerrno>
#include <charconv>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>

namespace volmap::io_detail {

std::string read_whole_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw_io(path, "is a directory, not a file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw_io(path, std::string("cannot open: ") + std::strerror(errno));
  std::string data;
  // One read of the announced size, then whatever else arrives (pipes, growing files).
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > 0) {
    data.resize(static_cast<std::size_t>(size));
    data.resize(std::fread(data.data(), 1, data.size(), f));
  }
  char chunk[1 << 16];
  std::size_t got;
  while ((got = std::fread(chunk, 1, sizeof chunk, f)) > 0) data.append(chunk, got);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw_io(path, "read error");
  return data;
}

FileBytes read_file_bytes(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw_io(path, "is a directory, not a file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size == 0) {  // pipes, special files, empty files: the general reader, then one copy
    const std::string data = read_whole_file(path);
    FileBytes f{HugeBuffer<char>(data.size()), data.size()};
    std::copy(data.begin(), data.end(), f.bytes.data());
    return f;
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw_io(path, std::string("cannot open: ") + std::strerror(errno));
  // One more byte than announced: a file that grew since the size query is detected and re-read.
  FileBytes f{HugeBuffer<char>(static_cast<std::size_t>(size) + 1), 0};
  f.size = std::fread(f.bytes.data(), 1, static_cast<std::size_t>(size) + 1, file);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) throw_io(path, "read error");
  if (f.size > size) {
    const std::string data = read_whole_file(path);
    f = FileBytes{HugeBuffer<char>(data.size()), data.size()};
    std::copy(data.begin(), data.end(), f.bytes.data());
  }
  return f;
}

bool parse_double(std::string_view text, double& value) {
  if (text.empty() || text.size() > kMaxNumberChars) return false;
  if (text[0] == '+') {
    text.remove_prefix(1);
    if (text.empty() || text[0] == '-' || text[0] == '+') return false;
  }
  // from_chars also accepts "inf"/"nan": only digits, '.', '-' may start a number.
  const char c0 = text[0] == '-' && text.size() > 1 ? text[1] : text[0];
  if (!((c0 >= '0' && c0 <= '9') || c0 == '.')) return false;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto result = std::from_chars(first, last, value, std::chars_format::general);
  if (result.ec != std::errc() || result.ptr != last) return false;
  return std::isfinite(value);
}

bool Tokenizer::next_plain_double(double& value) {
  const char* p = pos_;
  std::size_t lines = 0;
  while (p != end_ && (*p == ' ' || *p == '\n')) lines += *p++ == '\n';
  if (p == end_) return false;
  const char c0 = *p == '-' && p + 1 != end_ ? p[1] : *p;
  if (!((c0 >= '0' && c0 <= '9') || c0 == '.')) return false;  // from_chars also takes inf/nan
  double v;
  const auto r = std::from_chars(p, end_, v, std::chars_format::general);
  if (r.ec != std::errc() || static_cast<std::size_t>(r.ptr - p) > kMaxNumberChars) return false;
  const char* stop = r.ptr;
  if (stop != end_ && *stop != ' ' && *stop != '\n') return false;
  if (!std::isfinite(v)) return false;
  value = v;
  pos_ = stop;
  line_ += lines;
  last_line_ = line_;
  return true;
}

std::string quote(std::string_view text) {
  std::string out = "'";
  const std::size_t n = std::min<std::size_t>(text.size(), 40);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
  }
  if (text.size() > n) out += "...(" + std::to_string(text.size()) + " chars)";
  return out + "'";
}

double expect_double(const Token& token, const std::string& path, const char* what) {
  double v;
  if (!parse_double(token.text, v)) {
    std::string reason = std::string(what) + ": expected a finite number, found " + quote(token.text);
    if (token.text.size() > kMaxNumberChars) reason = std::string(what) + ": number token too long";
    throw_bad_input(path, token.line, reason);
  }
  return v;
}

std::int64_t expect_int(const Token& token, const std::string& path, const char* what) {
  std::int64_t v;
  if (!parse_int64(token.text, v))
    throw_bad_input(path, token.line, std::string(what) + ": expected an integer, found " + quote(token.text));
  return v;
}

std::size_t expect_count(const Token& token, const std::string& path, const char* what, std::size_t remaining_bytes,
                         std::size_t min_bytes_each, std::size_t max_count) {
  const std::int64_t v = expect_int(token, path, what);
  if (v < 0) throw_bad_input(path, token.line, std::string(what) + ": negative count " + std::to_string(v));
  const auto n = static_cast<std::uint64_t>(v);
  if (n > max_count)
    throw_bad_input(path, token.line, std::string(what) + ": count " + std::to_string(n) + " exceeds the supported maximum " +
                                          std::to_string(max_count));
  // The last element may lack its trailing separator: allow one byte of slack.
  if (min_bytes_each > 0 && n > (static_cast<std::uint64_t>(remaining_bytes) + 1) / min_bytes_each)
    throw_bad_input(path, token.line, std::string(what) + ": declared count " + std::to_string(n) +
                                          " cannot fit in the remaining " + std::to_string(remaining_bytes) +
                                          " bytes of the file (truncated or corrupt)");
  return static_cast<std::size_t>(n);
}

void check_mesh_writable(const TetMeshData& mesh, const std::string& path) {
  const std::size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  if (mesh.xyz.size() != 3 * nv || mesh.tets.size() != 4 * nt)
    throw Error(ErrorKind::BadInput, path, 0, "cannot write: xyz/tets array sizes are not multiples of 3/4");
  if (!mesh.vertex_labels.empty() && mesh.vertex_labels.size() != nv)
    throw Error(ErrorKind::BadInput, path, 0, "cannot write: vertex_labels has the wrong size");
  if (!mesh.tet_labels.empty() && mesh.tet_labels.size() != nt)
    throw Error(ErrorKind::BadInput, path, 0, "cannot write: tet_labels has the wrong size");
  for (std::size_t k = 0; k < mesh.tets.size(); ++k)
    if (mesh.tets[k] >= nv)
      throw Error(ErrorKind::BadInput, path, 0, "cannot write: tet " + std::to_string(k / 4) + " references vertex " +
                                                    std::to_string(mesh.tets[k]) + " >= " + std::to_string(nv));
  for (double c : mesh.xyz)
    if (!std::isfinite(c)) throw Error(ErrorKind::BadInput, path, 0, "cannot write: non-finite vertex coordinate");
}

void TextWriter::put_double(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  buffer_.append(buf, static_cast<std::size_t>(r.ptr - buf));
  maybe_flush();
}

void TextWriter::put_int(std::int64_t v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  buffer_.append(buf, static_cast<std::size_t>(r.ptr - buf));
  maybe_flush();
}

void TextWriter::put_fixed6(double v) {
  char buf[400];
  const int n = std::snprintf(buf, sizeof buf, "%f", v);
  if (n > 0) buffer_.append(buf, static_cast<std::size_t>(std::min(n, static_cast<int>(sizeof buf) - 1)));
  maybe_flush();
}

void TextWriter::flush() {
  if (!buffer_.empty()) std::fwrite(buffer_.data(), 1, buffer_.size(), out_.file());
  buffer_.clear();
}

}  // namespace volmap::io_detail
