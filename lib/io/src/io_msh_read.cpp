// Gmsh .msh reader: MSH 2.x (2.0-2.2) and 4.1, ASCII and binary (what is kept: io.hpp and
// volmap-reference.md §2.7).
// Layout rules this reader relies on (Gmsh reference manual, "MSH file format"):
//  - `$MeshFormat` first: `version file-type data-size`; binary files follow the line with the int 1
//    in the file's byte order (our endianness marker) and a newline.
//  - Binary payloads start right after the newline of their section's last ASCII line: `$Nodes` /
//    `$Elements` plus a count line in 2.x, the section keyword line alone in 4.1. Ints are 4 bytes;
//    2.x doubles are data-size (8) bytes; 4.1 size_t fields are data-size (4 or 8) bytes, doubles 8.
//  - $NodeData headers (string, real and integer tags) are ASCII in both encodings; binary entries
//    are a 4-byte node tag followed by the values.
//  - Unknown sections are skipped up to their `$End<name>` line; `$Elements` must follow `$Nodes`.
// Every count is checked against the bytes left in the file before anything is allocated. Errors
// name the file and the line (binary errors also give the byte offset).
#include <volmap/core/count_text.hpp>
#include <volmap/io/io.hpp>

#include "io_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

namespace volmap {
namespace {

using io_detail::Token;
using io_detail::Tokenizer;

struct GmshElementType {
  int code;
  int nodes;
  int dim;
  const char* family;
  int corners;  // nodes of the linear element of the family
};

// Gmsh element types (code, nodes, dimension). Codes not listed are refused as unknown.
constexpr GmshElementType kElementTypes[] = {
    {1, 2, 1, "line", 2},           {2, 3, 2, "triangle", 3},       {3, 4, 2, "quadrangle", 4},
    {4, 4, 3, "tetrahedron", 4},    {5, 8, 3, "hexahedron", 8},     {6, 6, 3, "prism", 6},
    {7, 5, 3, "pyramid", 5},        {8, 3, 1, "line", 2},           {9, 6, 2, "triangle", 3},
    {10, 9, 2, "quadrangle", 4},    {11, 10, 3, "tetrahedron", 4},  {12, 27, 3, "hexahedron", 8},
    {13, 18, 3, "prism", 6},        {14, 14, 3, "pyramid", 5},      {15, 1, 0, "point", 1},
    {16, 8, 2, "quadrangle", 4},    {17, 20, 3, "hexahedron", 8},   {18, 15, 3, "prism", 6},
    {19, 13, 3, "pyramid", 5},      {20, 9, 2, "triangle", 3},      {21, 10, 2, "triangle", 3},
    {22, 12, 2, "triangle", 3},     {23, 15, 2, "triangle", 3},     {24, 15, 2, "triangle", 3},
    {25, 21, 2, "triangle", 3},     {26, 4, 1, "line", 2},          {27, 5, 1, "line", 2},
    {28, 6, 1, "line", 2},          {29, 20, 3, "tetrahedron", 4},  {30, 35, 3, "tetrahedron", 4},
    {31, 56, 3, "tetrahedron", 4},  {36, 16, 2, "quadrangle", 4},   {37, 25, 2, "quadrangle", 4},
    {38, 36, 2, "quadrangle", 4},   {42, 28, 2, "triangle", 3},     {43, 36, 2, "triangle", 3},
    {44, 45, 2, "triangle", 3},     {45, 55, 2, "triangle", 3},     {46, 66, 2, "triangle", 3},
    {47, 49, 2, "quadrangle", 4},   {48, 64, 2, "quadrangle", 4},   {49, 81, 2, "quadrangle", 4},
    {50, 100, 2, "quadrangle", 4},  {51, 121, 2, "quadrangle", 4},  {62, 7, 1, "line", 2},
    {63, 8, 1, "line", 2},          {64, 9, 1, "line", 2},          {65, 10, 1, "line", 2},
    {66, 11, 1, "line", 2},         {71, 84, 3, "tetrahedron", 4},  {72, 120, 3, "tetrahedron", 4},
    {73, 165, 3, "tetrahedron", 4}, {74, 220, 3, "tetrahedron", 4}, {75, 286, 3, "tetrahedron", 4},
    {90, 40, 3, "prism", 6},        {91, 75, 3, "prism", 6},        {92, 64, 3, "hexahedron", 8},
    {93, 125, 3, "hexahedron", 8},  {94, 216, 3, "hexahedron", 8},  {95, 343, 3, "hexahedron", 8},
    {96, 512, 3, "hexahedron", 8},  {97, 729, 3, "hexahedron", 8},  {98, 1000, 3, "hexahedron", 8},
    {106, 126, 3, "prism", 6},      {107, 196, 3, "prism", 6},      {108, 288, 3, "prism", 6},
    {109, 405, 3, "prism", 6},      {110, 550, 3, "prism", 6}};
constexpr int kLinearTet = 4;

const GmshElementType* find_element_type(std::int64_t code) {
  for (const GmshElementType& t : kElementTypes)
    if (t.code == code) return &t;
  return nullptr;
}

std::string type_name(const GmshElementType& t) {
  return t.nodes == t.corners ? std::string(t.family) : std::string(t.family) + " (" + std::to_string(t.nodes) + "-node)";
}

constexpr std::size_t kMaxVertices = std::numeric_limits<std::uint32_t>::max() - 1;
constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

// Node tag -> position in file order: a dense table when tags are compact, else a sorted list.
class NodeIndex {
 public:
  // Returns the first tag that occurs twice, or 0 when all are distinct (tags are >= 1).
  std::uint64_t build(const std::vector<std::uint64_t>& tags, std::uint64_t max_tag) {
    dense_.clear();
    sorted_.clear();
    if (max_tag <= 2 * tags.size() + 1024) {
      dense_.assign(max_tag + 1, kNoVertex);
      for (std::size_t i = 0; i < tags.size(); ++i) {
        if (dense_[tags[i]] != kNoVertex) return tags[i];
        dense_[tags[i]] = static_cast<std::uint32_t>(i);
      }
      return 0;
    }
    sorted_.reserve(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i) sorted_.emplace_back(tags[i], static_cast<std::uint32_t>(i));
    std::sort(sorted_.begin(), sorted_.end());
    for (std::size_t i = 1; i < sorted_.size(); ++i)
      if (sorted_[i].first == sorted_[i - 1].first) return sorted_[i].first;
    return 0;
  }
  std::uint32_t find(std::uint64_t tag) const {
    if (!sorted_.empty() || dense_.empty()) {
      const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(tag, std::uint32_t(0)));
      return it != sorted_.end() && it->first == tag ? it->second : kNoVertex;
    }
    return tag < dense_.size() ? dense_[tag] : kNoVertex;
  }

