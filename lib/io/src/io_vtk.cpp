// Legacy VTK UNSTRUCTURED_GRID reader and writer (ASCII and BINARY, binary = big-endian).
// Ids are 0-based in the file and in memory; tets keep their file order and vertex order.
// Reader accepts: blank lines before the header, an empty title, CRLF, the 4.x layout
// (`CELLS n size` + rows `k i j ...`) and the 5.1 layout (`CELLS n_off n_conn` + `OFFSETS type`
// + `CONNECTIVITY type`, detected by the OFFSETS keyword), float/double POINTS, a missing
// CELL_TYPES section (then every cell must have 4 ids), METADATA blocks, and FIELD / CELL_DATA /
// POINT_DATA attribute sections, which are skipped except int SCALARS named "label" (read back into
// vertex_labels / tet_labels, the way our writer stores Medit labels).
// Cell-type rule: VTK_TETRA (10, 4 ids) cells are kept in order; cells of dimension < 3 (types 1-9:
// vertices, lines, triangles, polygons, quads) are skipped, like Medit's Triangles/Edges; any other
// type (hexahedra, wedges, pyramids, quadratic cells, ...) is rejected as Unsupported.
#include <volmap/io/io.hpp>

#include "io_text.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace volmap {
namespace {

using io_detail::Token;
using io_detail::Tokenizer;

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

enum class ValueType { Float, Double, Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Invalid };

ValueType parse_type(std::string_view t) {
  if (iequals(t, "float")) return ValueType::Float;
  if (iequals(t, "double")) return ValueType::Double;
  if (iequals(t, "char")) return ValueType::Int8;
  if (iequals(t, "unsigned_char")) return ValueType::UInt8;
  if (iequals(t, "short")) return ValueType::Int16;
  if (iequals(t, "unsigned_short")) return ValueType::UInt16;
  if (iequals(t, "int") || iequals(t, "vtktypeint32")) return ValueType::Int32;
  if (iequals(t, "unsigned_int") || iequals(t, "vtktypeuint32")) return ValueType::UInt32;
  if (iequals(t, "long") || iequals(t, "vtktypeint64") || iequals(t, "vtkidtype")) return ValueType::Int64;
  if (iequals(t, "unsigned_long") || iequals(t, "vtktypeuint64")) return ValueType::UInt64;
  return ValueType::Invalid;
}

std::size_t type_size(ValueType t) {
  switch (t) {
    case ValueType::Int8: case ValueType::UInt8: return 1;
    case ValueType::Int16: case ValueType::UInt16: return 2;
    case ValueType::Float: case ValueType::Int32: case ValueType::UInt32: return 4;
    default: return 8;
  }
}

template <typename T>
T load_be(const unsigned char* p) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v = (v << 8) | p[i];
  if constexpr (sizeof(T) == 1) {
    const auto b = static_cast<std::uint8_t>(v);
    T out;
    std::memcpy(&out, &b, 1);
    return out;
  } else if constexpr (sizeof(T) == 2) {
    const auto b = static_cast<std::uint16_t>(v);
    T out;
    std::memcpy(&out, &b, 2);
    return out;
  } else if constexpr (sizeof(T) == 4) {
    const auto b = static_cast<std::uint32_t>(v);
    T out;
    std::memcpy(&out, &b, 4);
    return out;
  } else {
    T out;
    std::memcpy(&out, &v, 8);
    return out;
  }
}

class VtkReader {
 public:
  VtkReader(const std::string& path, const std::string& data) : path_(path), data_(data), tok_(nullptr, nullptr, false) {}

