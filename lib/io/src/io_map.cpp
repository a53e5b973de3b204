// Boundary maps (`vid x y z`, vid 0-based, one entry per line, any whitespace) and rationals files
// (one exact GMP rational `num/den` or `num` per token, 3 per vertex in mesh order).
// Readers report file and 1-based line; validation against a mesh uses boundary_vertex_ids().
#include <volmap/core/boundary_faces.hpp>
#include <volmap/io/io.hpp>

#include "io_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <gmp.h>
#include <limits>
#include <numeric>

namespace volmap {
namespace {

using io_detail::Token;

// Splits one line [begin, end) into whitespace-separated tokens (at most `max` + 1 are stored).
std::size_t split_line(const char* begin, const char* end, std::string_view* out, std::size_t max) {
  std::size_t n = 0;
  const char* p = begin;
  while (p < end) {
    while (p < end && io_detail::is_space(*p)) ++p;
    if (p == end) break;
    const char* s = p;
    while (p < end && !io_detail::is_space(*p)) ++p;
    if (n <= max) out[n] = std::string_view(s, static_cast<std::size_t>(p - s));
    ++n;
  }
  return n;
}

}  // namespace

BoundaryMap read_boundary_map(const std::string& path) {
  // A line holds 4 numbers of at most kMaxNumberChars each: anything much longer is not a map.
  const std::string data = io_detail::read_whole_file(path, {/*text=*/true, 0, /*max_line=*/1 << 16});
  BoundaryMap map;
  // Upper bound of entries: a line holds at least 8 bytes ("v x y z\n"); reserve conservatively.
  const std::size_t lines_estimate = static_cast<std::size_t>(std::count(data.begin(), data.end(), '\n')) + 1;
  map.vids.reserve(lines_estimate);
  map.xyz.reserve(3 * lines_estimate);
  map.source_lines.reserve(lines_estimate);
  const char* p = data.data();
  const char* end = p + data.size();
  std::size_t line = 0;
  std::string_view tokens[5];
  while (p < end) {
    ++line;
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    if (!eol) eol = end;
    const std::size_t n = split_line(p, eol, tokens, 4);
    p = eol + (eol < end ? 1 : 0);
    if (n == 0) continue;  // blank line
    if (n != 4)
      throw_bad_input(path, line, "expected 'vid x y z' (4 values), found " + std::to_string(n) + " values");
    std::int64_t vid;
    if (!io_detail::parse_int64(tokens[0], vid))
      throw_bad_input(path, line, "vertex id: expected an integer, found " + io_detail::quote(tokens[0]));
    if (vid < 0) throw_bad_input(path, line, "negative vertex id " + std::to_string(vid));
    if (vid >= static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max()))
      throw_bad_input(path, line, "vertex id " + std::to_string(vid) + " too large");
    double c[3];
    for (int k = 0; k < 3; ++k)
      if (!io_detail::parse_double(tokens[1 + k], c[k]))
        throw_bad_input(path, line, "coordinate: expected a finite number, found " + io_detail::quote(tokens[1 + k]));
    map.vids.push_back(static_cast<std::uint32_t>(vid));
    map.xyz.insert(map.xyz.end(), c, c + 3);
    map.source_lines.push_back(static_cast<std::uint32_t>(std::min<std::size_t>(line, std::numeric_limits<std::uint32_t>::max())));
  }
  if (map.vids.empty()) throw_bad_input(path, 0, "empty boundary map");
  // Duplicates: sort entry indices by vid (no hashing), report the later line of the first clash.
  std::vector<std::uint32_t> order(map.vids.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return map.vids[a] < map.vids[b] || (map.vids[a] == map.vids[b] && a < b);
  });
  std::size_t worst = std::numeric_limits<std::size_t>::max();
  for (std::size_t k = 1; k < order.size(); ++k)
    if (map.vids[order[k]] == map.vids[order[k - 1]]) worst = std::min<std::size_t>(worst, order[k]);
  if (worst != std::numeric_limits<std::size_t>::max())
    throw_bad_input(path, map.source_lines[worst], "duplicate vertex id " + std::to_string(map.vids[worst]));
  return map;
}

void write_boundary_map(AtomicOutput& out, const BoundaryMap& map, MapPrecision precision) {
  const std::string& path = out.destination();
  if (map.xyz.size() != 3 * map.vids.size())
    throw Error(ErrorKind::BadInput, path, 0, "cannot write: map xyz size is not 3 * number of vids");
  for (double c : map.xyz)
    if (!std::isfinite(c)) throw Error(ErrorKind::BadInput, path, 0, "cannot write: non-finite map coordinate");
  std::vector<std::uint32_t> order(map.vids.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return map.vids[a] < map.vids[b]; });
  io_detail::TextWriter w(out);
  for (std::uint32_t k : order) {
    w.put_int(map.vids[k]);
    for (int c = 0; c < 3; ++c) {
      w.put(' ');
      if (precision == MapPrecision::Full)
        w.put_double(map.xyz[3 * k + c]);
      else
        w.put_fixed6(map.xyz[3 * k + c]);
    }
    w.put('\n');
  }
  w.flush();
}

void write_boundary_map(const std::string& path, const BoundaryMap& map, MapPrecision precision) {
  AtomicOutput out(path);
  write_boundary_map(out, map, precision);
  out.commit();
}

