// VTK XML UnstructuredGrid (.vtu) writer and reader, tets only. Ids 0-based, order kept.
// Writer: version 1.0, LittleEndian, header_type UInt64; Points Float64 x3; Cells connectivity and
// offsets Int64 (end offsets 4, 8, ...), types UInt8 (10); PointData/CellData Int32 "label" when the
// Medit labels are not all zero; optional CellData Float64 arrays. Encoding: appended raw (default)
// or ascii with shortest round-trip doubles — both read back bit-exactly.
// Reader: a small XML scanner (no external parser) for ascii, inline base64 ("binary") and
// appended (raw or base64) arrays, any numeric type, either byte order, UInt32/UInt64 headers;
// compressed files (a `compressor` attribute) are rejected as Unsupported. The cell-type rule is the
// legacy reader's: type 10 kept, types 1-9 skipped, anything else Unsupported.
#include <volmap/io/io.hpp>

#include "io_text.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace volmap {
namespace {

// ---------- base64 ----------
int b64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// Decodes base64, ignoring whitespace; VTK may concatenate padded blocks (header and data encoded
// separately), so '=' resets the 4-character group. Returns false on an invalid character.
bool decode_base64(std::string_view in, std::string& out) {
  out.clear();
  out.reserve(in.size() / 4 * 3);
  std::uint32_t acc = 0;
  int n = 0;
  for (char c : in) {
    if (io_detail::is_space(c)) continue;
    if (c == '=') {
      if (n == 2) out.push_back(static_cast<char>((acc >> 4) & 0xFF));
      if (n == 3) {
        out.push_back(static_cast<char>((acc >> 10) & 0xFF));
        out.push_back(static_cast<char>((acc >> 2) & 0xFF));
      }
      acc = 0;
      n = 0;
      continue;
    }
    const int v = b64_value(c);
    if (v < 0) return false;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    if (++n == 4) {
      out.push_back(static_cast<char>((acc >> 16) & 0xFF));
      out.push_back(static_cast<char>((acc >> 8) & 0xFF));
      out.push_back(static_cast<char>(acc & 0xFF));
      acc = 0;
      n = 0;
    }
  }
  if (n == 2) out.push_back(static_cast<char>((acc >> 4) & 0xFF));
  if (n == 3) {
    out.push_back(static_cast<char>((acc >> 10) & 0xFF));
    out.push_back(static_cast<char>((acc >> 2) & 0xFF));
  }
  return n != 1;
}

// ---------- XML scanning ----------
struct Attribute {
  std::string_view name, value;
};
struct Tag {
  std::string_view name;
  std::vector<Attribute> attributes;
  bool closing = false, self_closing = false;
  std::size_t begin = 0, end = 0;  // [begin, end) = '<' ... '>'
  std::string_view attr(std::string_view key) const {
    for (const Attribute& a : attributes)
      if (a.name == key) return a.value;
    return {};
  }
  bool has(std::string_view key) const {
    for (const Attribute& a : attributes)
      if (a.name == key) return true;
    return false;
  }
};

enum class NumType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64, Invalid };
NumType num_type(std::string_view t) {
  if (t == "Int8" || t == "Char") return NumType::Int8;
  if (t == "UInt8" || t == "UChar") return NumType::UInt8;
  if (t == "Int16") return NumType::Int16;
  if (t == "UInt16") return NumType::UInt16;
  if (t == "Int32") return NumType::Int32;
  if (t == "UInt32") return NumType::UInt32;
  if (t == "Int64") return NumType::Int64;
  if (t == "UInt64") return NumType::UInt64;
  if (t == "Float32") return NumType::Float32;
  if (t == "Float64") return NumType::Float64;
  return NumType::Invalid;
}
std::size_t num_size(NumType t) {
  switch (t) {
    case NumType::Int8: case NumType::UInt8: return 1;
    case NumType::Int16: case NumType::UInt16: return 2;
    case NumType::Int32: case NumType::UInt32: case NumType::Float32: return 4;
    default: return 8;
  }
}

