// Surface IO (see io_surface.hpp): OFF, OBJ, PLY and STL parsed and written here, polygons flattened
// with a first-corner fan triangulation.
#include <volmap/io/atomic_file.hpp>
#include <volmap/core/error.hpp>
#include <volmap/io/io_surface.hpp>

#include "io_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace volmap {
namespace {

std::string lower_extension(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  std::string out = ext;
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool supported(const std::string& ext) { return ext == ".obj" || ext == ".off" || ext == ".stl" || ext == ".ply"; }

// ---------- text formats ----

using io_detail::Token;

// Splits [p, end) into lines; calls f(line_text, line_number) for each, '#' comments removed.
template <typename F>
void for_each_line(const std::string& data, F&& f) {
  const char* p = data.data();
  const char* end = p + data.size();
  std::size_t line = 0;
  while (p < end) {
    ++line;
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    const char* stop = eol ? eol : end;
    const char* hash = static_cast<const char*>(std::memchr(p, '#', static_cast<std::size_t>(stop - p)));
    if (!f(std::string_view(p, static_cast<std::size_t>((hash ? hash : stop) - p)), line)) return;
    p = eol ? eol + 1 : end;
  }
}

std::size_t split(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && io_detail::is_space(line[i])) ++i;
    if (i == line.size()) break;
    const std::size_t b = i;
    while (i < line.size() && !io_detail::is_space(line[i])) ++i;
    out.push_back(line.substr(b, i - b));
  }
  return out.size();
}

void add_polygon(SurfaceData& s, const std::vector<std::uint32_t>& corners) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    s.tris.push_back(corners[0]);
    s.tris.push_back(corners[k]);
    s.tris.push_back(corners[k + 1]);
  }
}

SurfaceData read_off(const std::string& path, const std::string& data) {
  SurfaceData s;
  std::vector<std::string_view> tok;
  std::vector<std::uint32_t> corners;
  enum { Header, Counts, Vertices, Faces, Done } state = Header;
  std::size_t nv = 0, nf = 0, read_v = 0, read_f = 0;
  for_each_line(data, [&](std::string_view line, std::size_t ln) {
    if (split(line, tok) == 0) return true;
    std::size_t first = 0;
    if (state == Header) {
      const std::string_view h = tok[0];
      if (h.size() < 3 || h.substr(h.size() - 3) != "OFF")
        throw_bad_input(path, ln, "expected an OFF header, found " + io_detail::quote(h));
      if (h != "OFF" && h != "COFF" && h != "NOFF" && h != "CNOFF")
        throw Error(ErrorKind::Unsupported, path, ln, "OFF variant " + io_detail::quote(h) + " is not supported");
      state = Counts;
      if (tok.size() == 1) return true;
      first = 1;
    }
    if (state == Counts) {
      if (tok.size() - first < 2) throw_bad_input(path, ln, "expected 'vertices faces [edges]'");
      const std::size_t remaining = data.size();
      nv = io_detail::expect_count(Token{tok[first], ln}, path, "OFF vertex count", remaining, 6, 0xFFFFFFF0u);
      nf = io_detail::expect_count(Token{tok[first + 1], ln}, path, "OFF face count", remaining, 8, 0xFFFFFFF0u);
      s.xyz.reserve(3 * nv);
      s.tris.reserve(3 * nf);
      state = nv ? Vertices : (nf ? Faces : Done);
      return true;
    }
    if (state == Vertices) {
      if (tok.size() < 3) throw_bad_input(path, ln, "vertex line needs x y z");
      for (int c = 0; c < 3; ++c) s.xyz.push_back(io_detail::expect_double(Token{tok[c], ln}, path, "vertex coordinate"));
      if (++read_v == nv) state = nf ? Faces : Done;
      return true;
    }
    if (state == Faces) {
      const std::int64_t n = io_detail::expect_int(Token{tok[0], ln}, path, "face size");
      if (n < 3 || static_cast<std::size_t>(n) + 1 > tok.size())
        throw_bad_input(path, ln, "face needs at least 3 corners and as many ids as announced");
      corners.clear();
      for (std::int64_t k = 1; k <= n; ++k) {
        const std::int64_t id = io_detail::expect_int(Token{tok[static_cast<std::size_t>(k)], ln}, path, "face vertex id");
        if (id < 0 || static_cast<std::size_t>(id) >= nv)
          throw_bad_input(path, ln, "face vertex id " + std::to_string(id) + " outside [0," + std::to_string(nv) + ")");
        corners.push_back(static_cast<std::uint32_t>(id));
      }
      add_polygon(s, corners);
      if (++read_f == nf) state = Done;
      return true;
    }
    return false;  // Done: ignore trailing content
  });
  if (state == Header) throw_bad_input(path, 0, "empty file (no OFF header)");
  if (state != Done) throw_bad_input(path, 0, "truncated: " + std::to_string(read_v) + "/" + std::to_string(nv) + " vertices, " +
                                                  std::to_string(read_f) + "/" + std::to_string(nf) + " faces");
  return s;
}