  TetMeshData read();

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& reason) const { throw_bad_input(path_, line, reason); }
  Token expect_token(const char* what) {
    Token t;
    if (!tok_.next(t)) fail(tok_.last_line(), std::string("unexpected end of file: expected ") + what);
    return t;
  }
  std::size_t expect_count(const char* what, std::size_t min_ascii_bytes) {
    const Token t = expect_token(what);
    return io_detail::expect_count(t, path_, what, tok_.remaining(), binary_ ? 1 : min_ascii_bytes,
                                   std::numeric_limits<std::uint32_t>::max());
  }
  ValueType expect_type(const char* what) {
    const Token t = expect_token(what);
    const ValueType v = parse_type(t.text);
    if (v == ValueType::Invalid) fail(t.line, std::string(what) + ": unsupported data type " + io_detail::quote(t.text));
    return v;
  }
  // Binary payloads start on the line after their keyword line.
  const unsigned char* begin_binary(std::size_t count, ValueType type, const char* what, std::size_t line) {
    tok_.skip_rest_of_line();
    const std::size_t bytes = count * type_size(type);
    if (count != 0 && bytes / count != type_size(type)) fail(line, std::string(what) + ": size overflow");
    if (tok_.remaining() < bytes)
      fail(line, std::string(what) + ": binary block truncated (" + std::to_string(bytes) + " bytes needed, " +
                     std::to_string(tok_.remaining()) + " left)");
    const auto* p = reinterpret_cast<const unsigned char*>(tok_.position());
    tok_.advance_to(tok_.position() + bytes);
    return p;
  }
  void read_doubles(std::size_t count, ValueType type, std::vector<double>& out, const char* what, std::size_t line);
  void read_ints(std::size_t count, ValueType type, std::vector<std::int64_t>& out, const char* what, std::size_t line);
  void skip_values(std::size_t count, ValueType type, const char* what, std::size_t line);
  void read_attributes(bool cells, std::size_t count, std::size_t line);
  void skip_field(std::size_t line);
  void skip_metadata();

  const std::string& path_;
  const std::string& data_;
  Tokenizer tok_;
  bool binary_ = false;
  std::vector<std::int32_t> vertex_labels_, tet_labels_;
};

void VtkReader::read_doubles(std::size_t count, ValueType type, std::vector<double>& out, const char* what,
                             std::size_t line) {
  if (binary_) {
    const unsigned char* p = begin_binary(count, type, what, line);
    out.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double v = type == ValueType::Double ? load_be<double>(p + 8 * i) : static_cast<double>(load_be<float>(p + 4 * i));
      if (!std::isfinite(v)) fail(line, std::string(what) + ": non-finite value at index " + std::to_string(i));
      out[i] = v;
    }
    return;
  }
  if (count / 2 > tok_.remaining()) fail(line, std::string(what) + ": declared size exceeds the file");
  out.resize(count);
  Token t;
  for (std::size_t i = 0; i < count; ++i) {
    if (!tok_.next(t))
      fail(tok_.last_line(), std::string(what) + " truncated: " + std::to_string(i) + " of " + std::to_string(count) + " values");
    if (!io_detail::parse_double(t.text, out[i])) io_detail::expect_double(t, path_, what);
    if (type == ValueType::Float) out[i] = static_cast<double>(static_cast<float>(out[i]));
  }
}

void VtkReader::read_ints(std::size_t count, ValueType type, std::vector<std::int64_t>& out, const char* what,
                          std::size_t line) {
  if (binary_) {
    const unsigned char* p = begin_binary(count, type, what, line);
    out.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      std::int64_t v = 0;
      switch (type) {
        case ValueType::Int8: v = load_be<std::int8_t>(p + i); break;
        case ValueType::UInt8: v = load_be<std::uint8_t>(p + i); break;
        case ValueType::Int16: v = load_be<std::int16_t>(p + 2 * i); break;
        case ValueType::UInt16: v = load_be<std::uint16_t>(p + 2 * i); break;
        case ValueType::Int32: v = load_be<std::int32_t>(p + 4 * i); break;
        case ValueType::UInt32: v = load_be<std::uint32_t>(p + 4 * i); break;
        case ValueType::Int64: v = load_be<std::int64_t>(p + 8 * i); break;
        case ValueType::UInt64: {
          const auto u = load_be<std::uint64_t>(p + 8 * i);
          v = u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) ? -1 : static_cast<std::int64_t>(u);
          break;
        }
        default: fail(line, std::string(what) + ": floating-point type where integers are expected");
      }
      out[i] = v;
    }
    return;
  }
  if (type == ValueType::Float || type == ValueType::Double)
    fail(line, std::string(what) + ": floating-point type where integers are expected");
  if (count / 2 > tok_.remaining()) fail(line, std::string(what) + ": declared size exceeds the file");
  out.resize(count);
  Token t;
  for (std::size_t i = 0; i < count; ++i) {
    if (!tok_.next(t))
      fail(tok_.last_line(), std::string(what) + " truncated: " + std::to_string(i) + " of " + std::to_string(count) + " values");
    if (!io_detail::parse_int64(t.text, out[i])) out[i] = io_detail::expect_int(t, path_, what);
  }
}

