// Medit .mesh reader/writer: every .mesh in ../shared/data loads with the counts its README lists,
// writer round-trips bit-exactly, malformed inputs throw volmap::Error with the right line.
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>

#include "test_support.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace volmap;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir() { return volmap_test::scratch_dir("io_medit"); }

std::string write_text(const std::string& name, const std::string& text) {
  return volmap_test::write_bytes(scratch_dir() / name, text);
}

// Parses `text` and returns the thrown error (or fails the test when nothing is thrown).
Error parse_error(const std::string& text, const char* name = "bad.mesh") {
  const std::string p = write_text(name, text);
  try {
    read_medit(p);
  } catch (const Error& e) {
    return e;
  }
  FAIL("no error thrown for " << name);
  return Error(ErrorKind::Failed, "");
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

const char* kTiny =
    "MeshVersionFormatted 1\nDimension 3\nVertices\n5\n"
    "0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 1 1 7\n"
    "Tetrahedra\n2\n1 2 3 4 0\n5 2 4 3 3\nEnd\n";

struct Expected {
  const char* file;
  std::size_t v, t;
};
// Counts from ../shared/data/README.md.
const Expected kMeshes[] = {
    {"volmap/G1/bimba.mesh", 16256, 62759},         {"volmap/G1/bird.mesh", 8905, 27865},
    {"volmap/G1/blade.mesh", 22166, 83917},         {"volmap/G1/bone.mesh", 2841, 8629},
    {"volmap/G1/bumpy_sphere.mesh", 9833, 41866},   {"volmap/G1/bunny.mesh", 17222, 65694},
    {"volmap/G1/buste.mesh", 26012, 100695},        {"volmap/G1/camile_hand.mesh", 25064, 95312},
    {"volmap/G1/devil.mesh", 18791, 72372},         {"volmap/G1/duck.mesh", 2710, 13238},
    {"volmap/G1/foot.mesh", 15237, 57816},          {"volmap/G1/gargoyle.mesh", 18698, 70296},
    {"volmap/G1/hand.mesh", 10351, 45787},          {"volmap/G1/homer.mesh", 20268, 73684},
    {"volmap/G1/moai.mesh", 17179, 73126},          {"volmap/G1/mouse.mesh", 21613, 82643},
    {"volmap/G1/octa_flower.mesh", 13752, 54619},   {"volmap/G1/pig.mesh", 23046, 90395},
    {"volmap/G1/ramses.mesh", 21225, 80541},        {"volmap/G1/sphinx.mesh", 15901, 62056},
    {"volmap/viewer-samples/bimba_input.mesh", 16621, 64034},
    {"volmap/viewer-samples/bimba_output.mesh", 16621, 64034},
    {"volmap/viewer-samples/bunny_input.mesh", 23083, 98840},
    {"volmap/viewer-samples/bunny_output.mesh", 23083, 98840},
    {"volmap/viewer-samples/duck_input.mesh", 12923, 72006},
    {"volmap/viewer-samples/duck_output.mesh", 12923, 72006},
    {"volmap/viewer-samples/hand_aigerman.mesh", 9833, 47516},
    {"volmap/viewer-samples/hand_pc_aigerman.mesh", 9833, 47516},
    {"volmap/viewer-samples/max.mesh", 9867, 40076},
    {"volmap/viewer-samples/max_pc.mesh", 9867, 40076},
    {"tetmeshes/cinolib/sphere.mesh", 4505, 24013},
    {"tetmeshes/libigl_tutorial/bunny.mesh", 5433, 34055},
    {"tetmeshes/libigl_tutorial/hand.mesh", 7234, 29998},
    {"tetmeshes/libigl_tutorial/octopus-low.mesh", 452, 1140},
    {"tetmeshes/robustpolycube/B0.mesh", 999, 4365},
    {"tetmeshes/robustpolycube/pente.mesh", 286, 862},
    {"negative/robustpolycube_NY_2.mesh", 847, 1986},
};

}  // namespace