SurfaceData read_obj(const std::string& path, const std::string& data) {
  SurfaceData s;
  std::vector<std::string_view> tok;
  std::vector<std::uint32_t> corners;
  struct PendingFace {
    std::size_t line, first, count;
  };
  std::vector<std::int64_t> ids;       // raw (possibly relative) ids, resolved as they come
  for_each_line(data, [&](std::string_view line, std::size_t ln) {
    if (split(line, tok) == 0) return true;
    if (tok[0] == "v") {
      if (tok.size() < 4) throw_bad_input(path, ln, "'v' needs x y z");
      for (int c = 1; c <= 3; ++c) s.xyz.push_back(io_detail::expect_double(Token{tok[c], ln}, path, "vertex coordinate"));
    } else if (tok[0] == "f") {
      if (tok.size() < 4) throw_bad_input(path, ln, "'f' needs at least 3 corners");
      corners.clear();
      const std::int64_t nv = static_cast<std::int64_t>(s.xyz.size() / 3);
      for (std::size_t k = 1; k < tok.size(); ++k) {
        const std::string_view c = tok[k].substr(0, tok[k].find('/'));
        const std::int64_t id = io_detail::expect_int(Token{c, ln}, path, "face vertex id");
        const std::int64_t zero_based = id > 0 ? id - 1 : nv + id;  // negative ids are relative
        if (id == 0 || zero_based < 0 || zero_based >= nv)
          throw_bad_input(path, ln, "face vertex id " + std::to_string(id) + " does not name one of the " + std::to_string(nv) +
                                        " vertices defined so far");
        corners.push_back(static_cast<std::uint32_t>(zero_based));
      }
      add_polygon(s, corners);
    }
    // Other statements (vn, vt, g, o, s, usemtl, mtllib, l, ...) carry nothing we use.
    return true;
  });
  (void)ids;
  if (s.tris.empty()) throw_bad_input(path, 0, "no faces");
  return s;
}

// PLY (ascii, binary_little_endian, binary_big_endian): vertex x/y/z of any numeric type; faces from a
// `face` element (vertex_indices / vertex_index list) or a `tristrips` element (-1 restarts a strip;
// odd strip triangles are flipped to keep the orientation; degenerate strip triangles dropped).
struct PlyProperty {
  std::string name;
  bool is_list = false;
  std::string count_type, type;
};
struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

std::size_t ply_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