class VtuReader {
 public:
  VtuReader(const std::string& path, const std::string& data) : path_(path), data_(data) {}
  TetMeshData read(std::vector<CellDataArray>* cell_data);

 private:
  [[noreturn]] void fail(std::size_t pos, const std::string& reason) const {
    throw_bad_input(path_, line_at(pos), reason);
  }
  std::size_t line_at(std::size_t pos) const {
    if (pos == std::string::npos || pos > data_.size()) return 0;
    return 1 + static_cast<std::size_t>(std::count(data_.begin(), data_.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
  }
  bool next_tag(std::size_t& pos, Tag& tag);
  // Values of a DataArray as doubles (exact for every integer up to 2^53 and all stored doubles).
  void array_values(const Tag& tag, std::size_t content_begin, std::size_t expected, std::vector<double>* as_double,
                    std::vector<std::int64_t>* as_int);
  std::uint64_t load(const unsigned char* p, std::size_t size) const {
    std::uint64_t v = 0;
    if (little_endian_)
      for (std::size_t i = size; i-- > 0;) v = (v << 8) | p[i];
    else
      for (std::size_t i = 0; i < size; ++i) v = (v << 8) | p[i];
    return v;
  }
  void decode_binary(const unsigned char* p, NumType type, std::size_t count, std::vector<double>* d,
                     std::vector<std::int64_t>* n, std::size_t pos);

  const std::string& path_;
  const std::string& data_;
  std::size_t xml_end_ = 0;          // XML part ends where AppendedData's payload starts
  std::size_t appended_begin_ = std::string::npos;  // first byte after '_'
  bool appended_base64_ = false;
  bool little_endian_ = true;
  std::size_t header_size_ = 4;
  Tag connectivity_tag_;
};

bool VtuReader::next_tag(std::size_t& pos, Tag& tag) {
  while (true) {
    const std::size_t lt = data_.find('<', pos);
    if (lt == std::string::npos || lt >= xml_end_) return false;
    if (data_.compare(lt, 4, "<!--") == 0) {
      const std::size_t e = data_.find("-->", lt + 4);
      if (e == std::string::npos) fail(lt, "unterminated XML comment");
      pos = e + 3;
      continue;
    }
    if (data_.compare(lt, 2, "<?") == 0 || data_.compare(lt, 2, "<!") == 0) {
      const std::size_t e = data_.find('>', lt);
      if (e == std::string::npos) fail(lt, "unterminated XML declaration");
      pos = e + 1;
      continue;
    }
    const std::size_t gt = data_.find('>', lt);
    if (gt == std::string::npos || gt > xml_end_) fail(lt, "unterminated XML tag");
    tag = Tag();
    tag.begin = lt;
    tag.end = gt + 1;
    std::size_t i = lt + 1;
    if (data_[i] == '/') tag.closing = true, ++i;
    std::size_t stop = gt;
    if (stop > i && data_[stop - 1] == '/') tag.self_closing = true, --stop;
    const std::size_t name_begin = i;
    while (i < stop && !io_detail::is_space(data_[i])) ++i;
    tag.name = std::string_view(data_.data() + name_begin, i - name_begin);
    while (i < stop) {
      while (i < stop && io_detail::is_space(data_[i])) ++i;
      if (i >= stop) break;
      const std::size_t an = i;
      while (i < stop && data_[i] != '=' && !io_detail::is_space(data_[i])) ++i;
      const std::string_view aname(data_.data() + an, i - an);
      while (i < stop && io_detail::is_space(data_[i])) ++i;
      if (i >= stop || data_[i] != '=') fail(lt, "malformed XML attribute " + io_detail::quote(aname));
      ++i;
      while (i < stop && io_detail::is_space(data_[i])) ++i;
      if (i >= stop || (data_[i] != '"' && data_[i] != '\'')) fail(lt, "XML attribute value must be quoted");
      const char q = data_[i++];
      const std::size_t vb = i;
      while (i < stop && data_[i] != q) ++i;
      if (i >= stop) fail(lt, "unterminated XML attribute value");
      tag.attributes.push_back({aname, std::string_view(data_.data() + vb, i - vb)});
      ++i;
    }
    pos = gt + 1;
    return true;
  }
}

void VtuReader::decode_binary(const unsigned char* p, NumType type, std::size_t count, std::vector<double>* d,
                              std::vector<std::int64_t>* n, std::size_t pos) {
  const std::size_t sz = num_size(type);
  if (d) d->resize(count);
  if (n) n->resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t raw = load(p + i * sz, sz);
    double dv = 0;
    std::int64_t iv = 0;
    bool integral = true;
    switch (type) {
      case NumType::Int8: iv = static_cast<std::int8_t>(raw); break;
      case NumType::UInt8: iv = static_cast<std::uint8_t>(raw); break;
      case NumType::Int16: iv = static_cast<std::int16_t>(raw); break;
      case NumType::UInt16: iv = static_cast<std::uint16_t>(raw); break;
      case NumType::Int32: iv = static_cast<std::int32_t>(raw); break;
      case NumType::UInt32: iv = static_cast<std::uint32_t>(raw); break;
      case NumType::Int64: iv = static_cast<std::int64_t>(raw); break;
      case NumType::UInt64: iv = raw > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) ? -1 : static_cast<std::int64_t>(raw); break;
      case NumType::Float32: {
        const auto b = static_cast<std::uint32_t>(raw);
        float f;
        std::memcpy(&f, &b, 4);
        dv = f;
        integral = false;
        break;
      }
      default: {
        std::memcpy(&dv, &raw, 8);
        integral = false;
        break;
      }
    }
    if (integral) dv = static_cast<double>(iv);
    if (!integral && !std::isfinite(dv)) fail(pos, "non-finite value in a DataArray");
    if (!integral && n) {
      if (dv != std::floor(dv) || std::fabs(dv) > 9e15) fail(pos, "non-integer value in an integer array");
      iv = static_cast<std::int64_t>(dv);
    }
    if (d) (*d)[i] = dv;
    if (n) (*n)[i] = iv;
  }
}

