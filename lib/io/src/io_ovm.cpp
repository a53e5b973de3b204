// OpenVolumeMesh text format (.ovm, header `OVM ASCII`) reader, tetrahedral cells only
// (volmap-reference.md §2.8).
// Sections in this order, keywords case-insensitive, '#' comments:
//   Vertices n, then n lines `x y z`;  Edges n, then n lines `v0 v1` (0-based vertex ids);
//   Faces n, then n lines `k h1..hk`: half-edge ids, 2e runs v0->v1 of edge e and 2e+1 runs back;
//   Polyhedra n, then n lines `k f1..fk`: half-face ids, 2f is face f as listed and 2f+1 the
//   reversed face (half-edges in reverse order, each opposite).
// Anything after Polyhedra (the VProp/EProp/.../CProp/MProp property sections) is ignored.
// A cell becomes a tet when it has 4 triangular half-faces over 4 distinct vertices whose 12
// directed edges pair up as 6 edges each run once in each direction (a closed, consistently
// oriented surface). Its vertex order is OpenVolumeMesh's: the first half-face's vertices (from
// the start of its first half-edge), then the remaining vertex. Half-face normals point into the
// cell, so these tets have orient3d < 0 (the opposite of VOLMAP's convention).
#include <volmap/io/io.hpp>

#include "io_text.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

namespace volmap {
namespace {

using io_detail::Token;
using io_detail::Tokenizer;

constexpr std::size_t kMaxCount = std::numeric_limits<std::uint32_t>::max() - 1;

bool keyword_is(std::string_view token, std::string_view keyword) {
  if (token.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < token.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(token[i])) != std::tolower(static_cast<unsigned char>(keyword[i]))) return false;
  return true;
}

class OvmReader {
 public:
  OvmReader(const std::string& path, const std::string& data)
      : path_(path), tok_(data.data(), data.data() + data.size(), /*hash_comments=*/true) {}
  TetMeshData read();

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& reason) const { throw_bad_input(path_, line, reason); }
  Token next(const char* what) {
    Token t;
    if (!tok_.next(t)) fail(tok_.last_line(), std::string("unexpected end of file: expected ") + what);
    return t;
  }
  std::size_t index(const char* what, std::size_t limit) {
    const Token t = next(what);
    const std::int64_t v = io_detail::expect_int(t, path_, what);
    if (v < 0 || static_cast<std::uint64_t>(v) >= limit)
      fail(t.line, std::string(what) + " " + std::to_string(v) + " outside [0," + std::to_string(limit) + ")");
    return static_cast<std::size_t>(v);
  }
  std::size_t section(const char* keyword, std::size_t min_bytes_each) {
    const Token t = next(keyword);
    if (!keyword_is(t.text, keyword))
      fail(t.line, std::string("expected the ") + keyword + " section, found " + io_detail::quote(t.text));
    return io_detail::expect_count(next("a count"), path_, keyword, tok_.remaining(), min_bytes_each, kMaxCount);
  }
  void read_header();
  void read_faces(std::size_t num_half_edges);
  // Vertices of half-face hf, three of them (faces are checked to be triangles when a cell uses them).
  void half_face_vertices(std::size_t hf, std::uint32_t v[3]) const;
  void read_cell(std::size_t cell, TetMeshData& mesh);

  const std::string& path_;
  Tokenizer tok_;
  std::vector<std::uint32_t> edges_;        // 2 vertex ids per edge
  std::vector<std::size_t> face_offsets_;   // CSR over face_half_edges_
  std::vector<std::uint32_t> face_half_edges_;
  std::vector<std::size_t> face_lines_;
};

void OvmReader::read_header() {
  Token a, b;
  if (!tok_.next(a)) fail(0, "empty file (not an OpenVolumeMesh .ovm file)");
  if (!keyword_is(a.text, "OVM") || !tok_.next(b)) fail(a.line, "not an OpenVolumeMesh text file: expected the header `OVM ASCII`");
  if (keyword_is(b.text, "BINARY"))
    throw Error(ErrorKind::Unsupported, path_, b.line, "binary .ovm files are not supported (save as OVM ASCII)");
  if (!keyword_is(b.text, "ASCII")) fail(b.line, "not an OpenVolumeMesh text file: expected the header `OVM ASCII`");
}

void OvmReader::read_faces(std::size_t num_half_edges) {
  const std::size_t nf = section("Faces", 8);
  face_offsets_.reserve(nf + 1);
  face_offsets_.push_back(0);
  face_lines_.reserve(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const Token k = next("a face's number of half-edges");
    face_lines_.push_back(k.line);
    const std::size_t n = io_detail::expect_count(k, path_, "face size", tok_.remaining(), 2, 1u << 20);
    if (n < 3) fail(k.line, "face " + std::to_string(f) + " has " + std::to_string(n) + " half-edges (at least 3)");
    for (std::size_t i = 0; i < n; ++i) face_half_edges_.push_back(static_cast<std::uint32_t>(index("half-edge id", num_half_edges)));
    face_offsets_.push_back(face_half_edges_.size());
  }
}

void OvmReader::half_face_vertices(std::size_t hf, std::uint32_t v[3]) const {
  const std::size_t f = hf / 2;
  const std::uint32_t* he = &face_half_edges_[face_offsets_[f]];
  auto from = [&](std::uint32_t h) { return edges_[2 * std::size_t(h / 2) + (h & 1)]; };
  // 2f: from-vertices of h0, h1, h2. 2f+1 runs opp(h2), opp(h1), opp(h0), whose from-vertices are
  // the to-vertices of h2, h1, h0: v0, v2, v1.
  v[0] = from(he[0]);
  v[1] = from(he[(hf & 1) ? 2 : 1]);
  v[2] = from(he[(hf & 1) ? 1 : 2]);
}