void VtkReader::skip_values(std::size_t count, ValueType type, const char* what, std::size_t line) {
  if (binary_) {
    begin_binary(count, type, what, line);
    return;
  }
  if (count > tok_.remaining()) fail(line, std::string(what) + ": declared size exceeds the file");
  Token t;
  for (std::size_t i = 0; i < count; ++i) {
    if (!tok_.next(t)) fail(tok_.last_line(), std::string(what) + " truncated");
    double unused;
    if (!io_detail::parse_double(t.text, unused)) io_detail::expect_double(t, path_, what);
  }
}

void VtkReader::skip_metadata() {
  // METADATA blocks run to the next empty line.
  tok_.skip_rest_of_line();
  while (tok_.remaining() > 0) {
    const char* p = tok_.position();
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', tok_.remaining()));
    const char* stop = eol ? eol : tok_.end();
    const bool blank = std::all_of(p, stop, [](char c) { return io_detail::is_space(c); });
    tok_.skip_rest_of_line();
    if (blank) break;
  }
}

void VtkReader::skip_field(std::size_t line) {
  expect_token("FIELD name");
  const std::size_t arrays = expect_count("FIELD array count", 8);
  for (std::size_t a = 0; a < arrays; ++a) {
    Token name = expect_token("FIELD array name");
    if (iequals(name.text, "METADATA")) {
      skip_metadata();
      name = expect_token("FIELD array name");
    }
    const Token comps_tok = expect_token("FIELD array components");
    const Token tuples_tok = expect_token("FIELD array tuples");
    const std::int64_t comps = io_detail::expect_int(comps_tok, path_, "FIELD array components");
    const std::int64_t tuples = io_detail::expect_int(tuples_tok, path_, "FIELD array tuples");
    if (comps < 0 || tuples < 0 || comps > (1 << 20) || tuples > std::numeric_limits<std::uint32_t>::max())
      fail(comps_tok.line, "FIELD array: bad size");
    const ValueType type = expect_type("FIELD array type");
    skip_values(static_cast<std::size_t>(comps) * static_cast<std::size_t>(tuples), type, "FIELD array", line);
  }
}