TEST_CASE("medit: tiny mesh, labels and 1-based ids") {
  const TetMeshData m = read_medit(write_text("tiny.mesh", kTiny));
  REQUIRE(m.num_vertices() == 5);
  REQUIRE(m.num_tets() == 2);
  CHECK(m.vertex_labels[4] == 7);
  CHECK(m.tet_labels == std::vector<std::int32_t>{0, 3});
  CHECK(m.tets == std::vector<std::uint32_t>{0, 1, 2, 3, 4, 1, 3, 2});
  CHECK(m.xyz[12] == 1.0);
}

TEST_CASE("medit: accepted variants") {
  // Keywords and counts split over lines, comments, CRLF, double spaces, tabs, no End, no final
  // newline, version 3, skipped sections, number spellings 1.e-3, -0, +1, 2.5E+2.
  const std::string text =
      "# header comment\r\nMeshVersionFormatted\r\n3\r\n\r\nDimension\r\n  3 # trailing comment\r\n"
      "Vertices\r\n4\r\n1.e-3  -0\t+1 0\r\n2.5E+2 0 0 0\r\n0 1 0 0\r\n0 0 1 -4\r\n"
      "Triangles 1\n1 2 3 9\nEdges\n0\nRequiredVertices 2 1 2\nCorners 1 1\n"
      "SomeUnknownSection 3\n1 2 3\n"
      "Tetrahedra\n1\n1 2 3 4 5\nEdges 1 1 2 0";
  const TetMeshData m = read_medit(write_text("variants.mesh", text));
  REQUIRE(m.num_vertices() == 4);
  REQUIRE(m.num_tets() == 1);
  CHECK(m.xyz[0] == 1e-3);
  CHECK(m.xyz[1] == 0.0);
  CHECK(std::signbit(m.xyz[1]));
  CHECK(m.xyz[2] == 1.0);
  CHECK(m.xyz[3] == 250.0);
  CHECK(m.vertex_labels[3] == -4);
  CHECK(m.tet_labels[0] == 5);
  // Tokens after End are ignored.
  const TetMeshData n = read_medit(write_text("after_end.mesh", std::string(kTiny) + "garbage 1 2 3"));
  CHECK(n.num_tets() == 2);
}