void validate_boundary_map(const BoundaryMap& map, const TetMeshData& mesh, const std::string& map_path) {
  const std::size_t nv = mesh.num_vertices();
  const std::vector<std::uint32_t> boundary = boundary_vertex_ids(mesh);
  std::vector<std::uint8_t> state(nv, 0);  // 0 interior, 1 boundary unseen, 2 boundary seen
  for (std::uint32_t v : boundary) state[v] = 1;
  auto line_of = [&](std::size_t k) -> std::size_t { return k < map.source_lines.size() ? map.source_lines[k] : 0; };
  auto where = [&](std::size_t k) {
    return map.source_lines.empty() ? " (entry " + std::to_string(k) + ")" : std::string();
  };
  if (map.xyz.size() != 3 * map.vids.size()) throw_bad_input(map_path, 0, "map xyz size is not 3 * number of vids");
  for (std::size_t k = 0; k < map.vids.size(); ++k) {
    const std::uint32_t v = map.vids[k];
    if (v >= nv)
      throw_bad_input(map_path, line_of(k), "vertex id " + std::to_string(v) + " out of range (the mesh has " +
                                                std::to_string(nv) + " vertices)" + where(k));
    if (state[v] == 0) throw_bad_input(map_path, line_of(k), "vertex id " + std::to_string(v) + " is an interior vertex" + where(k));
    if (state[v] == 2) throw_bad_input(map_path, line_of(k), "duplicate vertex id " + std::to_string(v) + where(k));
    state[v] = 2;
  }
  for (std::uint32_t v : boundary)
    if (state[v] != 2)
      throw_bad_input(map_path, 0, "boundary vertex " + std::to_string(v) + " is missing from the map (" +
                                       std::to_string(map.vids.size()) + " entries for " + std::to_string(boundary.size()) +
                                       " boundary vertices)");
}

// ---- rationals ----

std::vector<Rational> read_rationals(const std::string& path, std::size_t expected_vertices) {
  const std::string data = io_detail::read_whole_file(path, {/*text=*/true});
  if (expected_vertices > std::numeric_limits<std::size_t>::max() / 6)
    throw_bad_input(path, 0, "expected vertex count too large");
  const std::size_t expected = 3 * expected_vertices;
  // Each value needs at least 2 bytes: refuse before allocating when the file cannot hold them.
  if (expected > 0 && expected - 1 > data.size() / 2 + 1)
    throw_bad_input(path, 0, "file too small for " + std::to_string(expected) + " rationals (" +
                                 std::to_string(expected_vertices) + " vertices)");
  std::vector<Rational> values;
  values.reserve(expected);
  io_detail::Tokenizer tok(data.data(), data.data() + data.size(), /*hash_comments=*/false);
  Token t;
  std::string buffer;
  mpq_t q;
  mpq_init(q);
  struct Clear {
    mpq_t& q;
    ~Clear() { mpq_clear(q); }
  } clear{q};
  while (tok.next(t)) {
    if (values.size() == expected)
      throw_bad_input(path, t.line, "more than the expected " + std::to_string(expected) + " values (3 per vertex)");
    // Syntax: [+-]digits[/digits]
    std::string_view s = t.text;
    std::size_t i = 0;
    if (!s.empty() && (s[0] == '-' || s[0] == '+')) ++i;
    const std::size_t num_start = i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    bool ok = i > num_start;
    std::size_t den_start = s.size();
    if (ok && i < s.size()) {
      if (s[i] != '/') ok = false;
      den_start = ++i;
      while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
      ok = ok && i > den_start && i == s.size();
    }
    if (!ok) throw_bad_input(path, t.line, "expected a rational 'num/den' or 'num', found " + io_detail::quote(s));
    if (den_start < s.size() && s.find_first_not_of('0', den_start) == std::string_view::npos)
      throw_bad_input(path, t.line, "zero denominator in " + io_detail::quote(s));
    buffer.assign(s[0] == '+' ? s.substr(1) : s);
    if (mpq_set_str(q, buffer.c_str(), 10) != 0)
      throw_bad_input(path, t.line, "malformed rational " + io_detail::quote(s));
    mpq_canonicalize(q);
    values.emplace_back(q);
  }
  if (values.size() != expected)
    throw_bad_input(path, tok.last_line(), "expected " + std::to_string(expected) + " values (3 per vertex for " +
                                          std::to_string(expected_vertices) + " vertices), found " +
                                          std::to_string(values.size()));
  return values;
}

void write_rationals(AtomicOutput& out, const std::vector<Rational>& xyz) {
  const std::string& path = out.destination();
  if (xyz.size() % 3 != 0) throw Error(ErrorKind::BadInput, path, 0, "cannot write: value count is not a multiple of 3");
  io_detail::TextWriter w(out);
  std::string text;
  for (const Rational& r : xyz) {
    const mpq_srcptr q = r.backend().data();
    // mpq_get_str writes "num/den", or "num" when den == 1 (the same text as mpq_out_str).
    text.resize(mpz_sizeinbase(mpq_numref(q), 10) + mpz_sizeinbase(mpq_denref(q), 10) + 3);
    mpq_get_str(text.data(), 10, q);
    w.put(std::string_view(text.c_str()));
    w.put('\n');
  }
  w.flush();
}

void write_rationals(const std::string& path, const std::vector<Rational>& xyz) {
  AtomicOutput out(path);
  write_rationals(out, xyz);
  out.commit();
}

}  // namespace volmap
