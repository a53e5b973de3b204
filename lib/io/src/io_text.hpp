// io_text.hpp (private to lib/src) — shared machinery of the text readers and writers:
// whole-file loading, a whitespace tokenizer over a memory buffer that tracks 1-based line numbers,
// strict number parsing (std::from_chars; finite values only, whole token consumed, bounded length)
// and a buffered writer that prints doubles in shortest round-trip form (std::to_chars), so every
// double written is read back bit-exactly.
#pragma once

#include <volmap/io/atomic_file.hpp>
#include <volmap/core/error.hpp>
#include <volmap/core/huge_pages.hpp>
#include <volmap/core/mesh_data.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

namespace volmap::io_detail {

// Longest numeric token accepted (the exact decimal expansion of a double has at most ~770
// significant digits; longer tokens are rejected as malformed rather than parsed).
inline constexpr std::size_t kMaxNumberChars = 1100;

// How read_whole_file vets what it reads, before allocating for the rest of the file.
struct ReadOptions {
  bool text = false;             // a NUL byte anywhere is refused ("binary data in a text file")
  std::size_t text_prefix = 0;   // binary formats with a text header: no NUL in the first bytes
  std::size_t max_line = 0;      // longest line accepted (0 = unbounded)
  bool strip_bom = true;         // a leading UTF-8 byte-order mark is dropped
};
// Streams (FIFOs, character devices) are read up to this many bytes; larger ones are refused.
inline constexpr std::size_t kMaxStreamBytes = std::size_t(1) << 30;

// Reads a whole file. Throws Error(Io) when it is missing, a directory, unreadable or a stream
// longer than kMaxStreamBytes, Error(BadInput) when the content breaks `options` (checked as the
// bytes arrive, so /dev/zero or a huge sparse file is refused after its first block).
std::string read_whole_file(const std::string& path, const ReadOptions& options = {});

// The same into a buffer mapped before the read (huge_pages.hpp): no zero fill, no page faults (the
// large text readers' path), vetted by the same `options`. Bytes [start, size) of `bytes`.
struct FileBytes {
  HugeBuffer<char> bytes;
  std::size_t size = 0;
  std::size_t start = 0;  // past a stripped byte-order mark
  const char* begin() const { return bytes.data() + start; }
  const char* end() const { return bytes.data() + size; }
};
FileBytes read_file_bytes(const std::string& path, const ReadOptions& options = {});

// A regular file read through a window that slides over it, for readers whose memory should not
// grow with the file: the window holds whole lines only (it ends after a newline, or at the end of
// the file), and the Tokenizer built on it moves on to the next lines when it reaches the window's
// end while skipping whitespace (Tokenizer(FileWindow&, ...)). Bytes are vetted as `options` says
// (`text` and `strip_bom` only) as they arrive. A line longer than the window grows the window.
class FileWindow {
 public:
  // `path` must suit (below); a path that changed into something else since is refused as Io.
  FileWindow(const std::string& path, const ReadOptions& options, std::size_t window_bytes = kHugePageBytes);
  ~FileWindow();
  FileWindow(const FileWindow&) = delete;
  FileWindow& operator=(const FileWindow&) = delete;

  // Whether `path` can be read this way (a non-empty regular file); other files go through
  // read_file_bytes.
  static bool suits(const std::string& path);

  // Drops the bytes before `keep_from` (inside the current window; null for the first window, which
  // also skips a byte-order mark), reads on, and sets [begin, end) to the new window. Returns false,
  // leaving everything as it was, when the file has no bytes left.
  bool advance(const char* keep_from, const char*& begin, const char*& end);
  // Bytes of the file after `p` (a position in the current window), by its size when opened.
  std::size_t remaining_after(const char* p) const;

 private:
  void read_more();