TEST_CASE("medit: malformed inputs give BadInput with file and line") {
  struct Case {
    const char* name;
    std::string text;
    std::size_t line;
    const char* reason_part;
  };
  const std::string head = "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";
  const Case cases[] = {
      {"id0", head + "Tetrahedra\n1\n0 2 3 4 0\n", 11, "outside [1,4]"},
      {"id5", head + "Tetrahedra\n1\n1 2 3 5 0\n", 11, "outside [1,4]"},
      {"idneg", head + "Tetrahedra\n1\n1 -2 3 4 0\n", 11, "outside"},
      {"dim2", "MeshVersionFormatted 1\nDimension 2\nVertices 0\n", 2, "Dimension 2"},
      {"version9", "MeshVersionFormatted 9\n", 1, "MeshVersionFormatted"},
      {"trunc_v", "MeshVersionFormatted 1\nDimension 3\nVertices\n3\n0.25 0.25 0.25 0\n1.25 0.25 0.25 0\n0.25 1.25", 7, "truncated"},
      {"trunc_t", head + "Tetrahedra\n2\n1 2 3 4 0\n1   2   3\n", 12, "truncated"},
      {"nan", "MeshVersionFormatted 1\nDimension 3\nVertices\n1\n0 nan 0 0\n", 5, "finite"},
      {"inf", "MeshVersionFormatted 1\nDimension 3\nVertices\n1\n0 0 inf 0\n", 5, "finite"},
      {"huge_exp", "MeshVersionFormatted 1\nDimension 3\nVertices\n1\n0 0 1e999 0\n", 5, "finite"},
      {"garbage", "MeshVersionFormatted 1\nDimension 3\nVertices\n1\n0 0 1x 0\n", 5, "'1x'"},
      {"overlong", "Vertices\n1\n" + std::string(5000, '1') + " 0 0 0\n", 3, "too long"},
      {"huge_count", "MeshVersionFormatted 1\nDimension 3\nVertices\n999999999\n0 0 0 0\n", 4, "cannot fit"},
      {"count_overflow", "MeshVersionFormatted 1\nDimension 3\nVertices\n999999999999\n0 0 0 0\n", 4, "maximum"},
      {"count_int64_overflow", "Vertices\n99999999999999999999999\n", 2, "integer"},
      {"huge_tets", head + "Tetrahedra\n4000000000\n1 2 3 4 0\n", 10, "Tetrahedra"},
      {"neg_count", "Vertices\n-3\n", 2, "negative"},
      {"wrong_count", head + "0 0 0 0\nTetrahedra\n1\n1 2 3 4 0\n", 9, "keyword"},
      {"no_tets", head + "End\n", 0, "no Tetrahedra"},
      {"float_id", head + "Tetrahedra\n1\n1 2 3.0 4 0\n", 11, "integer"},
      {"empty", "", 0, "empty"},
      {"comments_only", "# nothing\n\n", 0, "empty"},
      {"second_vertices", head + "Vertices\n0\n", 9, "second"},
  };
  for (const Case& c : cases) {
    const std::string name = c.name;
    CAPTURE(name);
    const Error e = parse_error(c.text, (std::string(c.name) + ".mesh").c_str());
    CHECK(e.kind() == ErrorKind::BadInput);
    CHECK(e.line() == c.line);
    CHECK(e.reason().find(c.reason_part) != std::string::npos);
    CHECK(e.file().find(c.name) != std::string::npos);
  }
  // Hexahedra are outside what we handle: Unsupported.
  try {
    read_medit(write_text("hex.mesh", head + "Hexahedra\n1\n1 2 3 4 1 2 3 4 0\n"));
    FAIL("hexahedra accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Unsupported);
  }
}

TEST_CASE("medit: missing file and directory are Io errors") {
  CHECK_THROWS_AS(read_medit((scratch_dir() / "does_not_exist.mesh").string()), Error);
  try {
    read_medit(scratch_dir().string());
    FAIL("directory accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Io);
  }
}

TEST_CASE("medit: writer round-trips bit-exactly, labels kept, atomic") {
  TetMeshData m;
  m.xyz = {0.1, -0.0, 1e-300, 5e-324, 1.7976931348623157e308, -2.0 / 3.0, 3.0, 4.0, 1.0 / 3.0, 0, 0, 1};
  m.vertex_labels = {1, -2, 3, 2147483647};
  m.tets = {3, 2, 1, 0};
  m.tet_labels = {-7};
  const std::string p = (scratch_dir() / "rt.mesh").string();
  write_medit(p, m);
  const TetMeshData r = read_medit(p);
  CHECK(same_bits(r.xyz, m.xyz));
  CHECK(r.tets == m.tets);
  CHECK(r.vertex_labels == m.vertex_labels);
  CHECK(r.tet_labels == m.tet_labels);
  // A failing write leaves no partial output and no temporary file behind.
  TetMeshData bad = m;
  bad.tets[0] = 99;
  const std::string q = (scratch_dir() / "bad_out.mesh").string();
  CHECK_THROWS_AS(write_medit(q, bad), Error);
  CHECK_FALSE(fs::exists(q));
  for (const auto& entry : fs::directory_iterator(scratch_dir()))
    CHECK(entry.path().filename().string().find(".tmp.") == std::string::npos);
  CHECK_THROWS_AS(write_medit((scratch_dir() / "no_such_dir" / "x.mesh").string(), m), Error);
}

TEST_CASE("medit: every .mesh in the data loads with the README counts and round-trips") {
  if (volmap_test::data_root().empty()) {
    MESSAGE("skipped: ../shared/data is absent");
    return;
  }
  for (const Expected& e : kMeshes) {
    const std::string file = e.file;
    CAPTURE(file);
    const auto p = volmap_test::data_file(e.file);
    if (p.empty()) {
      MESSAGE("missing " << e.file);
      continue;
    }
    const TetMeshData m = read_medit(p.string());
    CHECK(m.num_vertices() == e.v);
    CHECK(m.num_tets() == e.t);
    const std::string out = (scratch_dir() / "roundtrip.mesh").string();
    write_medit(out, m);
    const TetMeshData r = read_medit(out);
    CHECK(same_bits(r.xyz, m.xyz));
    CHECK(r.tets == m.tets);
    CHECK(r.vertex_labels == m.vertex_labels);
    CHECK(r.tet_labels == m.tet_labels);
  }
}

TEST_CASE("medit: labels and sections of specific files") {
  VOLMAP_REQUIRE_DATA(pente, "tetmeshes/robustpolycube/pente.mesh");
  const TetMeshData m = read_medit(pente.string());
  // pente.mesh: vertex labels are not all equal (README: non-zero labels), tets label 1.
  bool any_label_not_1 = false;
  for (auto l : m.vertex_labels) any_label_not_1 |= (l != 1);
  CHECK(any_label_not_1);
  CHECK(m.tet_labels[0] == 1);
  // First vertex of pente.mesh is "3 1 2 1".
  CHECK(m.xyz[0] == 3.0);
  CHECK(m.xyz[1] == 1.0);
  CHECK(m.xyz[2] == 2.0);
}

TEST_CASE("medit: parse time of G1 bunny and buste (informative)") {
  VOLMAP_REQUIRE_DATA(bunny, "volmap/G1/bunny.mesh");
  VOLMAP_REQUIRE_DATA(buste, "volmap/G1/buste.mesh");
  for (const auto& p : {bunny, buste}) {
    double best = 1e9;
    for (int rep = 0; rep < 3; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      const TetMeshData m = read_medit(p.string());
      const auto t1 = std::chrono::steady_clock::now();
      best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
      CHECK(m.num_tets() > 0);
    }
    MESSAGE(p.filename().string() << ": best parse " << best << " ms");
  }
}

TEST_CASE("medit: coordinates are the doubles std::from_chars gives (random decimal forms, exact ties)") {
  // The reader's bulk path (Tokenizer::next_plain_double: a whole vertex line at a time, falling back
  // to the token-by-token path) must read every token whole and round it correctly; the oracle is
  // std::from_chars on each token on its own.
  std::mt19937_64 rng(20261124);
  std::vector<std::string> tokens;
  auto digit_string = [&](int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += char('0' + rng() % 10);
    return s;
  };
  for (int i = 0; i < 60000; ++i) {
    const int int_digits = int(rng() % 8), frac_digits = int(rng() % 22);
    std::string t = (rng() % 3 == 0 ? "-" : "") + digit_string(int_digits);
    if (frac_digits > 0 || int_digits == 0) t += "." + digit_string(frac_digits > 0 ? frac_digits : 1);
    if (rng() % 16 == 0) t += "e" + std::to_string(int(rng() % 40) - 20);
    tokens.push_back(t);
  }
  // Shortest round-trip forms of random doubles (what volmap and most tools write) and 17-digit forms.
  std::uniform_real_distribution<double> u(-200.0, 200.0);
  for (int i = 0; i < 20000; ++i) {
    char buf[64];
    const double x = u(rng) * std::pow(10.0, double(int(rng() % 9) - 4));
    tokens.push_back(std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr));
    std::snprintf(buf, sizeof buf, "%.17g", x);
    tokens.push_back(buf);
  }
  // Exact ties between two doubles, written with decimals: 2^53 + odd, and 2^52 + k + 1/2.
  for (std::uint64_t k = 1; k < 200; k += 2) {
    tokens.push_back(std::to_string((std::uint64_t(1) << 53) + k) + ".0");
    tokens.push_back(std::to_string((std::uint64_t(1) << 52) + k) + ".5");
    tokens.push_back("-" + std::to_string((std::uint64_t(1) << 52) + k + 1) + ".5");
  }
  tokens.insert(tokens.end(), {"0.0", "-0.0", "0.5", ".25", "-.75", "7.", "0.1", "0.30000000000000004",
                               "9999999999999999999", "0.9999999999999999999", "1.0000000000000000001",
                               "123456789012345678.9", "0.00000000000000000001"});
  while (tokens.size() % 3 != 0) tokens.push_back("1");
  const std::size_t nv = tokens.size() / 3;
  std::string text = "MeshVersionFormatted 1\nDimension 3\nVertices\n" + std::to_string(nv) + "\n";
  for (std::size_t v = 0; v < nv; ++v) text += tokens[3 * v] + " " + tokens[3 * v + 1] + " " + tokens[3 * v + 2] + " 0\n";
  text += "Tetrahedra\n1\n1 2 3 4 0\nEnd\n";
  const TetMeshData m = read_medit(write_text("decimals.mesh", text));
  REQUIRE(m.xyz.size() == tokens.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    double expected = 0;
    std::from_chars(tokens[i].data(), tokens[i].data() + tokens[i].size(), expected);
    if (std::memcmp(&expected, &m.xyz[i], sizeof expected) != 0 && mismatches++ < 10)
      MESSAGE("token " << tokens[i] << ": read " << m.xyz[i] << ", from_chars " << expected);
  }
  CHECK(mismatches == 0);
}

// Regular files are read through a window of 2 MiB that slides over whole lines (io_text.hpp,
// FileWindow): a file several windows long, with the layouts that could straddle a window's end —
// records split over lines, comments, blank and CRLF lines, and one comment line longer than the
// window — must give exactly the arrays it was written from, and errors past the first window must
// name their exact line and byte offset.
TEST_CASE("medit: files longer than the reading window") {
  const std::size_t nv = 60000, nt = 150000;
  std::mt19937 rng(2026);
  std::uniform_int_distribution<int> coordinate(-4000000, 4000000);
  std::uniform_int_distribution<std::uint32_t> vertex(0, nv - 1);
  std::vector<double> xyz(3 * nv);
  std::vector<std::uint32_t> tets(4 * nt);
  for (double& x : xyz) x = coordinate(rng) / 1024.0;  // exact in decimal and in binary
  for (std::uint32_t& v : tets) v = vertex(rng);
  std::string text = "MeshVersionFormatted 1\nDimension 3\nVertices\n" + std::to_string(nv) + "\n";
  auto number = [](double x) {
    char buf[64];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
  };
  for (std::size_t i = 0; i < nv; ++i) {
    if (i == nv / 2) text += "# " + std::string(3 << 20, 'c') + "\n";  // longer than the window
    if (i % 1511 == 0) text += "# a comment line\n\n";
    const std::string sep = i % 997 == 0 ? "\n" : " ";  // a record split over two lines
    text += number(xyz[3 * i]) + " " + number(xyz[3 * i + 1]) + sep + number(xyz[3 * i + 2]) + " 0" +
            (i % 1999 == 0 ? "\r\n" : "\n");
  }
  text += "Tetrahedra\n" + std::to_string(nt) + "\n";
  for (std::size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 4; ++k) text += std::to_string(tets[4 * t + k] + 1) + (k % 2 == 0 && t % 1303 == 0 ? "  \n" : " ");
    text += "7\n";
  }
  text += "End\n";
  REQUIRE(text.size() > (6u << 20));

  const TetMeshData mesh = read_medit(write_text("long.mesh", text));
  CHECK(same_bits(mesh.xyz, xyz));
  CHECK(mesh.tets == tets);
  CHECK(mesh.tet_labels == std::vector<std::int32_t>(nt, 7));

  SUBCASE("a malformed id past the first windows names its line") {
    std::string bad = text;
    const std::size_t line_start = bad.rfind('\n', bad.size() - 200) + 1;  // a tet line near the end
    REQUIRE(line_start > bad.find("Tetrahedra"));
    bad.replace(line_start, 1, "x");
    const std::size_t bad_line = 1 + std::size_t(std::count(bad.begin(), bad.begin() + std::ptrdiff_t(line_start), '\n'));
    const Error e = parse_error(bad, "long_bad.mesh");
    CHECK(e.line() == bad_line);
  }
  SUBCASE("a NUL byte past the first window is named with its offset") {
    std::string bad = text;
    const std::size_t offset = bad.size() - 100;
    bad[offset] = '\0';
    const Error e = parse_error(bad, "long_nul.mesh");
    CHECK(e.reason().find("NUL byte at offset " + std::to_string(offset)) != std::string::npos);
  }
  SUBCASE("a file cut in its last window is truncated at the right element") {
    const std::string cut = text.substr(0, text.size() - 4 - 2 * 12);  // without End and the last tets
    const Error e = parse_error(cut, "long_cut.mesh");
    CHECK(e.reason().find("Tetrahedra block truncated") != std::string::npos);
    CHECK(e.reason().find("of " + std::to_string(nt)) != std::string::npos);
  }
}