void OvmReader::read_cell(std::size_t cell, TetMeshData& mesh) {
  const Token k = next("a cell's number of half-faces");
  const std::size_t nf = face_lines_.size();
  const std::size_t n = io_detail::expect_count(k, path_, "cell size", tok_.remaining(), 2, 1u << 20);
  std::size_t hf[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t h = index("half-face id", 2 * nf);
    if (i < 4) hf[i] = h;
  }
  const std::string name = "cell " + std::to_string(cell);
  if (n != 4)
    throw Error(ErrorKind::Unsupported, path_, k.line,
                name + " has " + std::to_string(n) + " faces: only tetrahedral cells are supported, not general polyhedra");
  std::uint32_t v[4][3];
  for (int i = 0; i < 4; ++i) {
    const std::size_t f = hf[i] / 2;
    const std::size_t size = face_offsets_[f + 1] - face_offsets_[f];
    if (size != 3)
      throw Error(ErrorKind::Unsupported, path_, k.line,
                  name + " has a face with " + std::to_string(size) + " edges (face " + std::to_string(f) +
                      "): only tetrahedral cells are supported, not general polyhedra");
    half_face_vertices(hf[i], v[i]);
  }
  // The fourth vertex: the one of the other half-faces not on the first.
  std::uint32_t apex = std::numeric_limits<std::uint32_t>::max();
  bool four = true;
  for (int i = 1; i < 4; ++i)
    for (std::uint32_t x : v[i])
      if (x != v[0][0] && x != v[0][1] && x != v[0][2]) {
        if (apex != std::numeric_limits<std::uint32_t>::max() && apex != x) four = false;
        apex = x;
      }
  // Closed and consistently oriented: each directed edge of the tet is run exactly once.
  bool closed = four && apex != std::numeric_limits<std::uint32_t>::max() && v[0][0] != v[0][1] && v[0][1] != v[0][2] &&
                v[0][0] != v[0][2];
  const std::uint32_t corners[4] = {v[0][0], v[0][1], v[0][2], apex};
  int runs[4][4] = {};
  for (int i = 0; i < 4 && closed; ++i)
    for (int e = 0; e < 3; ++e) {
      const auto a = std::find(corners, corners + 4, v[i][e]) - corners;
      const auto b = std::find(corners, corners + 4, v[i][(e + 1) % 3]) - corners;
      if (a == 4 || b == 4 || a == b) {
        closed = false;
        break;
      }
      ++runs[a][b];
    }
  for (int a = 0; a < 4 && closed; ++a)
    for (int b = 0; b < 4; ++b)
      if (a != b && runs[a][b] != 1) closed = false;
  if (!closed)
    fail(k.line, name + " is not a tetrahedron: its 4 half-faces do not bound 4 vertices with consistently oriented faces");
  mesh.tets.insert(mesh.tets.end(), corners, corners + 4);
}

TetMeshData OvmReader::read() {
  read_header();
  TetMeshData mesh;
  const std::size_t nv = section("Vertices", 6);
  mesh.xyz.resize(3 * nv);
  for (double& c : mesh.xyz) {
    const Token t = next("a vertex coordinate");
    if (!io_detail::parse_double(t.text, c)) io_detail::expect_double(t, path_, "vertex coordinate");
  }
  const std::size_t ne = section("Edges", 4);
  edges_.resize(2 * ne);
  for (std::size_t e = 0; e < ne; ++e) {
    edges_[2 * e] = static_cast<std::uint32_t>(index("edge vertex", nv));
    edges_[2 * e + 1] = static_cast<std::uint32_t>(index("edge vertex", nv));
    if (edges_[2 * e] == edges_[2 * e + 1]) fail(tok_.last_line(), "edge " + std::to_string(e) + " joins a vertex to itself");
  }
  read_faces(2 * ne);
  // Each face's half-edges must chain into a loop (the to-vertex of one is the from-vertex of the next).
  for (std::size_t f = 0; f + 1 < face_offsets_.size(); ++f) {
    const std::size_t b = face_offsets_[f], n = face_offsets_[f + 1] - b;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t h = face_half_edges_[b + i], g = face_half_edges_[b + (i + 1) % n];
      const std::uint32_t to = edges_[2 * std::size_t(h / 2) + 1 - (h & 1)], from = edges_[2 * std::size_t(g / 2) + (g & 1)];
      if (to != from) fail(face_lines_[f], "face " + std::to_string(f) + ": its half-edges do not form a closed loop");
    }
  }
  const std::size_t nc = section("Polyhedra", 10);
  mesh.tets.reserve(4 * nc);
  for (std::size_t c = 0; c < nc; ++c) read_cell(c, mesh);
  Token rest;
  if (tok_.next(rest) && !(rest.text.size() > 4 && keyword_is(rest.text.substr(rest.text.size() - 4), "Prop")))
    fail(rest.line, "unexpected " + io_detail::quote(rest.text) + " after the Polyhedra section (a property section, e.g. VProp, expected)");
  mesh.vertex_labels.assign(nv, 0);
  mesh.tet_labels.assign(nc, 0);
  return mesh;
}

}  // namespace

TetMeshData read_ovm(const std::string& path) {
  const std::string data = io_detail::read_whole_file(path);
  return OvmReader(path, data).read();
}

}  // namespace volmap
