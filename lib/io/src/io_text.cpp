// Shared text IO helpers (see io_text.hpp): file loading, strict number parsing, buffered writing.
#include "io_text.hpp"

#include <volmap/io/io.hpp>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>

namespace volmap {

std::string read_text_file(const std::string& path, std::size_t max_line_bytes) {
  io_detail::ReadOptions options;
  options.text = true;
  options.max_line = max_line_bytes;
  return io_detail::read_whole_file(path, options);
}

}  // namespace volmap

namespace volmap::io_detail {

namespace {

// Vets the bytes [from, data.size()) of a file being read (see ReadOptions). `line_start` is the
// offset where the current line began; `line` its 1-based number.
void vet_block(const std::string& path, const std::string& data, std::size_t from, const ReadOptions& options,
               std::size_t& line_start, std::size_t& line) {
  const std::size_t prefix_end = std::min(data.size(), options.text_prefix);
  if (from < prefix_end && std::memchr(data.data() + from, '\0', prefix_end - from))
    throw_bad_input(path, 0, "binary data (a NUL byte) in the header: not a file of this format");
  if (options.max_line == 0) {  // fast path: only NUL bytes matter
    const void* nul = options.text ? std::memchr(data.data() + from, '\0', data.size() - from) : nullptr;
    if (nul)
      throw_bad_input(path, 0, "binary data (a NUL byte at offset " +
                                   std::to_string(static_cast<const char*>(nul) - data.data()) + "): not a text file");
    return;
  }
  for (std::size_t k = from; k < data.size(); ++k) {
    const char c = data[k];
    if (c == '\n') {
      ++line;
      line_start = k + 1;
    } else if (c == '\0' && options.text) {
      throw_bad_input(path, line, "binary data (a NUL byte at offset " + std::to_string(k) + "): not a text file");
    } else if (options.max_line && k - line_start >= options.max_line) {
      throw_bad_input(path, line, "line longer than " + std::to_string(options.max_line) + " bytes: not a file of this format");
    }
  }
}

}  // namespace

std::string read_whole_file(const std::string& path, const ReadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) throw_io(path, "is a directory, not a file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw_io(path, std::string("cannot open: ") + std::strerror(errno));
  struct Closer {
    std::FILE* f;
    ~Closer() { std::fclose(f); }
  } closer{f};
  const bool regular = fs::is_regular_file(status);
  const std::uintmax_t announced = regular ? fs::file_size(path, ec) : 0;
  const std::size_t limit = regular ? std::numeric_limits<std::size_t>::max() : kMaxStreamBytes;
  std::string data;
  std::size_t line_start = 0, line = 1;
  bool sized = false;
  try {
    // Blocks of 64 KiB, each vetted as it arrives; once the first block passed, a regular file's
    // announced size is allocated at once.
    constexpr std::size_t kBlock = 1 << 16;
    while (true) {
      if (!sized && data.size() >= kBlock && announced > data.size()) {
        data.reserve(static_cast<std::size_t>(announced) + 1);
        sized = true;
      }
      const std::size_t before = data.size();
      const std::size_t want = sized && announced > before ? static_cast<std::size_t>(announced) - before : kBlock;
      data.resize(before + std::max<std::size_t>(want, 1));
      const std::size_t got = std::fread(data.data() + before, 1, data.size() - before, f);
      data.resize(before + got);
      if (got == 0) break;
      if (options.strip_bom && before == 0 && data.size() >= 3 && data.compare(0, 3, "\xEF\xBB\xBF") == 0) {
        data.erase(0, 3);  // a UTF-8 byte-order mark carries nothing
      }
      vet_block(path, data, std::min(before, data.size()), options, line_start, line);
      if (data.size() > limit)
        throw_io(path, "is a stream longer than " + std::to_string(limit >> 20) + " MiB: refusing to read more");
    }
  } catch (const std::bad_alloc&) {
    throw_io(path, "out of memory after reading " + std::to_string(data.size()) + " bytes (file too large)");
  }
  if (std::ferror(f)) throw_io(path, "read error");
  return data;
}

namespace {
FileBytes copy_to_file_bytes(const std::string& data) {
  FileBytes f{HugeBuffer<char>(data.size()), data.size()};
  std::copy(data.begin(), data.end(), f.bytes.data());
  return f;
}
}  // namespace

FileBytes read_file_bytes(const std::string& path, const ReadOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw_io(path, "is a directory, not a file");
  const auto size = std::filesystem::file_size(path, ec);
  // Pipes, special files, empty files and line-length limits: the general reader, then one copy.
  if (ec || size == 0 || options.max_line != 0) return copy_to_file_bytes(read_whole_file(path, options));
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw_io(path, std::string("cannot open: ") + std::strerror(errno));
  // One more byte than announced: a file that grew since the size query is detected and re-read.
  FileBytes f{HugeBuffer<char>(static_cast<std::size_t>(size) + 1), 0};
  f.size = std::fread(f.bytes.data(), 1, static_cast<std::size_t>(size) + 1, file);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) throw_io(path, "read error");
  if (f.size > size) return copy_to_file_bytes(read_whole_file(path, options));
  const char* data = f.bytes.data();
  if (options.strip_bom && f.size >= 3 && std::memcmp(data, "\xEF\xBB\xBF", 3) == 0) f.start = 3;
  const std::size_t prefix_end = std::min(f.size, f.start + options.text_prefix);
  if (std::memchr(data + f.start, '\0', prefix_end - f.start))
    throw_bad_input(path, 0, "binary data (a NUL byte) in the header: not a file of this format");
  if (options.text) {
    if (const void* nul = std::memchr(data + f.start, '\0', f.size - f.start))
      throw_bad_input(path, 0, "binary data (a NUL byte at offset " +
                                   std::to_string(static_cast<const char*>(nul) - data - f.start) + "): not a text file");
  }
  return f;
}

