// Legacy VTK and VTK XML (.vtu): every .vtk in ../shared/data loads with its README counts; real
// meshes round-trip bit-exactly through .vtk (ASCII, BINARY) and .vtu (raw, ascii); hand-made files
// cover the 5.1 layout, binary big-endian, base64, attribute sections and the cell-type rule;
// malformed files throw volmap::Error (never crash).
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>

#include "mesh_compare.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <unistd.h>
#include <fstream>

using namespace volmap;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir() { return volmap_test::scratch_dir("io_vtk"); }
std::string write_bytes(const std::string& name, const std::string& bytes) {
  return volmap_test::write_bytes(scratch_dir() / name, bytes);
}
using volmap_test::same_bits;
void check_same(const TetMeshData& a, const TetMeshData& b) { volmap_test::check_same_mesh(a, b); }
template <typename T>
void put_be(std::string& s, T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (std::size_t i = sizeof(T); i-- > 0;) s.push_back(static_cast<char>(b[i]));
}
template <typename T>
void put_le(std::string& s, T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) s.push_back(static_cast<char>(b[i]));
}
std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8 | (unsigned char)in[i + 2];
    out += k[v >> 18], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += k[v & 63];
  }
  if (i + 1 == in.size()) {
    const unsigned v = (unsigned char)in[i] << 16;
    out += k[v >> 18], out += k[(v >> 12) & 63], out += "==";
  } else if (i + 2 == in.size()) {
    const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8;
    out += k[v >> 18], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += '=';
  }
  return out;
}

// Two tets sharing face (1,2,3).
const double kXyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
const std::uint32_t kTets[] = {0, 1, 2, 3, 4, 1, 3, 2};

TetMeshData two_tets() {
  TetMeshData m;
  m.xyz.assign(std::begin(kXyz), std::end(kXyz));
  m.tets.assign(std::begin(kTets), std::end(kTets));
  m.vertex_labels.assign(5, 0);
  m.tet_labels.assign(2, 0);
  return m;
}

const char* kAsciiHead = "# vtk DataFile Version 2.0\ntitle\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n"
                         "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n";

Error vtk_error(const std::string& text, const char* name = "bad.vtk") {
  const std::string p = write_bytes(name, text);
  try {
    read_tet_mesh(p);
  } catch (const Error& e) {
    return e;
  }
  FAIL("no error for " << name);
  return Error(ErrorKind::Failed, "");
}

struct Expected {
  const char* file;
  std::size_t v, t;
};
const Expected kVtk[] = {
    {"volmap/viewer-samples/bimba_object.vtk", 16621, 64034},
    {"volmap/viewer-samples/bimba_parameter.vtk", 16621, 64034},
    {"tetmeshes/stardecompositionmaps/open.vtk", 850, 2474},
    {"tetmeshes/stardecompositionmaps/thumb.vtk", 878, 2727},
    {"maps/galaxymaps/example_object.vtk", 7, 10},
    {"maps/galaxymaps/example_parameter.vtk", 7, 10},
    {"maps/galaxymaps/tlc_polycube_bird_object.vtk", 5650, 20203},
    {"maps/galaxymaps/tlc_polycube_bird_parameter.vtk", 5650, 20203},
    {"maps/galaxymaps/tgs_100349_object.vtk", 8895, 34879},
    {"maps/galaxymaps/tgs_100349_parameter.vtk", 8895, 34879},
    {"maps/galaxymaps/cub_rockerarm291_object.vtk", 2328, 8682},
    {"maps/galaxymaps/cub_rockerarm291_parameter.vtk", 2328, 8682},
    {"maps/lim_benchmark/armadillo-598-rest.vtk", 6077, 23982},
    {"maps/lim_benchmark/armadillo-598-init.vtk", 6077, 23982},
};

}  // namespace