void VtuReader::array_values(const Tag& tag, std::size_t content_begin, std::size_t expected,
                             std::vector<double>* as_double, std::vector<std::int64_t>* as_int) {
  const NumType type = num_type(tag.attr("type"));
  if (type == NumType::Invalid) fail(tag.begin, "DataArray: unsupported type " + io_detail::quote(tag.attr("type")));
  const std::string_view format = tag.attr("format");
  if (format == "ascii") {
    const std::size_t content_end = data_.find('<', content_begin);
    if (content_end == std::string::npos) fail(tag.begin, "unterminated DataArray");
    if (expected / 2 > content_end - content_begin) fail(tag.begin, "DataArray: fewer values than declared");
    io_detail::Tokenizer tok(data_.data() + content_begin, data_.data() + content_end, false);
    const std::size_t first_line = line_at(content_begin);
    for (std::size_t k = 1; k < first_line; ++k) tok.count_line();
    if (as_double) as_double->resize(expected);
    if (as_int) as_int->resize(expected);
    io_detail::Token t;
    const bool is_float = type == NumType::Float32 || type == NumType::Float64;
    for (std::size_t i = 0; i < expected; ++i) {
      if (!tok.next(t))
        throw_bad_input(path_, tok.last_line(), "DataArray " + io_detail::quote(tag.attr("Name")) + ": " + std::to_string(i) +
                                                    " of " + std::to_string(expected) + " values");
      if (is_float) {
        double v;
        if (!io_detail::parse_double(t.text, v)) v = io_detail::expect_double(t, path_, "DataArray value");
        if (type == NumType::Float32) v = static_cast<float>(v);
        if (as_double) (*as_double)[i] = v;
        if (as_int) {
          if (v != std::floor(v) || std::fabs(v) > 9e15) throw_bad_input(path_, t.line, "non-integer value in an integer array");
          (*as_int)[i] = static_cast<std::int64_t>(v);
        }
      } else {
        std::int64_t v;
        if (!io_detail::parse_int64(t.text, v)) v = io_detail::expect_int(t, path_, "DataArray value");
        if (as_double) (*as_double)[i] = static_cast<double>(v);
        if (as_int) (*as_int)[i] = v;
      }
    }
    if (tok.next(t)) throw_bad_input(path_, t.line, "DataArray: more values than declared");
    return;
  }
  const std::size_t sz = num_size(type);
  if (expected > std::numeric_limits<std::size_t>::max() / sz) fail(tag.begin, "DataArray too large");
  const std::size_t bytes = expected * sz;
  if (format == "binary") {
    const std::size_t content_end = data_.find('<', content_begin);
    if (content_end == std::string::npos) fail(tag.begin, "unterminated DataArray");
    std::string decoded;
    if (!decode_base64(std::string_view(data_.data() + content_begin, content_end - content_begin), decoded))
      fail(content_begin, "DataArray: invalid base64");
    if (decoded.size() < header_size_) fail(content_begin, "DataArray: missing binary header");
    const std::uint64_t declared = load(reinterpret_cast<const unsigned char*>(decoded.data()), header_size_);
    if (declared != bytes || decoded.size() < header_size_ + bytes)
      fail(content_begin, "DataArray " + io_detail::quote(tag.attr("Name")) + ": binary block holds " + std::to_string(declared) +
                              " bytes, " + std::to_string(bytes) + " expected");
    decode_binary(reinterpret_cast<const unsigned char*>(decoded.data()) + header_size_, type, expected, as_double, as_int,
                  content_begin);
    return;
  }
  if (format == "appended") {
    if (appended_begin_ == std::string::npos) fail(tag.begin, "appended DataArray but no AppendedData section");
    std::int64_t offset;
    if (!io_detail::parse_int64(tag.attr("offset"), offset) || offset < 0) fail(tag.begin, "DataArray: bad offset");
    if (appended_base64_) {
      // Base64 appended data: each array is encoded separately starting at `offset` characters.
      const std::size_t start = appended_begin_ + static_cast<std::size_t>(offset);
      std::size_t stop = data_.find('<', start);
      if (start > data_.size() || stop == std::string::npos) fail(tag.begin, "DataArray offset beyond the data");
      std::string header_dec, decoded;
      const std::size_t header_chars = (header_size_ + 2) / 3 * 4;
      if (!decode_base64(std::string_view(data_.data() + start, std::min(header_chars, stop - start)), header_dec) ||
          header_dec.size() < header_size_)
        fail(tag.begin, "DataArray: invalid base64 header");
      const std::uint64_t declared = load(reinterpret_cast<const unsigned char*>(header_dec.data()), header_size_);
      if (declared != bytes) fail(tag.begin, "DataArray: appended block size mismatch");
      const std::size_t total_chars = (header_size_ + bytes + 2) / 3 * 4;
      if (!decode_base64(std::string_view(data_.data() + start, std::min(total_chars, stop - start)), decoded) ||
          decoded.size() < header_size_ + bytes)
        fail(tag.begin, "DataArray: truncated appended base64 data");
      decode_binary(reinterpret_cast<const unsigned char*>(decoded.data()) + header_size_, type, expected, as_double,
                    as_int, tag.begin);
      return;
    }
    const std::size_t start = appended_begin_ + static_cast<std::size_t>(offset);
    if (start > data_.size() || data_.size() - start < header_size_) fail(tag.begin, "DataArray offset beyond the file");
    const auto* p = reinterpret_cast<const unsigned char*>(data_.data() + start);
    const std::uint64_t declared = load(p, header_size_);
    if (declared != bytes)
      fail(tag.begin, "DataArray " + io_detail::quote(tag.attr("Name")) + ": appended block holds " + std::to_string(declared) +
                          " bytes, " + std::to_string(bytes) + " expected");
    if (data_.size() - start - header_size_ < bytes) fail(tag.begin, "DataArray: appended data truncated");
    decode_binary(p + header_size_, type, expected, as_double, as_int, tag.begin);
    return;
  }
  fail(tag.begin, "DataArray: unsupported format " + io_detail::quote(format));
}