 private:
  std::vector<std::uint32_t> dense_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> sorted_;
};

class MshReader {
 public:
  MshReader(const std::string& path, const std::string& data, TetMeshReadNotes* notes)
      : path_(path), tok_(data.data(), data.data() + data.size(), /*hash_comments=*/false), notes_(notes) {}
  TetMeshData read();

 private:
  // ---- errors and low-level reading (ASCII tokens or binary values, by the current mode) ----
  [[noreturn]] void fail(const std::string& reason) const {
    if (binary_payload_)
      throw_bad_input(path_, tok_.line(), reason + " (byte offset " + std::to_string(tok_.position() - tok_.begin()) + ")");
    throw_bad_input(path_, tok_.last_line(), reason);
  }
  [[noreturn]] void unsupported(const std::string& reason) const {
    throw Error(ErrorKind::Unsupported, path_, binary_payload_ ? tok_.line() : tok_.last_line(), reason);
  }
  Token next_token(const char* what) {
    Token t;
    if (!tok_.next(t)) fail(std::string("unexpected end of file: expected ") + what);
    return t;
  }
  const unsigned char* take(std::size_t bytes, const char* what) {
    if (tok_.remaining() < bytes)
      fail(std::string(what) + ": binary data truncated (" + std::to_string(bytes) + " bytes needed, " +
           std::to_string(tok_.remaining()) + " left)");
    const auto* p = reinterpret_cast<const unsigned char*>(tok_.position());
    tok_.advance_to(tok_.position() + bytes);
    return p;
  }
  std::uint64_t load(const unsigned char* p, std::size_t bytes) const {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < bytes; ++i) v |= std::uint64_t(p[big_endian_ ? bytes - 1 - i : i]) << (8 * i);
    return v;
  }
  std::int64_t read_int(const char* what) {
    if (binary_payload_) return static_cast<std::int32_t>(static_cast<std::uint32_t>(load(take(4, what), 4)));
    return io_detail::expect_int(next_token(what), path_, what);
  }
  std::uint64_t read_size(const char* what) {
    if (binary_payload_) {
      const std::uint64_t v = load(take(size_bytes_, what), size_bytes_);
      if (v > (std::uint64_t(1) << 62)) fail(std::string(what) + ": value " + std::to_string(v) + " out of range");
      return v;
    }
    const std::int64_t v = io_detail::expect_int(next_token(what), path_, what);
    if (v < 0) fail(std::string(what) + ": negative value " + std::to_string(v));
    return static_cast<std::uint64_t>(v);
  }
  double read_double(const char* what) {
    double v;
    if (binary_payload_) {
      const std::uint64_t bits = load(take(8, what), 8);
      std::memcpy(&v, &bits, 8);
      if (!std::isfinite(v)) fail(std::string(what) + ": non-finite value");
      return v;
    }
    const Token t = next_token(what);
    if (!io_detail::parse_double(t.text, v)) io_detail::expect_double(t, path_, what);
    return v;
  }
  // A count written as an ASCII line (2.x $Nodes / $Elements, $NodeData tags), also in binary files.
  std::uint64_t ascii_count(const char* what) {
    const std::int64_t v = io_detail::expect_int(next_token(what), path_, what);
    if (v < 0) fail(std::string(what) + ": negative count " + std::to_string(v));
    return static_cast<std::uint64_t>(v);
  }
  std::int32_t read_int32(const char* what) {
    const std::int64_t v = read_int(what);
    if (v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
      fail(std::string(what) + ": " + std::to_string(v) + " out of 32-bit range");
    return static_cast<std::int32_t>(v);
  }
  // A declared count that must fit in the rest of the file: each element takes at least
  // `binary_bytes` (binary) or `ascii_bytes` (ASCII) bytes.
  std::size_t bounded(std::uint64_t n, std::size_t binary_bytes, std::size_t ascii_bytes, std::size_t max, const char* what) {
    const std::size_t each = binary_payload_ ? binary_bytes : ascii_bytes;
    if (n > max) fail(std::string(what) + ": count " + std::to_string(n) + " exceeds the supported maximum " + std::to_string(max));
    if (each > 0 && n > (static_cast<std::uint64_t>(tok_.remaining()) + 1) / each)
      fail(std::string(what) + ": declared count " + std::to_string(n) + " cannot fit in the remaining " +
           std::to_string(tok_.remaining()) + " bytes of the file (truncated or corrupt)");
    return static_cast<std::size_t>(n);
  }
  std::size_t read_count(const char* what, std::size_t binary_bytes, std::size_t ascii_bytes, std::size_t max = kMaxVertices) {
    return bounded(read_size(what), binary_bytes, ascii_bytes, max, what);
  }
  // Binary payloads start on the line after the section's last ASCII token.
  void begin_payload() {
    if (!binary_) return;
    tok_.skip_rest_of_line();
    binary_payload_ = true;
  }
  void expect_end(const std::string& section) {
    binary_payload_ = false;
    const std::string end = "$End" + section;
    Token t;
    if (!tok_.next(t)) fail("unexpected end of file: expected " + end);
    if (t.text != end)
      throw_bad_input(path_, t.line, "expected " + end + ", found " + io_detail::quote(t.text) +
                                         " (the counts of $" + section + " disagree with its content)");
  }
  void skip_section(const std::string& section);

  // ---- sections ----
  void read_format();
  void read_entities();
  void read_nodes();
  void read_elements();
  void read_element_block(const GmshElementType* type, std::int64_t code, std::size_t count, std::size_t tags_per_element,
                          std::int64_t entity, bool with_tag);
  void read_node_data();
  std::string read_quoted_string();
  void add_node(std::uint64_t tag, double x, double y, double z) {
    if (tag == 0) fail("node tag 0 (Gmsh node tags start at 1)");
    node_tags_.push_back(tag);
    max_node_tag_ = std::max(max_node_tag_, tag);
    xyz_.insert(xyz_.end(), {x, y, z});
  }
  void note_ignored(const GmshElementType& type, std::size_t count);
  TetMeshData assemble();

  const std::string& path_;
  Tokenizer tok_;
  TetMeshReadNotes* notes_;
  int version_ = 0;  // 2 or 41
  bool binary_ = false, big_endian_ = false, binary_payload_ = false;
  std::size_t size_bytes_ = 8;  // 4.1 size_t fields (the data-size of $MeshFormat)

  bool have_nodes_ = false, have_elements_ = false, have_entities_ = false, have_node_labels_ = false;
  std::vector<std::uint64_t> node_tags_;
  std::uint64_t max_node_tag_ = 0;
  std::vector<double> xyz_;
  NodeIndex index_;
  std::size_t nodes_line_ = 0;
  std::vector<std::uint32_t> tets_;  // 4 node positions per tet (file order)
  std::vector<std::int64_t> tet_physical_, tet_entity_;  // 2.x: per element; 4.1: physical from $Entities
  std::map<std::int64_t, std::vector<std::int32_t>> volume_physicals_;  // 4.1 volume entity -> physical tags
  std::vector<std::pair<std::uint32_t, std::int32_t>> node_labels_;   // $NodeData "label"
  std::vector<TetMeshReadNotes::IgnoredElements> ignored_;
};

void MshReader::skip_section(const std::string& section) {
  const std::string end = "$End" + section;
  const std::string_view rest(tok_.position(), tok_.remaining());
  std::size_t at = 0;
  while ((at = rest.find(end, at)) != std::string_view::npos) {
    const bool line_start = at == 0 ? tok_.position() == tok_.begin() || tok_.position()[-1] == '\n' : rest[at - 1] == '\n';
    const std::size_t after = at + end.size();
    const bool line_end = after == rest.size() || io_detail::is_space(rest[after]);
    if (line_start && line_end) {
      tok_.advance_to(tok_.position() + at);
      expect_end(section);
      return;
    }
    at = after;
  }
  fail("section $" + section + " has no " + end);
}

void MshReader::read_format() {
  Token t;
  if (!tok_.next(t)) throw_bad_input(path_, 0, "empty file (not a Gmsh .msh file)");
  if (t.text == "$NOD" || t.text == "$NOE")
    throw Error(ErrorKind::Unsupported, path_, t.line, "MSH version 1 is not supported (save as MSH 4.1 or 2.2)");
  if (t.text != "$MeshFormat")
    throw_bad_input(path_, t.line, "not a Gmsh .msh file: expected $MeshFormat, found " + io_detail::quote(t.text));
  const Token version = next_token("the MSH version");
  const std::string_view v = version.text;
  if (v == "2" || v == "2.0" || v == "2.1" || v == "2.2")
    version_ = 2;
  else if (v == "4.1")
    version_ = 41;
  else
    throw Error(ErrorKind::Unsupported, path_, version.line,
                "MSH version " + io_detail::quote(v) + " is not supported (2.2 and 4.1 are; Gmsh: -format msh22 or msh41)");
  const std::int64_t file_type = io_detail::expect_int(next_token("the file type"), path_, "file type");
  if (file_type != 0 && file_type != 1) fail("file type " + std::to_string(file_type) + " (0 = ASCII, 1 = binary)");
  binary_ = file_type == 1;
  const std::int64_t data_size = io_detail::expect_int(next_token("the data size"), path_, "data size");
  if (version_ == 2 ? data_size != 8 : (data_size != 4 && data_size != 8))
    throw Error(ErrorKind::Unsupported, path_, tok_.last_line(),
                "data size " + std::to_string(data_size) + (version_ == 2 ? " (MSH 2 files use 8-byte doubles)" : " (MSH 4.1: 4 or 8)"));
  if (version_ == 41) size_bytes_ = static_cast<std::size_t>(data_size);
  if (binary_) {
    begin_payload();
    const unsigned char* one = take(4, "endianness marker");
    if (one[0] == 1 && one[1] == 0 && one[2] == 0 && one[3] == 0)
      big_endian_ = false;
    else if (one[0] == 0 && one[1] == 0 && one[2] == 0 && one[3] == 1)
      big_endian_ = true;
    else
      fail("binary endianness marker is not the integer 1 in either byte order");
  }
  expect_end("MeshFormat");
}

void MshReader::read_entities() {
  have_entities_ = true;
  begin_payload();
  std::size_t counts[4];
  for (std::size_t& c : counts) c = read_count("number of entities", 4 + 24 + size_bytes_, 8);
  for (int dim = 0; dim < 4; ++dim) {
    for (std::size_t e = 0; e < counts[dim]; ++e) {
      const std::int32_t tag = read_int32("entity tag");
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) read_double("entity bounding box");
      const std::size_t nphys = read_count("number of physical tags", 4, 2, std::numeric_limits<std::size_t>::max());
      std::vector<std::int32_t> physicals;
      for (std::size_t k = 0; k < nphys; ++k) {
        const std::int32_t p = read_int32("physical tag");
        if (k < 8) physicals.push_back(p);
      }
      if (dim == 3) volume_physicals_[tag] = std::move(physicals);
      if (dim > 0) {
        const std::size_t nbound = read_count("number of bounding entities", 4, 2, std::numeric_limits<std::size_t>::max());
        for (std::size_t k = 0; k < nbound; ++k) read_int("bounding entity tag");
      }
    }
  }
  expect_end("Entities");
}