TEST_CASE("vtk: every .vtk in the data loads with the README counts") {
  if (volmap_test::data_root().empty()) {
    MESSAGE("skipped: ../shared/data is absent");
    return;
  }
  for (const Expected& e : kVtk) {
    const std::string file = e.file;
    CAPTURE(file);
    const auto p = volmap_test::data_file(e.file);
    if (p.empty()) continue;
    const TetMeshData m = read_tet_mesh(p.string());
    CHECK(m.num_vertices() == e.v);
    CHECK(m.num_tets() == e.t);
  }
  // example_object.vtk: first point "3 0 1".
  VOLMAP_REQUIRE_DATA(ex, "maps/galaxymaps/example_object.vtk");
  const TetMeshData m = read_vtk(ex.string());
  CHECK(m.xyz[0] == 3.0);
  CHECK(m.xyz[1] == 0.0);
  CHECK(m.xyz[2] == 1.0);
}

TEST_CASE("vtk: viewer VTK twins have the Medit coordinates and the same tets up to rotation") {
  VOLMAP_REQUIRE_DATA(obj, "volmap/viewer-samples/bimba_object.vtk");
  VOLMAP_REQUIRE_DATA(in, "volmap/viewer-samples/bimba_input.mesh");
  VOLMAP_REQUIRE_DATA(par, "volmap/viewer-samples/bimba_parameter.vtk");
  VOLMAP_REQUIRE_DATA(out, "volmap/viewer-samples/bimba_output.mesh");
  const TetMeshData a = read_vtk(obj.string()), b = read_medit(in.string());
  const TetMeshData c = read_vtk(par.string()), d = read_medit(out.string());
  CHECK(same_bits(a.xyz, b.xyz));
  CHECK(same_bits(c.xyz, d.xyz));
  REQUIRE(a.tets.size() == b.tets.size());
  std::size_t rotated = 0, mismatched = 0;
  for (std::size_t t = 0; t < a.num_tets(); ++t) {
    std::array<std::uint32_t, 4> x{a.tets[4 * t], a.tets[4 * t + 1], a.tets[4 * t + 2], a.tets[4 * t + 3]};
    std::array<std::uint32_t, 4> y{b.tets[4 * t], b.tets[4 * t + 1], b.tets[4 * t + 2], b.tets[4 * t + 3]};
    if (x != y) ++rotated;
    std::sort(x.begin(), x.end());
    std::sort(y.begin(), y.end());
    if (x != y) ++mismatched;
  }
  CHECK(mismatched == 0);
  CHECK(rotated == 18936);  // README: 18,936 of the 64,034 tets are rotated
  CHECK(a.tets == c.tets);
}

TEST_CASE("vtk/vtu: real meshes round-trip bit-exactly") {
  const char* files[] = {"volmap/G1/bone.mesh", "volmap/G1/duck.mesh", "volmap/viewer-samples/hand_aigerman.mesh",
                         "tetmeshes/robustpolycube/pente.mesh", "tetmeshes/cinolib/sphere.mesh",
                         "maps/lim_benchmark/armadillo-598-init.vtk"};
  int done = 0;
  for (const char* f : files) {
    const std::string file = f;
    CAPTURE(file);
    const auto p = volmap_test::data_file(f);
    if (p.empty()) continue;
    const TetMeshData m = read_tet_mesh(p.string());
    const std::string base = (scratch_dir() / "rt").string();
    write_vtu(base + ".vtu", m);
    check_same(read_tet_mesh(base + ".vtu"), m);
    write_vtu(base + "_a.vtu", m, {}, VtuEncoding::Ascii);
    check_same(read_tet_mesh(base + "_a.vtu"), m);
    write_vtk(base + ".vtk", m, false);
    check_same(read_tet_mesh(base + ".vtk"), m);
    write_vtk(base + "_b.vtk", m, true);
    check_same(read_tet_mesh(base + "_b.vtk"), m);
    // .mesh -> .vtu -> .mesh -> read
    write_medit(base + ".mesh", read_vtu(base + ".vtu"));
    check_same(read_medit(base + ".mesh"), m);
    ++done;
  }
  if (!volmap_test::data_root().empty()) CHECK(done == 6);
}