SurfaceData read_ply(const std::string& path, const std::string& data) {
  const std::size_t header_end = data.find("end_header");
  if (data.compare(0, 3, "ply") != 0 || header_end == std::string::npos) throw_bad_input(path, 1, "not a PLY file");
  std::size_t body = data.find('\n', header_end);
  body = body == std::string::npos ? data.size() : body + 1;
  std::vector<PlyElement> elements;
  int format = -1;  // 0 ascii, 1 LE, 2 BE
  std::vector<std::string_view> tok;
  std::size_t header_lines = 0;
  for_each_line(data.substr(0, body), [&](std::string_view line, std::size_t ln) {
    header_lines = ln;
    if (split(line, tok) == 0) return true;
    if (tok[0] == "format") {
      if (tok.size() < 2) throw_bad_input(path, ln, "bad format line");
      format = tok[1] == "ascii" ? 0 : tok[1] == "binary_little_endian" ? 1 : tok[1] == "binary_big_endian" ? 2 : -1;
      if (format < 0) throw_bad_input(path, ln, "unknown PLY format " + io_detail::quote(tok[1]));
    } else if (tok[0] == "element") {
      if (tok.size() < 3) throw_bad_input(path, ln, "bad element line");
      PlyElement e;
      e.name = std::string(tok[1]);
      e.count = io_detail::expect_count(Token{tok[2], ln}, path, "PLY element count", data.size(), 1, 0xFFFFFFF0u);
      elements.push_back(e);
    } else if (tok[0] == "property") {
      if (elements.empty()) throw_bad_input(path, ln, "property before any element");
      PlyProperty p;
      if (tok.size() >= 5 && tok[1] == "list") {
        p.is_list = true, p.count_type = std::string(tok[2]), p.type = std::string(tok[3]), p.name = std::string(tok[4]);
        if (!ply_size(p.count_type) || !ply_size(p.type)) throw_bad_input(path, ln, "unknown PLY list type");
      } else if (tok.size() >= 3) {
        p.type = std::string(tok[1]), p.name = std::string(tok[2]);
        if (!ply_size(p.type)) throw_bad_input(path, ln, "unknown PLY type " + io_detail::quote(tok[1]));
      } else {
        throw_bad_input(path, ln, "bad property line");
      }
      elements.back().properties.push_back(p);
    }
    return true;
  });
  if (format < 0) throw_bad_input(path, 0, "PLY header has no format line");
  SurfaceData s;
  const unsigned char* p = reinterpret_cast<const unsigned char*>(data.data()) + body;
  const unsigned char* end = reinterpret_cast<const unsigned char*>(data.data()) + data.size();
  io_detail::Tokenizer text(data.data() + body, data.data() + data.size(), false);
  for (std::size_t k = 0; k < header_lines; ++k) text.count_line();
  auto read_value = [&](const std::string& type) -> double {
    if (format == 0) {
      Token t;
      if (!text.next(t)) throw_bad_input(path, text.line(), "PLY data truncated");
      return io_detail::expect_double(t, path, "PLY value");
    }
    const std::size_t sz = ply_size(type);
    if (static_cast<std::size_t>(end - p) < sz) throw_bad_input(path, 0, "PLY binary data truncated");
    unsigned char b[8];
    for (std::size_t i = 0; i < sz; ++i) b[i] = format == 1 ? p[i] : p[sz - 1 - i];
    p += sz;
    if (type == "float" || type == "float32") { float f; std::memcpy(&f, b, 4); return f; }
    if (type == "double" || type == "float64") { double d; std::memcpy(&d, b, 8); return d; }
    std::uint64_t u = 0;
    std::memcpy(&u, b, sz);
    const bool is_signed = type[0] != 'u';
    if (is_signed && sz < 8 && (u >> (8 * sz - 1)) & 1) return static_cast<double>(static_cast<std::int64_t>(u | (~std::uint64_t(0) << (8 * sz))));
    return static_cast<double>(u);
  };
  std::vector<std::int64_t> list;
  for (const PlyElement& e : elements) {
    const bool vertex = e.name == "vertex", face = e.name == "face", strips = e.name == "tristrips";
    if (vertex) s.xyz.assign(3 * e.count, 0.0);
    for (std::size_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& prop : e.properties) {
        if (prop.is_list) {
          const double n = read_value(prop.count_type);
          // Validated against the bytes left before anything is allocated: every list entry takes at
          // least 2 bytes in ASCII (digit + separator) and its type's size in binary.
          const std::size_t left = format == 0 ? data.size() / 2 + 1 : static_cast<std::size_t>(end - p) / ply_size(prop.type);
          if (n < 0 || n > static_cast<double>(left) || n != std::floor(n))
            throw_bad_input(path, format == 0 ? text.line() : 0,
                            "bad PLY list size (negative, fractional or more entries than the file holds: at most " +
                                std::to_string(left) + ")");
          list.resize(static_cast<std::size_t>(n));
          for (auto& v : list) {
            // Range-checked before the conversion (a float/double entry may hold anything, e.g. 1e29).
            const double x = read_value(prop.type);
            if (!(x >= -0x1p62 && x <= 0x1p62) || x != std::floor(x))
              throw_bad_input(path, format == 0 ? text.line() : 0, "PLY list entry is not an integer id");
            v = static_cast<std::int64_t>(x);
          }
          const bool ids = prop.name == "vertex_indices" || prop.name == "vertex_index";
          const std::int64_t nv = static_cast<std::int64_t>(s.xyz.size() / 3);
          if (face && ids) {
            if (list.size() < 3) throw_bad_input(path, 0, "PLY face with fewer than 3 corners");
            std::vector<std::uint32_t> corners;
            for (auto v : list) {
              if (v < 0 || v >= nv) throw_bad_input(path, 0, "PLY face id " + std::to_string(v) + " out of range");
              corners.push_back(static_cast<std::uint32_t>(v));
            }
            add_polygon(s, corners);
          } else if (strips && ids) {
            std::size_t start = 0;
            for (std::size_t k = 0; k <= list.size(); ++k) {
              if (k < list.size() && list[k] != -1) continue;
              for (std::size_t j = start; j + 2 < k; ++j) {
                std::int64_t a = list[j], b = list[j + 1], c = list[j + 2];
                if (((j - start) & 1) != 0) std::swap(a, b);
                for (auto v : {a, b, c})
                  if (v < 0 || v >= nv) throw_bad_input(path, 0, "PLY strip id " + std::to_string(v) + " out of range");
                if (a == b || b == c || a == c) continue;
                s.tris.push_back(static_cast<std::uint32_t>(a));
                s.tris.push_back(static_cast<std::uint32_t>(b));
                s.tris.push_back(static_cast<std::uint32_t>(c));
              }
              start = k + 1;
            }
          }
        } else {
          const double v = read_value(prop.type);
          if (vertex) {
            const int c = prop.name == "x" ? 0 : prop.name == "y" ? 1 : prop.name == "z" ? 2 : -1;
            if (c >= 0) {
              if (!std::isfinite(v)) throw_bad_input(path, 0, "non-finite PLY coordinate");
              s.xyz[3 * i + static_cast<std::size_t>(c)] = v;
            }
          }
        }
      }
    }
  }
  if (s.tris.empty()) throw_bad_input(path, 0, "no faces");
  return s;
}