bool FileWindow::suits(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  return !ec && std::filesystem::is_regular_file(status) && std::filesystem::file_size(path, ec) > 0 && !ec;
}

FileWindow::FileWindow(const std::string& path, const ReadOptions& options, std::size_t window_bytes)
    : path_(path), options_(options), buffer_(std::max<std::size_t>(window_bytes, 4096)) {
  if (options.text_prefix != 0 || options.max_line != 0)
    throw Error(ErrorKind::Unsupported, path, 0, "internal: a file window vets text and byte-order marks only");
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw_io(path, std::string("cannot open: ") + std::strerror(errno));
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);  // a regular file (suits): its size or an error
  if (ec) throw_io(path, "is not a regular file");
  file_size_ = static_cast<std::size_t>(size);
}

FileWindow::~FileWindow() {
  if (file_) std::fclose(file_);
}

std::size_t FileWindow::remaining_after(const char* p) const {
  const std::size_t at = offset_ + static_cast<std::size_t>(p - buffer_.data());
  return std::max(file_size_, offset_ + filled_) - at;
}

// Appends what fits (growing the buffer when it is full) and vets it.
void FileWindow::read_more() {
  if (filled_ == buffer_.size()) {
    HugeBuffer<char> bigger(2 * buffer_.size());
    std::memcpy(bigger.data(), buffer_.data(), filled_);
    buffer_ = std::move(bigger);
  }
  const std::size_t got = std::fread(buffer_.data() + filled_, 1, buffer_.size() - filled_, file_);
  if (std::ferror(file_)) throw_io(path_, "read error");
  if (got == 0) {
    eof_ = true;
    return;
  }
  if (options_.text)
    if (const void* nul = std::memchr(buffer_.data() + filled_, '\0', got))
      throw_bad_input(path_, 0, "binary data (a NUL byte at offset " +
                                    std::to_string(offset_ + static_cast<std::size_t>(static_cast<const char*>(nul) - buffer_.data())) +
                                    "): not a text file");
  filled_ += got;
}

bool FileWindow::advance(const char* keep_from, const char*& begin, const char*& end) {
  const bool first = keep_from == nullptr;
  if (!first && eof_ && exposed_ == filled_) return false;  // nothing more in the file
  // Move the unconsumed bytes (from keep_from: the rest of the window, then the partial line after
  // it) to the front.
  const std::size_t keep_at = first ? 0 : static_cast<std::size_t>(keep_from - buffer_.data());
  std::memmove(buffer_.data(), buffer_.data() + keep_at, filled_ - keep_at);
  offset_ += keep_at;
  filled_ -= keep_at;
  exposed_ -= keep_at;
  std::size_t start = 0;
  while (true) {
    const std::size_t before = filled_;
    if (!eof_) read_more();
    if (first && offset_ == 0 && options_.strip_bom && filled_ >= 3 && std::memcmp(buffer_.data(), "\xEF\xBB\xBF", 3) == 0)
      start = 3;  // a UTF-8 byte-order mark carries nothing
    if (eof_) {
      exposed_ = filled_;
      break;
    }
    // Expose up to the last newline read, once there is one after what was exposed already.
    const char* data = buffer_.data();
    const void* last = memrchr(data + before, '\n', filled_ - before);
    if (last) {
      exposed_ = static_cast<std::size_t>(static_cast<const char*>(last) - data) + 1;
      break;
    }
  }
  begin = buffer_.data() + (first ? start : 0);
  end = buffer_.data() + exposed_;
  return true;
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