TEST_CASE("vtk: ASCII variants: 5.1 layout, float points, attributes, no CELL_TYPES, CRLF, blank first line") {
  // 5.1 layout with OFFSETS/CONNECTIVITY and attribute sections to skip.
  const std::string v51 =
      "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "FIELD FieldData 1\nTIME 1 1 double\n0.5\n"
      "POINTS 5 float\n0 0 0 1 0 0 0 1 0\n0 0 1 1 1 1\n"
      "METADATA\nINFORMATION 0\n\n"
      "CELLS 3 8\nOFFSETS vtktypeint64\n0 4 8\nCONNECTIVITY vtktypeint64\n0 1 2 3 4 1 3 2\n"
      "CELL_TYPES 2\n10\n10\n"
      "CELL_DATA 2\nSCALARS label int 1\nLOOKUP_TABLE default\n7 -8\n"
      "VECTORS v double\n1 2 3 4 5 6\n"
      "POINT_DATA 5\nSCALARS temp float 1\nLOOKUP_TABLE default\n1 2 3 4 5\n"
      "FIELD f 2\na 1 5 int\n1 2 3 4 5\nb 2 5 double\n1 2 3 4 5 6 7 8 9 10\n";
  TetMeshData m = read_vtk(write_bytes("v51.vtk", v51));
  CHECK(same_bits(m.xyz, two_tets().xyz));
  CHECK(m.tets == two_tets().tets);
  CHECK(m.tet_labels == std::vector<std::int32_t>{7, -8});
  // Legacy rows, CRLF, blank line before the header, empty title, no CELL_TYPES.
  const std::string legacy = "\r\n# vtk DataFile Version 2.0\r\n\r\nASCII\r\nDATASET UNSTRUCTURED_GRID\r\nPOINTS 5 double\r\n"
                             "0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n1 1 1\r\nCELLS 2 10\r\n4 0 1 2 3\r\n4 4 1 3 2";
  m = read_vtk(write_bytes("legacy.vtk", legacy));
  CHECK(m.tets == two_tets().tets);
  // Float points are rounded to float precision.
  m = read_vtk(write_bytes("float.vtk", "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n"
                                        "0.1 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n"));
  CHECK(m.xyz[0] == static_cast<double>(0.1f));
}

TEST_CASE("vtk: cell-type rule: lower-dimensional cells skipped, other 3D cells rejected") {
  const std::string mixed = std::string(kAsciiHead) + "CELLS 4 16\n1 4\n3 0 1 2\n4 0 1 2 3\n4 4 1 3 2\nCELL_TYPES 4\n1\n5\n10\n10\n"
                                                      "CELL_DATA 4\nSCALARS label int\nLOOKUP_TABLE default\n1 2 3 4\n";
  const TetMeshData m = read_vtk(write_bytes("mixed.vtk", mixed));
  CHECK(m.tets == two_tets().tets);
  CHECK(m.tet_labels == std::vector<std::int32_t>{3, 4});
  const std::string hex = std::string(kAsciiHead) + "CELLS 2 14\n4 0 1 2 3\n8 0 1 2 3 4 0 1 2\nCELL_TYPES 2\n10\n12\n";
  const Error e = vtk_error(hex, "hex.vtk");
  CHECK(e.kind() == ErrorKind::Unsupported);
  CHECK(e.reason().find("type 12") != std::string::npos);
  const Error e2 = vtk_error(std::string(kAsciiHead) + "CELLS 1 4\n3 0 1 2\n", "no_types_tri.vtk");
  CHECK(e2.reason().find("every cell must be a 4-id tet") != std::string::npos);
}