void MshReader::read_nodes() {
  if (have_nodes_) fail("second $Nodes section");
  have_nodes_ = true;
  nodes_line_ = tok_.last_line();
  if (version_ == 2) {
    const std::uint64_t declared = ascii_count("number of nodes");
    begin_payload();
    const std::size_t n = bounded(declared, 4 + 3 * 8, 8, kMaxVertices, "number of nodes");
    node_tags_.reserve(n);
    xyz_.reserve(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::int64_t tag = read_int("node tag");
      if (tag < 1) fail("node tag " + std::to_string(tag) + " (Gmsh node tags start at 1)");
      const double x = read_double("node x"), y = read_double("node y"), z = read_double("node z");
      add_node(static_cast<std::uint64_t>(tag), x, y, z);
    }
  } else {
    begin_payload();
    const std::size_t blocks = read_count("number of node blocks", 12 + size_bytes_, 8);
    const std::size_t n = read_count("number of nodes", size_bytes_ + 24, 8);
    read_size("minimum node tag");
    read_size("maximum node tag");
    node_tags_.reserve(n);
    xyz_.reserve(3 * n);
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = read_int("node block entity dimension");
      read_int("node block entity tag");
      const std::int64_t parametric = read_int("node block parametric flag");
      if (dim < 0 || dim > 3) fail("node block entity dimension " + std::to_string(dim) + " (0 to 3)");
      if (parametric != 0 && parametric != 1) fail("node block parametric flag " + std::to_string(parametric) + " (0 or 1)");
      const std::size_t extra = parametric ? static_cast<std::size_t>(dim) : 0;
      const std::size_t count = read_count("nodes in block", size_bytes_ + 8 * (3 + extra), 8);
      if (count > n - node_tags_.size())
        fail("node blocks hold more nodes than the " + std::to_string(n) + " the $Nodes header declares");
      const std::size_t first = node_tags_.size();
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint64_t tag = read_size("node tag");
        add_node(tag, 0, 0, 0);
      }
      for (std::size_t i = 0; i < count; ++i) {
        double* p = &xyz_[3 * (first + i)];
        p[0] = read_double("node x"), p[1] = read_double("node y"), p[2] = read_double("node z");
        for (std::size_t k = 0; k < extra; ++k) read_double("parametric coordinate");
      }
    }
    if (node_tags_.size() != n)
      fail("the $Nodes header declares " + std::to_string(n) + " nodes, its blocks hold " + std::to_string(node_tags_.size()));
  }
  expect_end("Nodes");
  if (const std::uint64_t dup = index_.build(node_tags_, max_node_tag_))
    throw_bad_input(path_, nodes_line_, "node tag " + std::to_string(dup) + " is defined twice");
}