  std::string path_;
  ReadOptions options_;
  std::FILE* file_ = nullptr;
  std::size_t file_size_ = 0;
  HugeBuffer<char> buffer_;
  std::size_t filled_ = 0;       // bytes of buffer_ holding file data
  std::size_t exposed_ = 0;      // bytes of buffer_ handed out (whole lines)
  std::size_t offset_ = 0;       // file offset of buffer_[0]
  bool eof_ = false;
};

struct Token {
  std::string_view text;
  std::size_t line = 0;  // 1-based line of the token's first character
};

inline bool is_space(char c) {
  // ' ' \t \n \v \f \r: one compare for the common printable case.
  const unsigned char u = static_cast<unsigned char>(c);
  return u == ' ' || (u >= '\t' && u <= '\r');
}
inline bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

// Whitespace tokenizer. With `hash_comments`, '#' starts a comment that runs to the end of the line.
class Tokenizer {
 public:
  Tokenizer(const char* begin, const char* end, bool hash_comments)
      : begin_(begin), pos_(begin), end_(end), hash_comments_(hash_comments) {}
  // Over a sliding window: skip_space moves the window on when it reaches its end, so Token texts
  // and saved States are valid until the next call that skips whitespace (next, next_unsigned, peek,
  // skip_space); the bulk fast paths never move it (they report the window's end as a failure), and
  // skip_rest_of_line / advance_to stay inside it (binary payloads need a whole-file Tokenizer).
  Tokenizer(FileWindow& window, bool hash_comments)
      : begin_(nullptr), pos_(nullptr), end_(nullptr), window_(&window), hash_comments_(hash_comments) {
    window.advance(nullptr, begin_, end_);
    pos_ = begin_;
  }