// STL. Binary: an 80-byte header, a uint32 triangle count n, then n records of 50 bytes (normal,
// three corners as float32, a 2-byte attribute); the file must be exactly 84 + 50 n bytes. ASCII:
// `solid` ... `facet normal` / `outer loop` / three `vertex x y z` / `endloop` / `endfacet` ...
// A file is binary when its size matches its count, ASCII when it starts with `solid` otherwise.
// Corners are welded into vertices by exact coordinates, numbered in order of first appearance.
void weld_corners(SurfaceData& s, const std::vector<double>& corners) {
  const std::size_t n = corners.size() / 3;
  std::vector<std::uint32_t> order(n);
  for (std::uint32_t k = 0; k < n; ++k) order[k] = k;
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    for (int c = 0; c < 3; ++c)
      if (corners[3 * a + c] != corners[3 * b + c]) return corners[3 * a + c] < corners[3 * b + c];
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> first(n);  // the first corner at the same position
  for (std::size_t k = 0; k < n; ++k) {
    const bool same = k > 0 && std::equal(&corners[3 * order[k]], &corners[3 * order[k]] + 3, &corners[3 * order[k - 1]]);
    first[order[k]] = same ? first[order[k - 1]] : order[k];
  }
  std::vector<std::uint32_t> id(n, 0xFFFFFFFFu);
  s.tris.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::uint32_t& v = id[first[k]];
    if (v == 0xFFFFFFFFu) {
      v = static_cast<std::uint32_t>(s.xyz.size() / 3);
      s.xyz.insert(s.xyz.end(), &corners[3 * k], &corners[3 * k] + 3);
    }
    s.tris[k] = v;
  }
}