void MshReader::note_ignored(const GmshElementType& type, std::size_t count) {
  for (auto& ig : ignored_)
    if (ig.code == type.code) {
      ig.count += count;
      return;
    }
  ignored_.push_back({type_name(type), type.code, count});
}

// Reads `count` elements of one type, each [tag] [tags_per_element tags] nodes (2.x ASCII lines start
// with tag, type and number of tags, read by the caller: with_tag is false then).
void MshReader::read_element_block(const GmshElementType* type, std::int64_t code, std::size_t count,
                                   std::size_t tags_per_element, std::int64_t entity, bool with_tag) {
  if (!type) unsupported("unknown Gmsh element type " + std::to_string(code));
  if (type->dim == 3 && type->code != kLinearTet)
    unsupported("element type " + std::to_string(code) + " (" + type_name(*type) +
                "): only linear tetrahedra are read; other 3D elements cannot be skipped without leaving holes");
  const bool tet = type->code == kLinearTet;
  const std::size_t value_bytes = version_ == 2 ? 4 : size_bytes_;
  const std::size_t values = (with_tag ? 1 : 0) + tags_per_element + static_cast<std::size_t>(type->nodes);
  bounded(count, value_bytes * values, 2 * values, kMaxVertices, "elements in block");
  if (!tet) {
    note_ignored(*type, count);
    if (binary_payload_) {
      take(count * values * value_bytes, "element data");
      return;
    }
    for (std::size_t i = 0; i < count * values; ++i) read_int("element data");
    return;
  }
  if (tets_.size() / 4 + count > kMaxVertices / 4) fail("too many tetrahedra");
  for (std::size_t i = 0; i < count; ++i) {
    if (with_tag) version_ == 2 ? static_cast<void>(read_int("element tag")) : static_cast<void>(read_size("element tag"));
    std::int64_t physical = 0, elementary = entity;
    for (std::size_t k = 0; k < tags_per_element; ++k) {
      const std::int64_t v = read_int("element tag list");
      if (k == 0) physical = v;
      if (k == 1) elementary = v;
    }
    for (int c = 0; c < 4; ++c) {
      const std::uint64_t node = version_ == 2 ? static_cast<std::uint64_t>(std::max<std::int64_t>(0, read_int("tet node tag")))
                                               : read_size("tet node tag");
      const std::uint32_t at = index_.find(node);
      if (at == kNoVertex)
        fail("tetrahedron " + std::to_string(tets_.size() / 4 + 1) + " uses node tag " + std::to_string(node) +
             ", which $Nodes does not define");
      tets_.push_back(at);
    }
    tet_physical_.push_back(physical);
    tet_entity_.push_back(elementary);
  }
}