  // Next token, or false at the end of the buffer.
  bool next(Token& token) {
    skip_space();
    if (pos_ == end_) return false;
    const char* start = pos_;
    while (pos_ != end_ && kind(*pos_) == kTokenChar) ++pos_;
    token.text = std::string_view(start, static_cast<std::size_t>(pos_ - start));
    token.line = line_;
    last_line_ = line_;
    return true;
  }
  // Fast path for plain unsigned decimal tokens (up to 18 digits): 1 = parsed into `value` (and the
  // token consumed), 0 = end of input, -1 = the next token is something else (nothing consumed;
  // callers fall back to next() and the strict parsers).
  int next_unsigned(std::uint64_t& value, std::size_t& token_line) {
    skip_space();
    if (pos_ == end_) return 0;
    const char* p = pos_;
    std::uint64_t x = 0;
    int digits = 0;
    while (p != end_ && digits < 18) {
      const unsigned d = static_cast<unsigned char>(*p) - unsigned('0');
      if (d > 9) break;
      x = x * 10 + d;
      ++p, ++digits;
    }
    if (digits == 0 || (p != end_ && kind(*p) == kTokenChar)) return -1;
    pos_ = p;
    last_line_ = token_line = line_;
    value = x;
    return 1;
  }
  // Bulk fast path of numeric blocks: `count` unsigned decimals of at most 9 digits, each preceded by
  // spaces or newlines and followed by a space, a newline or the end. On success they are stored in
  // values and consumed; otherwise NOTHING is consumed (tabs, CR, comments, signs, longer numbers)
  // and the caller takes the general path (next_unsigned / next), which words the errors.
  bool next_plain_unsigned(std::uint32_t* values, int count) {
    const char* p = pos_;
    std::size_t lines = 0;
    for (int k = 0; k < count; ++k) {
      while (p != end_ && (*p == ' ' || *p == '\n')) lines += *p++ == '\n';
      const char* first = p;
      std::uint32_t x;
      int digits = end_ - p >= 8 ? swar_digits(p, x) : 8;
      if (digits < 8) {
        p += digits;
      } else {  // 8 or more digits, or near the end of the buffer
        x = 0;
        while (p != end_) {
          const unsigned d = static_cast<unsigned char>(*p) - unsigned('0');
          if (d > 9) break;
          x = x * 10 + d;
          ++p;
        }
        digits = static_cast<int>(p - first);
      }
      if (digits == 0 || digits > 9 || (p != end_ && *p != ' ' && *p != '\n')) return false;
      values[k] = x;
    }
    pos_ = p;
    line_ += lines;
    last_line_ = line_;
    return true;
  }
  // The common layout of an integer block line, faster: the previous line's '\n' (if any), then
  // `count` decimals of 1..7 digits separated by single spaces, then '\n' (not consumed). Same values,
  // state and all-or-nothing contract as next_plain_unsigned, which it falls back to otherwise.
  bool next_plain_line(std::uint32_t* values, int count) {
    const char* p = pos_;
    if (end_ - p < 9 * count + 1) return next_plain_unsigned(values, count);  // SWAR loads need 8 bytes
    std::size_t line = line_;
    if (*p == '\n') ++p, ++line;
    for (int k = 0; k < count; ++k) {
      std::uint32_t x;
      const int digits = swar_digits(p, x);
      if (digits == 0 || digits == 8 || p[digits] != (k + 1 < count ? ' ' : '\n'))
        return next_plain_unsigned(values, count);
      values[k] = x;
      p += k + 1 < count ? digits + 1 : digits;
    }
    pos_ = p;
    line_ = last_line_ = line;
    return true;
  }
  // Bulk fast path for one finite double in plain decimal or exponent form (std::from_chars, at most
  // kMaxNumberChars), same separators and same all-or-nothing contract as next_plain_unsigned.
  bool next_plain_double(double& value);
  // Saved position, to re-read a stretch with the general path (which reports errors precisely).
  struct State {
    const char* pos;
    std::size_t line, last_line;
  };
  State save() const { return {pos_, line_, last_line_}; }
  void restore(const State& s) { pos_ = s.pos, line_ = s.line, last_line_ = s.last_line; }
  bool peek(Token& token) {
    skip_space();  // moves the window first, if it must, so that the saved position stays valid
    const char* saved = pos_;
    const std::size_t saved_line = line_;
    const std::size_t saved_last = last_line_;
    const bool ok = next(token);
    pos_ = saved, line_ = saved_line, last_line_ = saved_last;
    return ok;
  }
  // Skips whitespace and comments; afterwards position() is at the next token (or the end).
  void skip_space() {
    do {
      while (pos_ != end_) {
        const unsigned k = kind(*pos_);
        if (k == kTokenChar) return;
        if (k == kNewline) {
          ++line_, ++pos_;
        } else if (k == kComment) {
          while (pos_ != end_ && *pos_ != '\n') ++pos_;
        } else {
          ++pos_;
        }
      }
    } while (window_ && move_window());
  }
  // Moves to the start of the next line (used after a keyword line whose rest is binary data).
  void skip_rest_of_line() {
    while (pos_ != end_ && *pos_ != '\n') ++pos_;
    if (pos_ != end_) ++pos_, ++line_;
  }
  std::size_t line() const { return line_; }
  // Counts one more line (for callers that consumed header lines themselves).
  void count_line() { ++line_; }
  // Line of the last token returned by next() (1 before any): where truncation errors point.
  std::size_t last_line() const { return last_line_; }
  // Bytes left to read (of the whole file for a window).
  std::size_t remaining() const {
    return window_ ? window_->remaining_after(pos_) : static_cast<std::size_t>(end_ - pos_);
  }
  const char* position() const { return pos_; }
  const char* end() const { return end_; }
  const char* begin() const { return begin_; }
  // Jumps forward to `p` (binary payloads), counting the newlines crossed.
  void advance_to(const char* p) {
    for (; pos_ < p; ++pos_)
      if (*pos_ == '\n') ++line_;
  }