TetMeshData VtuReader::read(std::vector<CellDataArray>* cell_data) {
  if (data_.find_first_not_of(" \t\r\n") == std::string::npos) throw_bad_input(path_, 0, "empty file (not a .vtu file)");
  // The XML part ends at the AppendedData payload (raw bytes may contain '<').
  xml_end_ = data_.size();
  const std::size_t ad = data_.find("<AppendedData");
  if (ad != std::string::npos) {
    const std::size_t gt = data_.find('>', ad);
    if (gt == std::string::npos) fail(ad, "unterminated AppendedData tag");
    const std::size_t underscore = data_.find('_', gt);
    if (underscore == std::string::npos) fail(ad, "AppendedData without the '_' marker");
    appended_begin_ = underscore + 1;
    const std::string_view head(data_.data() + ad, gt - ad);
    appended_base64_ = head.find("base64") != std::string_view::npos;
    xml_end_ = gt + 1;
  }
  std::size_t pos = 0;
  Tag tag;
  bool have_file = false, have_piece = false;
  std::size_t np = 0, nc = 0;
  enum Section { None, Points, Cells, PointData, CellData } section = None;
  std::vector<double> xyz;
  std::vector<std::int64_t> connectivity, offsets, types, vlabels, clabels;
  bool have_points = false, have_conn = false, have_off = false, have_types = false;
  std::vector<CellDataArray> arrays;
  while (next_tag(pos, tag)) {
    if (tag.closing) {
      if (tag.name == "Points" || tag.name == "Cells" || tag.name == "PointData" || tag.name == "CellData") section = None;
      continue;
    }
    if (tag.name == "VTKFile") {
      if (tag.attr("type") != "UnstructuredGrid")
        throw Error(ErrorKind::Unsupported, path_, line_at(tag.begin),
                    "VTKFile type " + io_detail::quote(tag.attr("type")) + " is not supported (UnstructuredGrid only)");
      if (tag.has("compressor") && !tag.attr("compressor").empty())
        throw Error(ErrorKind::Unsupported, path_, line_at(tag.begin), "compressed .vtu files are not supported");
      const std::string_view bo = tag.attr("byte_order");
      little_endian_ = bo != "BigEndian";
      const std::string_view ht = tag.attr("header_type");
      header_size_ = ht == "UInt64" ? 8 : 4;
      if (!ht.empty() && ht != "UInt64" && ht != "UInt32") fail(tag.begin, "unsupported header_type");
      have_file = true;
    } else if (tag.name == "Piece") {
      if (have_piece) throw Error(ErrorKind::Unsupported, path_, line_at(tag.begin), "more than one Piece is not supported");
      std::int64_t a, b;
      if (!io_detail::parse_int64(tag.attr("NumberOfPoints"), a) || !io_detail::parse_int64(tag.attr("NumberOfCells"), b) ||
          a < 0 || b < 0 || a > std::numeric_limits<std::uint32_t>::max() || b > std::numeric_limits<std::uint32_t>::max())
        fail(tag.begin, "Piece: bad NumberOfPoints/NumberOfCells");
      // Every point needs >= 3 bytes and every cell >= 3 (ascii "0 " ids) in any encoding.
      if (static_cast<std::uint64_t>(a) > data_.size() || static_cast<std::uint64_t>(b) > data_.size())
        fail(tag.begin, "Piece: declared counts cannot fit in the file");
      np = static_cast<std::size_t>(a), nc = static_cast<std::size_t>(b);
      have_piece = true;
    } else if (tag.name == "Points") {
      section = Points;
    } else if (tag.name == "Cells") {
      section = Cells;
    } else if (tag.name == "PointData") {
      section = PointData;
    } else if (tag.name == "CellData") {
      section = CellData;
    } else if (tag.name == "DataArray") {
      if (!have_piece) fail(tag.begin, "DataArray outside a Piece");
      const std::string_view name = tag.attr("Name");
      std::int64_t comps = 1;
      if (tag.has("NumberOfComponents") && (!io_detail::parse_int64(tag.attr("NumberOfComponents"), comps) || comps < 1 || comps > 64))
        fail(tag.begin, "DataArray: bad NumberOfComponents");
      const std::size_t after = tag.end;
      if (section == Points) {
        if (comps != 3) fail(tag.begin, "Points DataArray must have 3 components");
        array_values(tag, after, 3 * np, &xyz, nullptr);
        have_points = true;
      } else if (section == Cells) {
        if (name == "connectivity") {
          // Size known only from offsets: read offsets first if needed by a second pass.
          connectivity_tag_ = tag;
          have_conn = true;
        } else if (name == "offsets") {
          array_values(tag, after, nc, nullptr, &offsets);
          have_off = true;
        } else if (name == "types") {
          array_values(tag, after, nc, nullptr, &types);
          have_types = true;
        }
      } else if (section == PointData && name == "label" && comps == 1) {
        array_values(tag, after, np, nullptr, &vlabels);
      } else if (section == CellData && comps == 1) {
        if (name == "label") {
          array_values(tag, after, nc, nullptr, &clabels);
        } else if (cell_data) {
          CellDataArray a;
          a.name = std::string(name);
          array_values(tag, after, nc, &a.values, nullptr);
          arrays.push_back(std::move(a));
        }
      }
      // Other arrays (vectors, unknown data) are skipped.
    }
  }
  if (!have_file) fail(0, "no <VTKFile type=\"UnstructuredGrid\"> element");
  if (!have_piece) fail(0, "no <Piece> element");
  if (!have_points && np > 0) fail(0, "no Points DataArray");
  if (!have_conn || !have_off || !have_types) fail(0, "Cells needs connectivity, offsets and types arrays");
  std::int64_t previous = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    if (offsets[c] < previous) fail(connectivity_tag_.begin, "offsets decrease at cell " + std::to_string(c));
    previous = offsets[c];
  }
  const std::size_t conn_size = nc ? static_cast<std::size_t>(offsets[nc - 1]) : 0;
  if (conn_size > data_.size()) fail(connectivity_tag_.begin, "offsets exceed what the file can hold");
  array_values(connectivity_tag_, connectivity_tag_.end, conn_size, nullptr, &connectivity);

  TetMeshData mesh;
  mesh.xyz = std::move(xyz);
  mesh.xyz.resize(3 * np);
  mesh.vertex_labels.assign(np, 0);
  for (std::size_t i = 0; i < vlabels.size() && i < np; ++i) mesh.vertex_labels[i] = static_cast<std::int32_t>(vlabels[i]);
  std::vector<std::size_t> kept;
  mesh.tets.reserve(4 * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::int64_t begin = c ? offsets[c - 1] : 0;
    const std::int64_t size = offsets[c] - begin;
    const std::int64_t type = types[c];
    if (type >= 1 && type <= 9) continue;
    if (type != 10)
      throw Error(ErrorKind::Unsupported, path_, line_at(connectivity_tag_.begin),
                  "cell " + std::to_string(c) + " has VTK type " + std::to_string(type) + " (only tetrahedra, type 10, are supported)");
    if (size != 4) fail(connectivity_tag_.begin, "cell " + std::to_string(c) + " is a tet with " + std::to_string(size) + " ids");
    for (std::int64_t j = begin; j < offsets[c]; ++j) {
      const std::int64_t id = connectivity[static_cast<std::size_t>(j)];
      if (id < 0 || static_cast<std::uint64_t>(id) >= np)
        fail(connectivity_tag_.begin, "cell " + std::to_string(c) + ": vertex id " + std::to_string(id) + " outside [0," +
                                          std::to_string(np) + ")");
      mesh.tets.push_back(static_cast<std::uint32_t>(id));
    }
    kept.push_back(c);
  }
  mesh.tet_labels.assign(kept.size(), 0);
  if (clabels.size() == nc)
    for (std::size_t i = 0; i < kept.size(); ++i) {
      const std::int64_t l = clabels[kept[i]];
      if (l < std::numeric_limits<std::int32_t>::min() || l > std::numeric_limits<std::int32_t>::max())
        fail(0, "cell label out of 32-bit range");
      mesh.tet_labels[i] = static_cast<std::int32_t>(l);
    }
  if (cell_data) {
    for (CellDataArray& a : arrays) {
      std::vector<double> v(kept.size());
      for (std::size_t i = 0; i < kept.size(); ++i) v[i] = a.values[kept[i]];
      a.values = std::move(v);
    }
    *cell_data = std::move(arrays);
  }
  return mesh;
}