SurfaceData read_stl(const std::string& path, const std::string& data) {
  std::vector<double> corners;
  std::uint32_t count = 0;
  if (data.size() >= 84) std::memcpy(&count, data.data() + 80, 4);  // little-endian hosts only (as every writer)
  const bool binary = data.size() >= 84 && data.size() == 84 + 50 * std::uint64_t(count);
  std::size_t text_start = data.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (text_start < data.size() && io_detail::is_space(data[text_start])) ++text_start;
  if (binary) {
    corners.reserve(9 * std::size_t(count));
    for (std::size_t t = 0; t < count; ++t) {
      const char* record = data.data() + 84 + 50 * t;
      for (int k = 0; k < 9; ++k) {
        float f;
        std::memcpy(&f, record + 12 + 4 * k, 4);
        if (!std::isfinite(f))
          throw_bad_input(path, 0, "binary STL triangle " + std::to_string(t) + ": non-finite corner coordinate");
        corners.push_back(f);
      }
    }
  } else if (data.compare(text_start, 5, "solid") == 0) {
    io_detail::Tokenizer tok(data.data() + text_start, data.data() + data.size(), false);
    Token t;
    std::size_t in_facet = 0;  // corners seen in the current facet
    while (tok.next(t)) {
      if (t.text == "vertex") {
        if (++in_facet > 3) throw_bad_input(path, t.line, "ASCII STL facet with more than 3 vertices");
        for (int c = 0; c < 3; ++c) {
          Token x;
          if (!tok.next(x)) throw_bad_input(path, t.line, "ASCII STL truncated inside a vertex");
          corners.push_back(io_detail::expect_double(x, path, "STL vertex coordinate"));
        }
      } else if (t.text == "endfacet") {
        if (in_facet != 3) throw_bad_input(path, t.line, "ASCII STL facet with " + std::to_string(in_facet) + " vertices");
        in_facet = 0;
      }
    }
    if (in_facet != 0) throw_bad_input(path, tok.last_line(), "ASCII STL truncated inside a facet");
  } else if (data.size() >= 84) {
    throw_bad_input(path, 0, "binary STL announces " + std::to_string(count) + " triangles (" +
                                 std::to_string(84 + 50 * std::uint64_t(count)) + " bytes) but the file has " +
                                 std::to_string(data.size()) + " bytes (truncated or not an STL file)");
  } else {
    throw_bad_input(path, 0, "neither an ASCII STL (no 'solid') nor a binary one (" + std::to_string(data.size()) +
                                 " bytes, fewer than the 84-byte header)");
  }
  if (corners.empty()) throw_bad_input(path, 0, "no triangles");
  SurfaceData s;
  weld_corners(s, corners);
  return s;
}

void write_stl(AtomicOutput& out, const SurfaceData& surface) {
  std::string bytes(80, ' ');
  bytes.replace(0, 24, "binary STL written by volmap");
  bytes.resize(80, ' ');
  const std::uint32_t count = static_cast<std::uint32_t>(surface.num_triangles());
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (std::size_t t = 0; t < surface.num_triangles(); ++t) {
    float f[12];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) f[3 + 3 * k + c] = static_cast<float>(surface.xyz[3 * surface.tris[3 * t + k] + c]);
    const float u[3] = {f[6] - f[3], f[7] - f[4], f[8] - f[5]}, v[3] = {f[9] - f[3], f[10] - f[4], f[11] - f[5]};
    f[0] = u[1] * v[2] - u[2] * v[1], f[1] = u[2] * v[0] - u[0] * v[2], f[2] = u[0] * v[1] - u[1] * v[0];
    const float len = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int c = 0; c < 3; ++c) f[c] = len > 0 && std::isfinite(len) ? f[c] / len : 0.0f;
    bytes.append(reinterpret_cast<const char*>(f), sizeof f);
    bytes.append(2, '\0');
  }
  write_text(out, bytes);
}

}  // namespace