TEST_CASE("vtk: BINARY big-endian, 4.x and 5.1 layouts") {
  std::string b4 = "# vtk DataFile Version 3.0\nbin\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n";
  for (double v : kXyz) put_be(b4, v);
  b4 += "\nCELLS 2 10\n";
  for (int t = 0; t < 2; ++t) {
    put_be<std::int32_t>(b4, 4);
    for (int k = 0; k < 4; ++k) put_be<std::int32_t>(b4, static_cast<std::int32_t>(kTets[4 * t + k]));
  }
  b4 += "\nCELL_TYPES 2\n";
  put_be<std::int32_t>(b4, 10);
  put_be<std::int32_t>(b4, 10);
  b4 += "\nCELL_DATA 2\nSCALARS label int 1\nLOOKUP_TABLE default\n";
  put_be<std::int32_t>(b4, -1);
  put_be<std::int32_t>(b4, 1 << 20);
  b4 += "\n";
  TetMeshData m = read_vtk(write_bytes("b4.vtk", b4));
  CHECK(same_bits(m.xyz, two_tets().xyz));
  CHECK(m.tets == two_tets().tets);
  CHECK(m.tet_labels == std::vector<std::int32_t>{-1, 1 << 20});

  std::string b5 = "# vtk DataFile Version 5.1\nbin\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n";
  for (double v : kXyz) put_be(b5, static_cast<float>(v));
  b5 += "\nCELLS 3 8\nOFFSETS vtktypeint64\n";
  for (std::int64_t o : {0, 4, 8}) put_be(b5, o);
  b5 += "\nCONNECTIVITY vtktypeint64\n";
  for (std::uint32_t id : kTets) put_be<std::int64_t>(b5, id);
  b5 += "\nCELL_TYPES 2\n";
  put_be<std::int32_t>(b5, 10);
  put_be<std::int32_t>(b5, 10);
  b5 += "\n";
  m = read_vtk(write_bytes("b5.vtk", b5));
  CHECK(same_bits(m.xyz, two_tets().xyz));
  CHECK(m.tets == two_tets().tets);

  // Truncated binary payload.
  const Error e = vtk_error(b4.substr(0, 120), "b4_trunc.vtk");
  CHECK(e.kind() == ErrorKind::BadInput);
  CHECK(e.line() == 5);
  CHECK(e.reason().find("truncated") != std::string::npos);
}

TEST_CASE("vtk: malformed files") {
  struct Case {
    const char* name;
    std::string text;
    std::size_t line;
    const char* part;
  };
  const std::string h = kAsciiHead;
  const Case cases[] = {
      {"id_range.vtk", h + "CELLS 1 5\n4 0 1 2 5\nCELL_TYPES 1\n10\n", 11, "outside [0,5)"},
      {"id_neg.vtk", h + "CELLS 1 5\n4 0 1 -2 3\nCELL_TYPES 1\n10\n", 11, "outside"},
      {"cells_size.vtk", h + "CELLS 1 6\n4 0 1 2 3\n", 12, "truncated"},
      {"cells_rows.vtk", h + "CELLS 2 10\n4 0 1 2 3\n9 0 1 2 3\n", 11, "beyond"},
      {"types_count.vtk", h + "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10 10\n", 0, "CELL_TYPES has 2"},
      {"nan.vtk", "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1 double\n0 nan 0\n", 6, "finite"},
      {"huge.vtk", "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4000000000 double\n0 0 0\n", 5, "POINTS"},
      {"huge_cells.vtk", h + "CELLS 100000000 500000000\n4 0 1 2 3\n", 11, "cannot fit"},
      {"no_cells.vtk", h, 0, "no CELLS"},
      {"header.vtk", "hello\n", 1, "not a legacy VTK"},
      {"empty.vtk", "", 0, "empty"},
      {"encoding.vtk", "# vtk DataFile Version 2.0\nt\nUTF8\n", 3, "ASCII or BINARY"},
      {"keyword.vtk", h + "BOGUS 3\n", 11, "unexpected keyword"},
      {"wrong_count.vtk", "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 2 double\n0 0 0 1 1 1 2 2 2\n", 6, "unexpected keyword"},
  };
  for (const Case& c : cases) {
    const std::string name = c.name;
    CAPTURE(name);
    const Error e = vtk_error(c.text, c.name);
    CHECK(e.kind() == ErrorKind::BadInput);
    CHECK(e.line() == c.line);
    CHECK(e.reason().find(c.part) != std::string::npos);
  }
  const Error poly = vtk_error("# vtk DataFile Version 2.0\nt\nASCII\nDATASET POLYDATA\n", "poly.vtk");
  CHECK(poly.kind() == ErrorKind::Unsupported);
}