void VtkReader::read_attributes(bool cells, std::size_t count, std::size_t /*line*/) {
  // Attribute arrays until the next CELL_DATA / POINT_DATA or the end.
  Token t;
  while (tok_.peek(t)) {
    const std::string_view k = t.text;
    if (iequals(k, "CELL_DATA") || iequals(k, "POINT_DATA")) return;
    tok_.next(t);
    if (iequals(k, "SCALARS")) {
      const Token name = expect_token("SCALARS name");
      const ValueType type = expect_type("SCALARS type");
      std::size_t comps = 1;
      Token maybe;
      // Optional component count on the same line.
      if (tok_.peek(maybe) && maybe.line == name.line) {
        tok_.next(maybe);
        const std::int64_t c = io_detail::expect_int(maybe, path_, "SCALARS components");
        if (c < 1 || c > 4) fail(maybe.line, "SCALARS: components must be 1..4");
        comps = static_cast<std::size_t>(c);
      }
      if (tok_.peek(maybe) && iequals(maybe.text, "LOOKUP_TABLE")) {
        tok_.next(maybe);
        expect_token("LOOKUP_TABLE name");
      }
      const bool is_label = name.text == "label" && comps == 1 && type != ValueType::Float && type != ValueType::Double;
      if (is_label) {
        std::vector<std::int64_t> values;
        read_ints(count, type, values, "label", name.line);
        auto& target = cells ? tet_labels_ : vertex_labels_;
        target.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
          if (values[i] < std::numeric_limits<std::int32_t>::min() || values[i] > std::numeric_limits<std::int32_t>::max())
            fail(name.line, "label out of 32-bit range");
          target[i] = static_cast<std::int32_t>(values[i]);
        }
      } else {
        skip_values(count * comps, type, "SCALARS", name.line);
      }
    } else if (iequals(k, "LOOKUP_TABLE")) {
      expect_token("LOOKUP_TABLE name");
      const std::size_t size = expect_count("LOOKUP_TABLE size", 8);
      skip_values(4 * size, binary_ ? ValueType::UInt8 : ValueType::Float, "LOOKUP_TABLE", t.line);
    } else if (iequals(k, "VECTORS") || iequals(k, "NORMALS") || iequals(k, "TENSORS")) {
      expect_token("array name");
      const ValueType type = expect_type("array type");
      skip_values(count * (iequals(k, "TENSORS") ? 9 : 3), type, "attribute array", t.line);
    } else if (iequals(k, "TEXTURE_COORDINATES")) {
      expect_token("TEXTURE_COORDINATES name");
      const Token dim = expect_token("TEXTURE_COORDINATES dim");
      const std::int64_t d = io_detail::expect_int(dim, path_, "TEXTURE_COORDINATES dim");
      if (d < 1 || d > 3) fail(dim.line, "TEXTURE_COORDINATES: dim must be 1..3");
      const ValueType type = expect_type("TEXTURE_COORDINATES type");
      skip_values(count * static_cast<std::size_t>(d), type, "TEXTURE_COORDINATES", t.line);
    } else if (iequals(k, "COLOR_SCALARS")) {
      expect_token("COLOR_SCALARS name");
      const Token nv = expect_token("COLOR_SCALARS count");
      const std::int64_t n = io_detail::expect_int(nv, path_, "COLOR_SCALARS count");
      if (n < 1 || n > 4) fail(nv.line, "COLOR_SCALARS: 1..4 values");
      skip_values(count * static_cast<std::size_t>(n), binary_ ? ValueType::UInt8 : ValueType::Float, "COLOR_SCALARS", t.line);
    } else if (iequals(k, "FIELD")) {
      skip_field(t.line);
    } else if (iequals(k, "METADATA")) {
      skip_metadata();
    } else {
      fail(t.line, "unknown attribute keyword " + io_detail::quote(k));
    }
  }
}