SurfaceData read_surface(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (!supported(ext)) throw Error(ErrorKind::Unsupported, path, 0, "unknown surface extension (expected .obj, .off, .stl or .ply)");
  io_detail::ReadOptions options;
  options.text = ext == ".off" || ext == ".obj";
  options.text_prefix = ext == ".ply" ? 16 : 0;
  options.strip_bom = ext != ".stl";  // a binary STL header may start with any bytes
  const std::string data = io_detail::read_whole_file(path, options);  // Io errors: missing, directory
  if (data.empty()) throw_bad_input(path, 0, "empty file");
  SurfaceData s = ext == ".off"   ? read_off(path, data)
                  : ext == ".obj" ? read_obj(path, data)
                  : ext == ".ply" ? read_ply(path, data)
                                  : read_stl(path, data);
  for (std::uint32_t v : s.tris)
    if (v >= s.num_vertices()) throw_bad_input(path, 0, "face references a missing vertex");
  return s;
}

void write_surface(AtomicOutput& out, const SurfaceData& surface) {
  const std::string& path = out.destination();
  const std::string ext = lower_extension(path);
  if (!supported(ext)) throw Error(ErrorKind::Unsupported, path, 0, "unknown surface extension (expected .obj, .off, .stl or .ply)");
  const std::size_t nv = surface.num_vertices();
  if (surface.xyz.size() != 3 * nv || surface.tris.size() % 3 != 0)
    throw Error(ErrorKind::BadInput, path, 0, "cannot write: array sizes are not multiples of 3");
  for (double c : surface.xyz)
    if (!std::isfinite(c)) throw Error(ErrorKind::BadInput, path, 0, "cannot write: non-finite coordinate");
  for (std::uint32_t v : surface.tris)
    if (v >= nv) throw Error(ErrorKind::BadInput, path, 0, "cannot write: triangle references vertex " + std::to_string(v));
  if (ext == ".stl") {
    write_stl(out, surface);
    return;
  }
  {
    // OFF / OBJ / PLY: shortest round-trip doubles (OFF, OBJ) or raw float64 (PLY).
    io_detail::TextWriter w(out);
    const std::size_t nt = surface.num_triangles();
    if (ext == ".ply") {
      w.put("ply\nformat binary_little_endian 1.0\ncomment volmap\nelement vertex ");
      w.put_int(static_cast<std::int64_t>(nv));
      w.put("\nproperty double x\nproperty double y\nproperty double z\nelement face ");
      w.put_int(static_cast<std::int64_t>(nt));
      w.put("\nproperty list uchar int vertex_indices\nend_header\n");
      std::string bytes;
      auto put_le = [&](std::uint64_t v, std::size_t size) {
        for (std::size_t i = 0; i < size; ++i) bytes.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
      };
      for (double d : surface.xyz) {
        std::uint64_t u;
        std::memcpy(&u, &d, 8);
        put_le(u, 8);
      }
      for (std::size_t t = 0; t < nt; ++t) {
        put_le(3, 1);
        for (int c = 0; c < 3; ++c) put_le(surface.tris[3 * t + c], 4);
      }
      w.put(bytes);
    } else {
      const bool off = ext == ".off";
      if (off) {
        w.put("OFF\n");
        w.put_int(static_cast<std::int64_t>(nv));
        w.put(' ');
        w.put_int(static_cast<std::int64_t>(nt));
        w.put(" 0\n");
      }
      for (std::size_t i = 0; i < nv; ++i) {
        if (!off) w.put("v ");
        for (int c = 0; c < 3; ++c) {
          w.put_double(surface.xyz[3 * i + c]);
          w.put(c == 2 ? '\n' : ' ');
        }
      }
      for (std::size_t t = 0; t < nt; ++t) {
        w.put(off ? "3" : "f");
        for (int c = 0; c < 3; ++c) {
          w.put(' ');
          w.put_int(static_cast<std::int64_t>(surface.tris[3 * t + c]) + (off ? 0 : 1));
        }
        w.put('\n');
      }
    }
    w.flush();
  }
}

void write_surface(const std::string& path, const SurfaceData& surface) {
  AtomicOutput out(path);
  write_surface(out, surface);
  out.commit();
}

}  // namespace volmap