 private:
  // The window's next lines, from pos_ on (false at the end of the file).
  bool move_window() {
    if (!window_->advance(pos_, begin_, end_)) return false;
    pos_ = begin_;
    return true;
  }
  // The leading decimal digits of the 8 bytes at p (SWAR): their count n (8 when all 8 are digits,
  // then `value` is not set) and, for n < 8, their value.
  static int swar_digits(const char* p, std::uint32_t& value) {
    std::uint64_t chunk;
    std::memcpy(&chunk, p, 8);
    const std::uint64_t t = chunk - 0x3030303030303030ull;  // bytes '0'..'9' -> 0..9
    // High bit of each byte that is not a digit (borrows and carries only reach later bytes).
    const std::uint64_t non_digit = ((t + 0x7676767676767676ull) | t) & 0x8080808080808080ull;
    if (non_digit == 0) return 8;
    const int n = __builtin_ctzll(non_digit) >> 3;
    if (n == 0) return 0;
    std::uint64_t v = t << (8 * (8 - n));  // the n digits, most significant first, after leading zeros
    v = ((v & 0x0F0F0F0F0F0F0F0Full) * 2561) >> 8;
    v = ((v & 0x00FF00FF00FF00FFull) * 6553601) >> 16;
    v = ((v & 0x0000FFFF0000FFFFull) * 42949672960001ull) >> 32;
    value = static_cast<std::uint32_t>(v);
    return n;
  }
  enum : unsigned char { kTokenChar = 0, kSpace = 1, kNewline = 2, kComment = 3 };
  unsigned kind(char c) const {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u > ' ' && u != '#') return kTokenChar;
    if (u == '\n') return kNewline;
    if (u == '#') return hash_comments_ ? kComment : kTokenChar;
    return (u == ' ' || (u >= '\t' && u <= '\r')) ? kSpace : kTokenChar;
  }
  const char* begin_;
  const char* pos_;
  const char* end_;
  FileWindow* window_ = nullptr;
  std::size_t line_ = 1;
  std::size_t last_line_ = 1;
  bool hash_comments_;
};

// Strict parsers: the whole token must be a number; a leading '+' is accepted; NaN, Inf, out-of-range
// and overlong tokens are rejected. Return false instead of throwing so callers word the error.
bool parse_double(std::string_view text, double& value);
// Integers: optional sign and 1..18 decimal digits (hand-rolled: the hot path of tet blocks).
inline bool parse_int64(std::string_view text, std::int64_t& value) {
  std::size_t i = 0;
  bool negative = false;
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) negative = text[0] == '-', i = 1;
  const std::size_t digits = text.size() - i;
  if (digits == 0 || digits > 18) return false;
  std::int64_t v = 0;
  for (; i < text.size(); ++i) {
    const unsigned d = static_cast<unsigned char>(text[i]) - unsigned('0');
    if (d > 9) return false;
    v = v * 10 + static_cast<std::int64_t>(d);
  }
  value = negative ? -v : v;
  return true;
}

// Throwing variants: Error(BadInput) at path:line "<what>: expected a finite number, found '<tok>'".
double expect_double(const Token& token, const std::string& path, const char* what);
std::int64_t expect_int(const Token& token, const std::string& path, const char* what);
// A count: an integer in [0, max_count]; and at least `min_bytes_each` bytes per element must remain
// in the file (protects allocations against huge declared counts in small files).
std::size_t expect_count(const Token& token, const std::string& path, const char* what, std::size_t remaining_bytes,
                         std::size_t min_bytes_each, std::size_t max_count);

// Throws Error(BadInput) naming `path` when the mesh cannot be written faithfully: array sizes not
// multiples of 3/4, ids >= num_vertices, non-finite coordinates, label arrays of the wrong size.
void check_mesh_writable(const TetMeshData& mesh, const std::string& path);

// Shortened, printable copy of a token for error messages.
std::string quote(std::string_view text);

// Buffered text output into an AtomicOutput.
class TextWriter {
 public:
  explicit TextWriter(AtomicOutput& out) : out_(out) { buffer_.reserve(kChunk + 4096); }
  ~TextWriter() = default;
  void put(std::string_view s) {
    buffer_.append(s.data(), s.size());
    maybe_flush();
  }
  void put(char c) {
    buffer_.push_back(c);
    maybe_flush();
  }
  void put_double(double v);  // shortest round-trip form
  void put_int(std::int64_t v);
  void put_fixed6(double v);  // printf("%f") — 6 decimals
  void flush();

 private:
  static constexpr std::size_t kChunk = 1 << 20;
  void maybe_flush() {
    if (buffer_.size() >= kChunk) flush();
  }
  AtomicOutput& out_;
  std::string buffer_;
};

}  // namespace volmap::io_detail