TetMeshData VtkReader::read() {
  // Header: optional blank lines, "# vtk DataFile Version x.y", a title line (may be empty), ASCII|BINARY.
  const char* p = data_.data();
  const char* end = p + data_.size();
  std::size_t line = 1;
  auto next_line = [&](std::string_view& out) {
    if (p >= end) return false;
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    const char* stop = eol ? eol : end;
    out = std::string_view(p, static_cast<std::size_t>(stop - p));
    while (!out.empty() && io_detail::is_space(out.back())) out.remove_suffix(1);
    p = eol ? eol + 1 : end;
    return true;
  };
  std::string_view l;
  bool got = false;
  while ((got = next_line(l)) && l.find_first_not_of(" \t\r\f\v") == std::string_view::npos) ++line;
  if (!got) fail(0, "empty file (not a legacy VTK file)");
  if (l.size() < 5 || !iequals(l.substr(0, 5), "# vtk"))
    fail(line, "not a legacy VTK file (expected '# vtk DataFile Version ...')");
  ++line;
  if (!next_line(l)) fail(line, "missing title line");
  ++line;
  if (!next_line(l)) fail(line, "missing ASCII/BINARY line");
  while (!l.empty() && io_detail::is_space(l.front())) l.remove_prefix(1);
  if (iequals(l, "ASCII"))
    binary_ = false;
  else if (iequals(l, "BINARY"))
    binary_ = true;
  else
    fail(line, "expected ASCII or BINARY, found " + io_detail::quote(l));
  tok_ = Tokenizer(p, end, false);
  for (std::size_t k = 0; k < line; ++k) tok_.count_line();

  TetMeshData mesh;
  std::vector<std::int64_t> offsets, connectivity, types;
  bool have_points = false, have_cells = false, have_types = false, have_dataset = false;
  std::size_t cells_line = 0, num_cells = 0;
  Token t;
  while (tok_.next(t)) {
    const std::string_view k = t.text;
    if (iequals(k, "DATASET")) {
      const Token kind = expect_token("dataset type");
      if (!iequals(kind.text, "UNSTRUCTURED_GRID"))
        throw Error(ErrorKind::Unsupported, path_, kind.line,
                    "DATASET " + std::string(kind.text) + " is not supported (UNSTRUCTURED_GRID only)");
      have_dataset = true;
    } else if (iequals(k, "POINTS")) {
      if (!have_dataset) fail(t.line, "POINTS before DATASET UNSTRUCTURED_GRID");
      if (have_points) fail(t.line, "second POINTS section");
      const std::size_t n = expect_count("POINTS", 6);
      const ValueType type = expect_type("POINTS type");
      if (type != ValueType::Float && type != ValueType::Double)
        throw Error(ErrorKind::Unsupported, path_, t.line, "POINTS must be float or double");
      if (binary_ && n > tok_.remaining() / (3 * type_size(type)))
        fail(t.line, "POINTS: declared count does not fit in the file (truncated binary block?)");
      read_doubles(3 * n, type, mesh.xyz, "POINTS", t.line);
      have_points = true;
    } else if (iequals(k, "CELLS")) {
      if (have_cells) fail(t.line, "second CELLS section");
      cells_line = t.line;
      const std::size_t a = expect_count("CELLS count", 2);
      const std::size_t b = expect_count("CELLS size", 2);
      // 5.1 layout: the next keyword is OFFSETS (check the raw bytes: binary data may follow).
      const char* q = tok_.position();
      while (q < tok_.end() && *q != '\n' && io_detail::is_space(*q)) ++q;
      if (q < tok_.end() && *q == '\n') ++q;
      while (q < tok_.end() && io_detail::is_space(*q)) ++q;
      const bool layout51 = static_cast<std::size_t>(tok_.end() - q) >= 7 && iequals(std::string_view(q, 7), "OFFSETS");
      if (layout51) {
        if (a == 0) fail(t.line, "CELLS: 5.1 layout needs at least one offset");
        const Token off = expect_token("OFFSETS");
        const ValueType ot = expect_type("OFFSETS type");
        read_ints(a, ot, offsets, "OFFSETS", off.line);
        const Token conn = expect_token("CONNECTIVITY");
        if (!iequals(conn.text, "CONNECTIVITY")) fail(conn.line, "expected CONNECTIVITY after OFFSETS");
        const ValueType ct = expect_type("CONNECTIVITY type");
        read_ints(b, ct, connectivity, "CONNECTIVITY", conn.line);
        num_cells = a - 1;
        if (offsets[0] != 0) fail(off.line, "OFFSETS must start at 0");
        for (std::size_t c = 0; c < num_cells; ++c)
          if (offsets[c + 1] < offsets[c]) fail(off.line, "OFFSETS decrease at cell " + std::to_string(c));
        if (static_cast<std::uint64_t>(offsets[num_cells]) != b)
          fail(off.line, "last offset " + std::to_string(offsets[num_cells]) + " != connectivity size " + std::to_string(b));
      } else {
        std::vector<std::int64_t> rows;
        if (binary_) {
          read_ints(b, ValueType::Int32, rows, "CELLS", t.line);
        } else {
          read_ints(b, ValueType::Int64, rows, "CELLS", t.line);
        }
        // Split "k i j ..." rows into offsets + connectivity.
        num_cells = a;
        offsets.assign(a + 1, 0);
        connectivity.clear();
        connectivity.reserve(b >= a ? b - a : 0);
        std::size_t r = 0;
        for (std::size_t c = 0; c < a; ++c) {
          if (r >= rows.size()) fail(t.line, "CELLS: size " + std::to_string(b) + " too small for " + std::to_string(a) + " cells");
          const std::int64_t k_ids = rows[r++];
          if (k_ids < 0 || static_cast<std::uint64_t>(k_ids) > rows.size() - r)
            fail(t.line, "CELLS: cell " + std::to_string(c) + " declares " + std::to_string(k_ids) + " ids, beyond the section size");
          connectivity.insert(connectivity.end(), rows.begin() + static_cast<std::ptrdiff_t>(r),
                              rows.begin() + static_cast<std::ptrdiff_t>(r + static_cast<std::size_t>(k_ids)));
          r += static_cast<std::size_t>(k_ids);
          offsets[c + 1] = static_cast<std::int64_t>(connectivity.size());
        }
        if (r != rows.size()) fail(t.line, "CELLS: size " + std::to_string(b) + " does not match the rows (" + std::to_string(r) + " used)");
      }
      have_cells = true;
    } else if (iequals(k, "CELL_TYPES")) {
      if (have_types) fail(t.line, "second CELL_TYPES section");
      const std::size_t n = expect_count("CELL_TYPES", 2);
      read_ints(n, ValueType::Int32, types, "CELL_TYPES", t.line);
      have_types = true;
    } else if (iequals(k, "CELL_DATA") || iequals(k, "POINT_DATA")) {
      const bool cells = iequals(k, "CELL_DATA");
      const std::size_t n = expect_count(cells ? "CELL_DATA" : "POINT_DATA", 0);
      read_attributes(cells, n, t.line);
      if (cells && !tet_labels_.empty() && n != num_cells) tet_labels_.clear();
    } else if (iequals(k, "FIELD")) {
      skip_field(t.line);
    } else if (iequals(k, "METADATA")) {
      skip_metadata();
    } else {
      fail(t.line, "unexpected keyword " + io_detail::quote(k));
    }
  }
  if (!have_dataset) fail(0, "no DATASET UNSTRUCTURED_GRID");
  if (!have_points) fail(0, "no POINTS section");
  if (!have_cells) fail(0, "no CELLS section");
  if (have_types && types.size() != num_cells)
    fail(0, "CELL_TYPES has " + std::to_string(types.size()) + " entries for " + std::to_string(num_cells) + " cells");

  const std::size_t nv = mesh.xyz.size() / 3;
  std::vector<std::uint32_t> kept_cells;
  mesh.tets.reserve(4 * num_cells);
  for (std::size_t c = 0; c < num_cells; ++c) {
    const std::int64_t size = offsets[c + 1] - offsets[c];
    const std::int64_t type = have_types ? types[c] : 10;
    if (type >= 1 && type <= 9) continue;  // lower-dimensional cell: skipped
    if (type != 10)
      throw Error(ErrorKind::Unsupported, path_, cells_line,
                  "cell " + std::to_string(c) + " has VTK type " + std::to_string(type) + " (only tetrahedra, type 10, are supported)");
    if (size != 4)
      fail(cells_line, "cell " + std::to_string(c) + " has " + std::to_string(size) + " ids" +
                           (have_types ? " but type 10 (tetra) needs 4" : " (no CELL_TYPES section: every cell must be a 4-id tet)"));
    for (std::int64_t j = offsets[c]; j < offsets[c + 1]; ++j) {
      const std::int64_t id = connectivity[static_cast<std::size_t>(j)];
      if (id < 0 || static_cast<std::uint64_t>(id) >= nv)
        fail(cells_line, "cell " + std::to_string(c) + ": vertex id " + std::to_string(id) + " outside [0," + std::to_string(nv) + ")");
      mesh.tets.push_back(static_cast<std::uint32_t>(id));
    }
    kept_cells.push_back(static_cast<std::uint32_t>(c));
  }
  mesh.vertex_labels.assign(nv, 0);
  if (vertex_labels_.size() == nv) mesh.vertex_labels = vertex_labels_;
  mesh.tet_labels.assign(kept_cells.size(), 0);
  if (tet_labels_.size() == num_cells)
    for (std::size_t i = 0; i < kept_cells.size(); ++i) mesh.tet_labels[i] = tet_labels_[kept_cells[i]];
  return mesh;
}