TEST_CASE("vtu: cell data, ascii and base64 inline, compressed rejected, malformed") {
  TetMeshData m = two_tets();
  m.tet_labels = {5, 6};
  m.vertex_labels = {0, 1, 2, 3, 4};
  const std::vector<CellDataArray> data = {{"energy", {0.1, 1e300}}, {"inverted", {0, 1}}};
  for (VtuEncoding enc : {VtuEncoding::AppendedRaw, VtuEncoding::Ascii}) {
    const std::string p = (scratch_dir() / "cd.vtu").string();
    write_vtu(p, m, data, enc);
    std::vector<CellDataArray> back;
    check_same(read_vtu(p, back), m);
    REQUIRE(back.size() == 2);
    CHECK(back[0].name == "energy");
    CHECK(back[0].values == data[0].values);
    CHECK(back[1].values == data[1].values);
  }
  // Inline base64 ("binary" format, UInt32 headers, header and data encoded together).
  auto block = [](const std::string& payload) {
    std::string s;
    put_le<std::uint32_t>(s, static_cast<std::uint32_t>(payload.size()));
    return base64(s + payload);
  };
  std::string pts, conn, off, types;
  for (double v : kXyz) put_le(pts, v);
  for (std::uint32_t id : kTets) put_le<std::int32_t>(conn, static_cast<std::int32_t>(id));
  put_le<std::int32_t>(off, 4);
  put_le<std::int32_t>(off, 8);
  types = std::string("\x0a\x0a", 2);
  const std::string b64 =
      "<?xml version=\"1.0\"?>\n<!-- comment -->\n<VTKFile type='UnstructuredGrid' version='0.1' byte_order='LittleEndian'>\n"
      "<UnstructuredGrid><Piece NumberOfPoints=\"5\" NumberOfCells=\"2\">\n"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"binary\">\n" + block(pts) +
      "\n</DataArray></Points>\n<Cells>\n"
      "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"binary\">" + block(conn) + "</DataArray>\n"
      "<DataArray type=\"Int32\" Name=\"offsets\" format=\"binary\">" + block(off) + "</DataArray>\n"
      "<DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">" + block(types) + "</DataArray>\n"
      "</Cells></Piece></UnstructuredGrid></VTKFile>\n";
  TetMeshData r = read_vtu(write_bytes("b64.vtu", b64));
  CHECK(same_bits(r.xyz, two_tets().xyz));
  CHECK(r.tets == two_tets().tets);

  std::string compressed = b64;
  compressed.replace(compressed.find("byte_order"), 10, "compressor='vtkZLibDataCompressor' byte_order");
  try {
    read_vtu(write_bytes("z.vtu", compressed));
    FAIL("compressed accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Unsupported);
  }
  // Malformed: an id out of range, truncated appended data, wrong value count, not XML.
  const std::string p = (scratch_dir() / "good.vtu").string();
  write_vtu(p, two_tets(), {}, VtuEncoding::Ascii);
  std::ifstream in(p, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string bad_id = text;
  bad_id.replace(bad_id.find("4 1 3 2"), 7, "4 1 3 9");
  CHECK_THROWS_AS(read_vtu(write_bytes("bad_id.vtu", bad_id)), Error);
  std::string few = text;
  few.replace(few.find("4 1 3 2"), 7, "4 1 3");
  CHECK_THROWS_AS(read_vtu(write_bytes("few.vtu", few)), Error);
  write_vtu(p, two_tets());
  std::ifstream in2(p, std::ios::binary);
  std::string raw((std::istreambuf_iterator<char>(in2)), std::istreambuf_iterator<char>());
  CHECK_THROWS_AS(read_vtu(write_bytes("trunc.vtu", raw.substr(0, raw.size() - 60))), Error);
  CHECK_THROWS_AS(read_vtu(write_bytes("notxml.vtu", "hello world")), Error);
  CHECK_THROWS_AS(read_vtu(write_bytes("empty.vtu", "")), Error);
  CHECK_THROWS_AS(read_tet_mesh(write_bytes("x.obj", "v 0 0 0\n")), Error);
  CHECK_THROWS_AS(read_vtu(scratch_dir().string()), Error);
  // Writer refuses cell data of the wrong size.
  CHECK_THROWS_AS(write_vtu(p, two_tets(), {{"e", {1.0}}}), Error);
}