// ---------- writer ----------
std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

TetMeshData read_vtu(const std::string& path) {
  const std::string data = io_detail::read_whole_file(path, {/*text=*/false, /*text_prefix=*/32});
  VtuReader reader(path, data);
  return reader.read(nullptr);
}

TetMeshData read_vtu(const std::string& path, std::vector<CellDataArray>& cell_data) {
  const std::string data = io_detail::read_whole_file(path, {/*text=*/false, /*text_prefix=*/32});
  VtuReader reader(path, data);
  return reader.read(&cell_data);
}

void write_vtu(const std::string& path, const TetMeshData& mesh, const std::vector<CellDataArray>& cell_data) {
  write_vtu(path, mesh, cell_data, VtuEncoding::AppendedRaw);
}

void write_vtu(AtomicOutput& out, const TetMeshData& mesh, const std::vector<CellDataArray>& cell_data,
               VtuEncoding encoding) {
  const std::string& path = out.destination();
  io_detail::check_mesh_writable(mesh, path);
  const std::size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  for (const CellDataArray& a : cell_data) {
    if (a.name.empty() || a.name == "label")
      throw Error(ErrorKind::BadInput, path, 0, "cannot write: cell data array name empty or reserved ('label')");
    if (a.values.size() != nt)
      throw Error(ErrorKind::BadInput, path, 0, "cannot write: cell data '" + a.name + "' has " + std::to_string(a.values.size()) +
                                                    " values for " + std::to_string(nt) + " tets");
    for (double v : a.values)
      if (!std::isfinite(v)) throw Error(ErrorKind::BadInput, path, 0, "cannot write: non-finite value in cell data '" + a.name + "'");
  }
  const bool vlabels = std::any_of(mesh.vertex_labels.begin(), mesh.vertex_labels.end(), [](std::int32_t x) { return x != 0; });
  const bool tlabels = std::any_of(mesh.tet_labels.begin(), mesh.tet_labels.end(), [](std::int32_t x) { return x != 0; });
  const bool raw = encoding == VtuEncoding::AppendedRaw;

  io_detail::TextWriter w(out);
  std::uint64_t offset = 0;  // running offset into the appended block
  auto open_array = [&](const char* type, const std::string& name, int comps, std::size_t bytes) {
    w.put("        <DataArray type=\"");
    w.put(type);
    w.put('"');
    if (!name.empty()) {
      w.put(" Name=\"");
      w.put(xml_escape(name));
      w.put('"');
    }
    if (comps != 1) {
      w.put(" NumberOfComponents=\"");
      w.put_int(comps);
      w.put('"');
    }
    if (raw) {
      w.put(" format=\"appended\" offset=\"");
      w.put_int(static_cast<std::int64_t>(offset));
      w.put("\"/>\n");
      offset += 8 + bytes;
    } else {
      w.put(" format=\"ascii\">\n");
    }
  };
  auto close_array = [&]() {
    if (!raw) w.put("\n        </DataArray>\n");
  };
  auto ascii_ints = [&](auto&& value_at, std::size_t count, std::size_t per_line) {
    for (std::size_t i = 0; i < count; ++i) {
      w.put_int(value_at(i));
      w.put((i + 1) % per_line == 0 && i + 1 < count ? '\n' : ' ');
    }
  };
  w.put("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  w.put("  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"");
  w.put_int(static_cast<std::int64_t>(nv));
  w.put("\" NumberOfCells=\"");
  w.put_int(static_cast<std::int64_t>(nt));
  w.put("\">\n");
  if (vlabels) {
    w.put("      <PointData>\n");
    open_array("Int32", "label", 1, 4 * nv);
    if (!raw) ascii_ints([&](std::size_t i) { return mesh.vertex_labels[i]; }, nv, 16);
    close_array();
    w.put("      </PointData>\n");
  }
  if (tlabels || !cell_data.empty()) {
    w.put("      <CellData>\n");
    if (tlabels) {
      open_array("Int32", "label", 1, 4 * nt);
      if (!raw) ascii_ints([&](std::size_t i) { return mesh.tet_labels[i]; }, nt, 16);
      close_array();
    }
    for (const CellDataArray& a : cell_data) {
      open_array("Float64", a.name, 1, 8 * nt);
      if (!raw)
        for (std::size_t i = 0; i < nt; ++i) {
          w.put_double(a.values[i]);
          w.put((i + 1) % 6 == 0 && i + 1 < nt ? '\n' : ' ');
        }
      close_array();
    }
    w.put("      </CellData>\n");
  }
  w.put("      <Points>\n");
  open_array("Float64", "Points", 3, 8 * 3 * nv);
  if (!raw)
    for (std::size_t i = 0; i < nv; ++i) {
      for (int c = 0; c < 3; ++c) {
        w.put_double(mesh.xyz[3 * i + c]);
        w.put(c == 2 ? (i + 1 < nv ? '\n' : ' ') : ' ');
      }
    }
  close_array();
  w.put("      </Points>\n      <Cells>\n");
  open_array("Int64", "connectivity", 1, 8 * 4 * nt);
  if (!raw) ascii_ints([&](std::size_t i) { return static_cast<std::int64_t>(mesh.tets[i]); }, 4 * nt, 4);
  close_array();
  open_array("Int64", "offsets", 1, 8 * nt);
  if (!raw) ascii_ints([&](std::size_t i) { return static_cast<std::int64_t>(4 * (i + 1)); }, nt, 8);
  close_array();
  open_array("UInt8", "types", 1, nt);
  if (!raw) ascii_ints([](std::size_t) { return std::int64_t(10); }, nt, 32);
  close_array();
  w.put("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n");
  if (raw) {
    w.put("  <AppendedData encoding=\"raw\">\n   _");
    // Little-endian payloads, each preceded by its UInt64 byte count (x86/ARM hosts are little-endian;
    // bytes are assembled explicitly so the output does not depend on the host).
    std::string block;
    auto put_le = [&](std::uint64_t v, std::size_t size) {
      for (std::size_t i = 0; i < size; ++i) block.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
      if (block.size() >= (1 << 20)) w.put(block), block.clear();
    };
    auto put_double_le = [&](double d) {
      std::uint64_t u;
      std::memcpy(&u, &d, 8);
      put_le(u, 8);
    };
    if (vlabels) {
      put_le(4 * nv, 8);
      for (std::size_t i = 0; i < nv; ++i) put_le(static_cast<std::uint32_t>(mesh.vertex_labels[i]), 4);
    }
    if (tlabels) {
      put_le(4 * nt, 8);
      for (std::size_t i = 0; i < nt; ++i) put_le(static_cast<std::uint32_t>(mesh.tet_labels[i]), 4);
    }
    for (const CellDataArray& a : cell_data) {
      put_le(8 * nt, 8);
      for (double v : a.values) put_double_le(v);
    }
    put_le(8 * 3 * nv, 8);
    for (double v : mesh.xyz) put_double_le(v);
    put_le(8 * 4 * nt, 8);
    for (std::uint32_t id : mesh.tets) put_le(id, 8);
    put_le(8 * nt, 8);
    for (std::size_t i = 0; i < nt; ++i) put_le(4 * (i + 1), 8);
    put_le(nt, 8);
    for (std::size_t i = 0; i < nt; ++i) put_le(10, 1);
    w.put(block);
    w.put("\n  </AppendedData>\n");
  }
  w.put("</VTKFile>\n");
  w.flush();
}

void write_vtu(const std::string& path, const TetMeshData& mesh, const std::vector<CellDataArray>& cell_data,
               VtuEncoding encoding) {
  AtomicOutput out(path);
  write_vtu(out, mesh, cell_data, encoding);
  out.commit();
}

}  // namespace volmap