void MshReader::read_elements() {
  if (!have_nodes_) unsupported("$Elements before $Nodes (node tags cannot be resolved)");
  if (have_elements_) fail("second $Elements section");
  have_elements_ = true;
  if (version_ == 2) {
    const std::uint64_t declared = ascii_count("number of elements");
    begin_payload();
    const std::size_t n = bounded(declared, 8, 8, std::numeric_limits<std::uint32_t>::max(), "number of elements");
    std::size_t done = 0;
    while (done < n) {
      std::int64_t code, ntags;
      std::size_t count = 1;
      if (binary_) {  // block header: type, number of elements that follow, tags per element
        code = read_int("element type");
        const std::int64_t follow = read_int("elements in block");
        if (follow < 1 || static_cast<std::uint64_t>(follow) > n - done)
          fail("element block of " + std::to_string(follow) + " elements (" + std::to_string(n - done) + " left to read)");
        count = static_cast<std::size_t>(follow);
        ntags = read_int("number of element tags");
      } else {  // one element per line: tag type ntags tags... nodes...
        read_int("element tag");
        code = read_int("element type");
        ntags = read_int("number of element tags");
      }
      if (ntags < 0 || ntags > 1024) fail("number of element tags " + std::to_string(ntags));
      read_element_block(find_element_type(code), code, count, static_cast<std::size_t>(ntags), 0, /*with_tag=*/binary_);
      done += count;
    }
  } else {
    begin_payload();
    const std::size_t blocks = read_count("number of element blocks", 12 + size_bytes_, 8);
    const std::size_t n = read_count("number of elements", 2 * size_bytes_, 4, std::numeric_limits<std::uint32_t>::max());
    read_size("minimum element tag");
    read_size("maximum element tag");
    std::size_t done = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = read_int("element block entity dimension");
      const std::int64_t entity = read_int("element block entity tag");
      const std::int64_t code = read_int("element type");
      const std::size_t count = read_count("elements in block", 2 * size_bytes_, 4, std::numeric_limits<std::uint32_t>::max());
      const GmshElementType* type = find_element_type(code);
      if (type && type->dim != dim)
        fail("element block of type " + std::to_string(code) + " (" + type_name(*type) + ") in an entity of dimension " + std::to_string(dim));
      if (count > n - done) fail("element blocks hold more elements than the " + std::to_string(n) + " the header declares");
      read_element_block(type, code, count, 0, entity, /*with_tag=*/true);
      done += count;
    }
    if (done != n) fail("the $Elements header declares " + std::to_string(n) + " elements, its blocks hold " + std::to_string(done));
  }
  expect_end("Elements");
}