// ---- writer ----

void put_be(std::string& out, const void* value, std::size_t size) {
  const auto* b = static_cast<const unsigned char*>(value);
  for (std::size_t i = 0; i < size; ++i) out.push_back(static_cast<char>(b[size - 1 - i]));
}

bool any_nonzero(const std::vector<std::int32_t>& v) {
  return std::any_of(v.begin(), v.end(), [](std::int32_t x) { return x != 0; });
}

}  // namespace

TetMeshData read_vtk(const std::string& path) {
  const std::string data = io_detail::read_whole_file(path, {/*text=*/false, /*text_prefix=*/32});
  VtkReader reader(path, data);
  return reader.read();
}

void write_vtk(AtomicOutput& out, const TetMeshData& mesh, bool binary) {
  const std::string& path = out.destination();
  io_detail::check_mesh_writable(mesh, path);
  const std::size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  if (nv > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()) || 5 * nt > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw Error(ErrorKind::Unsupported, path, 0, "mesh too large for the legacy VTK 4.x layout (int32 ids)");
  io_detail::TextWriter w(out);
  w.put("# vtk DataFile Version 4.2\nvolmap tet mesh\n");
  w.put(binary ? "BINARY\n" : "ASCII\n");
  w.put("DATASET UNSTRUCTURED_GRID\nPOINTS ");
  w.put_int(static_cast<std::int64_t>(nv));
  w.put(" double\n");
  std::string bytes;
  auto put_int32_block = [&](auto&& value_at, std::size_t count, std::size_t per_line) {
    if (binary) {
      bytes.clear();
      for (std::size_t i = 0; i < count; ++i) {
        const std::int32_t v = value_at(i);
        put_be(bytes, &v, 4);
        if (bytes.size() >= (1 << 20)) w.put(bytes), bytes.clear();
      }
      w.put(bytes);
      w.put('\n');
    } else {
      for (std::size_t i = 0; i < count; ++i) {
        w.put_int(value_at(i));
        w.put((i + 1) % per_line == 0 ? '\n' : ' ');
      }
      if (count % per_line != 0) w.put('\n');
    }
  };
  if (binary) {
    for (std::size_t i = 0; i < 3 * nv; ++i) {
      put_be(bytes, &mesh.xyz[i], 8);
      if (bytes.size() >= (1 << 20)) w.put(bytes), bytes.clear();
    }
    w.put(bytes);
    w.put('\n');
  } else {
    for (std::size_t i = 0; i < nv; ++i) {
      w.put_double(mesh.xyz[3 * i]);
      w.put(' ');
      w.put_double(mesh.xyz[3 * i + 1]);
      w.put(' ');
      w.put_double(mesh.xyz[3 * i + 2]);
      w.put('\n');
    }
  }
  w.put("CELLS ");
  w.put_int(static_cast<std::int64_t>(nt));
  w.put(' ');
  w.put_int(static_cast<std::int64_t>(5 * nt));
  w.put('\n');
  put_int32_block([&](std::size_t i) { return i % 5 == 0 ? 4 : static_cast<std::int32_t>(mesh.tets[4 * (i / 5) + i % 5 - 1]); },
                  5 * nt, 5);
  w.put("CELL_TYPES ");
  w.put_int(static_cast<std::int64_t>(nt));
  w.put('\n');
  put_int32_block([](std::size_t) { return 10; }, nt, 1);
  // Medit labels survive a round trip as int SCALARS named "label" (written only when not all 0).
  if (any_nonzero(mesh.tet_labels)) {
    w.put("CELL_DATA ");
    w.put_int(static_cast<std::int64_t>(nt));
    w.put("\nSCALARS label int 1\nLOOKUP_TABLE default\n");
    put_int32_block([&](std::size_t i) { return mesh.tet_labels[i]; }, nt, 1);
  }
  if (any_nonzero(mesh.vertex_labels)) {
    w.put("POINT_DATA ");
    w.put_int(static_cast<std::int64_t>(nv));
    w.put("\nSCALARS label int 1\nLOOKUP_TABLE default\n");
    put_int32_block([&](std::size_t i) { return mesh.vertex_labels[i]; }, nv, 1);
  }
  w.flush();
}

void write_vtk(const std::string& path, const TetMeshData& mesh, bool binary) {
  AtomicOutput out(path);
  write_vtk(out, mesh, binary);
  out.commit();
}

}  // namespace volmap
