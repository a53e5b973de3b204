// Medit .mesh reader and writer (ASCII). Files are 1-based; TetMeshData is 0-based.
// Reader: keywords and counts on any lines, '#' comments, any whitespace (CRLF too), optional End
// and final newline, MeshVersionFormatted 1-3. Vertices and Tetrahedra are read (labels kept, tet
// vertex order kept as written). Sections with a known element size (Triangles, Edges, Corners, ...)
// are skipped by count; unknown sections are skipped up to the next token that starts with a letter.
// Hexahedra/Prisms/Pyramids with a non-zero count are rejected as Unsupported (tet meshes only).
// Rejected: ids outside [1,nv], Dimension != 3, truncated blocks, NaN/Inf or malformed numbers,
// counts that cannot fit in the rest of the file (checked before allocating).
// Writer: cinolib's layout, doubles in shortest round-trip form, atomic.
#include <volmap/io/io.hpp>

#include "io_text.hpp"

#include <cmath>
#include <cstring>
#include <limits>

namespace volmap {
namespace {

using io_detail::Token;
using io_detail::Tokenizer;

struct SkippedSection {
  const char* keyword;
  std::size_t tokens_per_element;
};
// Element sizes of the standard Medit sections we do not use (ids + label, or values).
constexpr SkippedSection kSkipped[] = {
    {"Triangles", 4},        {"Quadrilaterals", 5},   {"Edges", 3},           {"Corners", 1},
    {"RequiredVertices", 1}, {"Ridges", 1},           {"RequiredEdges", 1},   {"RequiredTriangles", 1},
    {"Normals", 3},          {"Tangents", 3},         {"NormalAtVertices", 2}, {"TangentAtEdges", 3},
    {"NormalAtTriangleVertices", 3}};
constexpr const char* kUnsupportedCells[] = {"Hexahedra", "Prisms", "Pyramids"};

constexpr std::size_t kMaxIndexCount = std::numeric_limits<std::uint32_t>::max() - 1;

std::string truncated(const char* section, std::size_t index, std::size_t count) {
  return std::string(section) + " block truncated: file ends at element " + std::to_string(index + 1) + " of " +
         std::to_string(count);
}

}  // namespace

namespace {

// The Medit grammar over `tok` (whole lines at a time; Token texts do not outlive the next token).
TetMeshData parse_medit(Tokenizer& tok, const std::string& path) {
  TetMeshData mesh;
  bool have_vertices = false, have_tets = false;
  std::size_t tets_line = 0;
  Token t;
  if (!tok.peek(t)) throw_bad_input(path, 0, "empty file (not a Medit .mesh)");

  while (tok.next(t)) {
    const std::string key(t.text);  // a copy: the window may move on while the section is read
    if (!io_detail::is_letter(key[0]))
      throw_bad_input(path, t.line, "expected a section keyword, found " + io_detail::quote(key) +
                                        " (wrong element count in the previous section?)");
    if (key == "End") break;
    Token count_tok;
    auto need_count = [&](const char* what) {
      if (!tok.next(count_tok)) throw_bad_input(path, t.line, std::string(what) + ": missing value at end of file");
    };
    if (key == "MeshVersionFormatted") {
      need_count("MeshVersionFormatted");
      const std::int64_t v = io_detail::expect_int(count_tok, path, "MeshVersionFormatted");
      if (v < 1 || v > 3)
        throw_bad_input(path, count_tok.line, "unsupported MeshVersionFormatted " + std::to_string(v) + " (1, 2 or 3)");
    } else if (key == "Dimension") {
      need_count("Dimension");
      const std::int64_t d = io_detail::expect_int(count_tok, path, "Dimension");
      if (d != 3) throw_bad_input(path, count_tok.line, "Dimension " + std::to_string(d) + " (only 3 is supported)");
    } else if (key == "Vertices") {
      if (have_vertices) throw_bad_input(path, t.line, "second Vertices section");
      need_count("Vertices");
      const std::size_t nv = io_detail::expect_count(count_tok, path, "Vertices", tok.remaining(), 8, kMaxIndexCount);
      reserve_mapped(mesh.xyz, 3 * nv);
      reserve_mapped(mesh.vertex_labels, nv);
      mesh.xyz.resize(3 * nv);
      mesh.vertex_labels.resize(nv);
      Token v;
      for (std::size_t i = 0; i < nv; ++i) {
        std::uint32_t label_fast;
        const Tokenizer::State line_start = tok.save();
        if (tok.next_plain_double(mesh.xyz[3 * i]) && tok.next_plain_double(mesh.xyz[3 * i + 1]) &&
            tok.next_plain_double(mesh.xyz[3 * i + 2]) && tok.next_plain_unsigned(&label_fast, 1) &&
            label_fast <= static_cast<std::uint32_t>(std::numeric_limits<std::int32_t>::max())) {
          mesh.vertex_labels[i] = static_cast<std::int32_t>(label_fast);
          continue;
        }
        tok.restore(line_start);  // the general path, with precise errors
        for (int c = 0; c < 3; ++c) {
          if (!tok.next(v)) throw_bad_input(path, tok.last_line(), truncated("Vertices", i, nv));
          if (!io_detail::parse_double(v.text, mesh.xyz[3 * i + c]))
            io_detail::expect_double(v, path, "vertex coordinate");  // throws with the reason
        }
        if (!tok.next(v)) throw_bad_input(path, tok.last_line(), truncated("Vertices", i, nv));
        const std::int64_t label = io_detail::expect_int(v, path, "vertex label");
        if (label < std::numeric_limits<std::int32_t>::min() || label > std::numeric_limits<std::int32_t>::max())
          throw_bad_input(path, v.line, "vertex label out of 32-bit range");
        mesh.vertex_labels[i] = static_cast<std::int32_t>(label);
      }
      have_vertices = true;
    } else if (key == "Tetrahedra") {
      if (have_tets) throw_bad_input(path, t.line, "second Tetrahedra section");
      need_count("Tetrahedra");
      const std::size_t nt = io_detail::expect_count(count_tok, path, "Tetrahedra", tok.remaining(), 10, kMaxIndexCount / 4);
      tets_line = count_tok.line;
      reserve_mapped(mesh.tets, 4 * nt);
      reserve_mapped(mesh.tet_labels, nt);
      mesh.tets.resize(4 * nt);
      mesh.tet_labels.resize(nt);
      // When Vertices came first, ids are range-checked here with their line; otherwise after the loop.
      const std::int64_t nv = have_vertices ? static_cast<std::int64_t>(mesh.num_vertices()) : std::numeric_limits<std::int64_t>::max();
      Token v;
      for (std::size_t i = 0; i < nt; ++i) {
        std::uint32_t fast_line[5];
        const Tokenizer::State line_start = tok.save();
        if (tok.next_plain_line(fast_line, 5)) {
          bool in_range = true;
          for (int c = 0; c < 4; ++c) in_range &= fast_line[c] >= 1 && std::int64_t(fast_line[c]) <= nv;
          if (in_range) {
            for (int c = 0; c < 4; ++c) mesh.tets[4 * i + c] = fast_line[c] - 1;
            mesh.tet_labels[i] = static_cast<std::int32_t>(fast_line[4]);  // < 10^9
            continue;
          }
          tok.restore(line_start);  // the general path, with precise errors
        }
        for (int c = 0; c < 4; ++c) {
          std::int64_t id;
          std::uint64_t fast;
          const int r = tok.next_unsigned(fast, v.line);
          if (r == 1) {
            id = static_cast<std::int64_t>(fast);
          } else {
            if (r == 0 || !tok.next(v)) throw_bad_input(path, tok.last_line(), truncated("Tetrahedra", i, nt));
            if (!io_detail::parse_int64(v.text, id)) id = io_detail::expect_int(v, path, "tet vertex id");
          }
          if (id < 1 || id > nv || id > static_cast<std::int64_t>(kMaxIndexCount))
            throw_bad_input(path, v.line, "tet " + std::to_string(i + 1) + ": vertex id " + std::to_string(id) +
                                              " outside [1," + std::to_string(have_vertices ? nv : 0) + "]");
          mesh.tets[4 * i + c] = static_cast<std::uint32_t>(id - 1);
        }
        std::int64_t label;
        std::uint64_t fast;
        const int r = tok.next_unsigned(fast, v.line);
        if (r == 1) {
          label = static_cast<std::int64_t>(fast);
        } else {
          if (r == 0 || !tok.next(v)) throw_bad_input(path, tok.last_line(), truncated("Tetrahedra", i, nt));
          if (!io_detail::parse_int64(v.text, label)) label = io_detail::expect_int(v, path, "tet label");
        }
        if (label < std::numeric_limits<std::int32_t>::min() || label > std::numeric_limits<std::int32_t>::max())
          throw_bad_input(path, v.line, "tet label out of 32-bit range");
        mesh.tet_labels[i] = static_cast<std::int32_t>(label);
      }
      have_tets = true;
    } else {
      bool handled = false;
      for (const char* cell : kUnsupportedCells) {
        if (key != cell) continue;
        need_count(cell);
        const std::int64_t n = io_detail::expect_int(count_tok, path, cell);
        if (n != 0)
          throw Error(ErrorKind::Unsupported, path, t.line,
                      std::string(cell) + " are not supported (tetrahedral meshes only)");
        handled = true;
      }
      for (const SkippedSection& s : kSkipped) {
        if (handled || key != s.keyword) continue;
        handled = true;
        need_count(s.keyword);
        const std::size_t n = io_detail::expect_count(count_tok, path, s.keyword, tok.remaining(),
                                                      2 * s.tokens_per_element, std::numeric_limits<std::size_t>::max() / 16);
        Token skip;
        for (std::size_t k = 0; k < n * s.tokens_per_element; ++k) {
          if (!tok.next(skip)) throw_bad_input(path, tok.last_line(), truncated(s.keyword, k / s.tokens_per_element, n));
          double unused;
          if (!io_detail::parse_double(skip.text, unused))
            throw_bad_input(path, skip.line, std::string(s.keyword) + ": expected a number, found " + io_detail::quote(skip.text));
        }
      }
      if (!handled) {
        // Unknown section: skip its tokens up to the next keyword (a token starting with a letter).
        Token skip;
        while (tok.peek(skip) && !io_detail::is_letter(skip.text[0])) tok.next(skip);
      }
    }
  }
  if (!have_vertices) throw_bad_input(path, 0, "no Vertices section");
  if (!have_tets) throw_bad_input(path, 0, "no Tetrahedra section");
  const std::size_t nv = mesh.num_vertices();
  for (std::size_t k = 0; k < mesh.tets.size(); ++k)
    if (mesh.tets[k] >= nv)
      throw_bad_input(path, tets_line, "tet " + std::to_string(k / 4 + 1) + ": vertex id " + std::to_string(mesh.tets[k] + 1) +
                                           " outside [1," + std::to_string(nv) + "]");
  return mesh;
}

}  // namespace

// Regular files are read through a sliding window (memory independent of the file's size), other
// files (pipes, devices) whole.
TetMeshData read_medit(const std::string& path) {
  const io_detail::ReadOptions options{/*text=*/true};
  if (io_detail::FileWindow::suits(path)) {
    io_detail::FileWindow window(path, options);
    Tokenizer tok(window, /*hash_comments=*/true);
    return parse_medit(tok, path);
  }
  const io_detail::FileBytes data = io_detail::read_file_bytes(path, options);
  Tokenizer tok(data.begin(), data.end(), /*hash_comments=*/true);
  return parse_medit(tok, path);
}

void write_medit(AtomicOutput& out, const TetMeshData& mesh) {
  const std::string& path = out.destination();
  const std::size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  io_detail::check_mesh_writable(mesh, path);
  const bool vlabels = mesh.vertex_labels.size() == nv;
  const bool tlabels = mesh.tet_labels.size() == nt;
  io_detail::TextWriter w(out);
  w.put("MeshVersionFormatted 1\nDimension 3\nVertices\n");
  w.put_int(static_cast<std::int64_t>(nv));
  w.put('\n');
  for (std::size_t i = 0; i < nv; ++i) {
    for (int c = 0; c < 3; ++c) {
      w.put_double(mesh.xyz[3 * i + c]);
      w.put(' ');
    }
    w.put_int(vlabels ? mesh.vertex_labels[i] : 0);
    w.put('\n');
  }
  w.put("Tetrahedra\n");
  w.put_int(static_cast<std::int64_t>(nt));
  w.put('\n');
  for (std::size_t i = 0; i < nt; ++i) {
    for (int c = 0; c < 4; ++c) {
      w.put_int(static_cast<std::int64_t>(mesh.tets[4 * i + c]) + 1);
      w.put(' ');
    }
    w.put_int(tlabels ? mesh.tet_labels[i] : 0);
    w.put('\n');
  }
  w.put("End\n");
  w.flush();
}

void write_medit(const std::string& path, const TetMeshData& mesh) {
  AtomicOutput out(path);
  write_medit(out, mesh);
  out.commit();
}

}  // namespace volmap