// A string tag: "quoted" (spaces allowed, on one line) or a bare token.
std::string MshReader::read_quoted_string() {
  tok_.skip_space();
  const char* p = tok_.position();
  if (p == tok_.end()) fail("unexpected end of file: expected a string tag");
  if (*p != '"') return std::string(next_token("a string tag").text);
  const char* q = p + 1;
  while (q != tok_.end() && *q != '"' && *q != '\n') ++q;
  if (q == tok_.end() || *q != '"') fail("unterminated string tag");
  tok_.advance_to(q + 1);
  return std::string(p + 1, q);
}

// $NodeData: only a one-component view named "label" is read (vertex labels, as write_msh stores
// them); any other view is skipped.
void MshReader::read_node_data() {
  const std::uint64_t nstrings = ascii_count("number of string tags");
  if (nstrings > 64) fail("number of string tags " + std::to_string(nstrings));
  std::string name;
  for (std::uint64_t k = 0; k < nstrings; ++k) {
    std::string s = read_quoted_string();
    if (k == 0) name = std::move(s);
  }
  const std::uint64_t nreals = ascii_count("number of real tags");
  if (nreals > 64) fail("number of real tags " + std::to_string(nreals));
  for (std::uint64_t k = 0; k < nreals; ++k) read_double("real tag");
  const std::uint64_t nints = ascii_count("number of integer tags");
  if (nints > 64) fail("number of integer tags " + std::to_string(nints));
  std::int64_t ints[3] = {0, 0, 0};
  for (std::uint64_t k = 0; k < nints; ++k) {
    const std::int64_t v = read_int("integer tag");
    if (k < 3) ints[k] = v;
  }
  if (name != "label" || nints < 3 || ints[1] != 1 || have_node_labels_) {
    skip_section("NodeData");
    return;
  }
  have_node_labels_ = true;
  if (ints[2] < 0) fail("negative number of $NodeData entries");
  begin_payload();
  const std::size_t n = bounded(static_cast<std::uint64_t>(ints[2]), 4 + 8, 4, kMaxVertices, "$NodeData entries");
  node_labels_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t tag = read_int("$NodeData node tag");
    const double value = read_double("$NodeData value");
    if (value != std::floor(value) || value < std::numeric_limits<std::int32_t>::min() || value > std::numeric_limits<std::int32_t>::max())
      fail("vertex label " + std::to_string(value) + " is not a 32-bit integer");
    const std::uint32_t at = tag < 1 ? kNoVertex : index_.find(static_cast<std::uint64_t>(tag));
    if (at == kNoVertex) fail("$NodeData \"label\" names node tag " + std::to_string(tag) + ", which $Nodes does not define");
    node_labels_.emplace_back(at, static_cast<std::int32_t>(value));
  }
  expect_end("NodeData");
}

// "1,024 triangles, 96 lines and 8 points"
std::string list_ignored(const std::vector<TetMeshReadNotes::IgnoredElements>& ignored) {
  std::string s;
  for (std::size_t i = 0; i < ignored.size(); ++i) {
    if (i > 0) s += i + 1 == ignored.size() ? " and " : ", ";
    const std::string& type = ignored[i].type;
    const std::size_t paren = type.find(" (");
    s += paren == std::string::npos ? count_of(ignored[i].count, type)
                                    : count_of(ignored[i].count, type.substr(0, paren)) + type.substr(paren);
  }
  return s;
}

TetMeshData MshReader::assemble() {
  if (!have_nodes_) throw_bad_input(path_, 0, "no $Nodes section");
  if (!have_elements_) throw_bad_input(path_, 0, "no $Elements section");
  if (tets_.empty())
    throw Error(ErrorKind::Unsupported, path_, 0,
                "no linear tetrahedra (element type 4)" +
                    (ignored_.empty() ? std::string() : ": the file holds " + list_ignored(ignored_) + " only (a surface mesh?)"));
  std::vector<std::string> messages;
  if (!ignored_.empty()) messages.push_back("skipped " + list_ignored(ignored_) + " (only tetrahedra are read)");

  // Vertices: the nodes some tet uses, in file order.
  const std::size_t num_nodes = node_tags_.size();
  std::vector<std::uint32_t> vertex_of(num_nodes, kNoVertex);
  for (std::uint32_t node : tets_) vertex_of[node] = 0;
  TetMeshData mesh;
  std::size_t nv = 0;
  bool identity = true;
  for (std::size_t i = 0; i < num_nodes; ++i) {
    if (vertex_of[i] == kNoVertex) continue;
    vertex_of[i] = static_cast<std::uint32_t>(nv);
    identity = identity && node_tags_[i] == nv + 1;
    ++nv;
  }
  mesh.xyz.resize(3 * nv);
  mesh.vertex_labels.assign(nv, 0);
  std::vector<std::uint64_t> source_ids(nv);
  for (std::size_t i = 0; i < num_nodes; ++i) {
    if (vertex_of[i] == kNoVertex) continue;
    std::copy(&xyz_[3 * i], &xyz_[3 * i] + 3, &mesh.xyz[3 * std::size_t(vertex_of[i])]);
    source_ids[vertex_of[i]] = node_tags_[i];
  }
  mesh.tets.resize(tets_.size());
  for (std::size_t k = 0; k < tets_.size(); ++k) mesh.tets[k] = vertex_of[tets_[k]];
  for (const auto& [node, label] : node_labels_)
    if (vertex_of[node] != kNoVertex) mesh.vertex_labels[vertex_of[node]] = label;
  const std::size_t dropped = num_nodes - nv;
  if (dropped > 0)
    messages.push_back("dropped " + count_of(dropped, "node") + " that no tetrahedron uses; vertices are numbered 0.." +
                       std::to_string(nv - 1) + " in file order (source_vertex_ids gives each vertex's node tag)");
  else if (!identity)
    messages.push_back("node tags are not 1.." + std::to_string(nv) +
                       " in file order; vertices are numbered 0.." + std::to_string(nv - 1) +
                       " in file order (source_vertex_ids gives each vertex's node tag)");

  // Tet labels: physical tags; without any, the volume entity tags when there are several.
  const std::size_t nt = tets_.size() / 4;
  if (version_ == 41) {
    std::size_t several = 0, missing = 0;
    std::int64_t several_entity = 0, missing_entity = 0;
    for (std::size_t t = 0; t < nt; ++t) {
      const auto it = volume_physicals_.find(tet_entity_[t]);
      if (it == volume_physicals_.end()) {
        if (have_entities_ && !missing++) missing_entity = tet_entity_[t];
        continue;
      }
      if (!it->second.empty()) tet_physical_[t] = it->second.front();
      if (it->second.size() > 1 && !several++) several_entity = tet_entity_[t];
    }
    if (several > 0)
      messages.push_back(count_of(several, "tet") + " lie in volume entities with several physical tags (first: entity " +
                         std::to_string(several_entity) + "); the first physical tag is the label");
    if (missing > 0)
      messages.push_back(count_of(missing, "tet") + " lie in volume entities that $Entities does not list (first: " +
                         std::to_string(missing_entity) + "); their label is 0");
  }
  const bool any_physical = std::any_of(tet_physical_.begin(), tet_physical_.end(), [](std::int64_t p) { return p != 0; });
  const std::vector<std::int64_t>* labels = nullptr;
  if (any_physical) {
    labels = &tet_physical_;
  } else {
    std::vector<std::int64_t> entities(tet_entity_);
    std::sort(entities.begin(), entities.end());
    const std::size_t distinct = static_cast<std::size_t>(std::unique(entities.begin(), entities.end()) - entities.begin());
    if (distinct > 1) {
      labels = &tet_entity_;
      messages.push_back("no tet has a physical tag: labels are the " + std::to_string(distinct) + " volume entity tags");
    }
  }
  mesh.tet_labels.assign(nt, 0);
  if (labels)
    for (std::size_t t = 0; t < nt; ++t) {
      const std::int64_t v = (*labels)[t];
      if (v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
        throw_bad_input(path_, 0, "tet label " + std::to_string(v) + " out of 32-bit range");
      mesh.tet_labels[t] = static_cast<std::int32_t>(v);
    }

  if (notes_) {
    notes_->ignored_elements = ignored_;
    notes_->dropped_vertices = dropped;
    if (!identity) notes_->source_vertex_ids = std::move(source_ids);
    notes_->messages.insert(notes_->messages.end(), messages.begin(), messages.end());
  }
  return mesh;
}

TetMeshData MshReader::read() {
  read_format();
  Token t;
  while (tok_.next(t)) {
    if (t.text.size() < 2 || t.text[0] != '$')
      throw_bad_input(path_, t.line, "expected a section header ($Name), found " + io_detail::quote(t.text) +
                                         " (wrong count in the previous section?)");
    const std::string name(t.text.substr(1));
    if (name == "MeshFormat") throw_bad_input(path_, t.line, "second $MeshFormat section");
    if (name.compare(0, 3, "End") == 0) throw_bad_input(path_, t.line, "unexpected " + std::string(t.text));
    if (name == "Entities" && version_ == 41)
      read_entities();
    else if (name == "Nodes")
      read_nodes();
    else if (name == "Elements")
      read_elements();
    else if (name == "NodeData")
      read_node_data();
    else
      skip_section(name);
  }
  return assemble();
}

}  // namespace

TetMeshData read_msh(const std::string& path, TetMeshReadNotes* notes) {
  const std::string data = io_detail::read_whole_file(path);
  if (notes) notes->format = "msh";
  return MshReader(path, data, notes).read();
}

}  // namespace volmap
