// Exact volume-map check: relative (VOLMAP) and absolute modes, degenerate = invalid, connectivity
// pairing (identical / per-tet reordered / tets permuted / mismatch = BadInput), boundary bit-exactness,
// rationals (exact conversion, rational-only degeneracies), and the VOLMAP oracles on the viewer pairs:
// bunny, duck, bimba valid; hand 98 (95 flipped + 3 zero) and max 243 (45 + 198) invalid.
#include <doctest/doctest.h>
#include <volmap/core/error.hpp>
#include <volmap/io/io.hpp>
#include <volmap/check/map_check.hpp>

#include "test_support.hpp"
#include "vmap_test_util.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace volmap;
namespace fs = std::filesystem;
using vmap_test::quote;

namespace {
fs::path scratch() {
  fs::path d = fs::temp_directory_path() / ("vmap_test_map_check_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST_CASE("identity map is certified; a flipped and a flattened tet are caught exactly") {
  const TetMeshData in = vmap_test::kuhn_grid(2);
  MapCheckReport r = check_map(in, in);
  CHECK(r.certified());
  CHECK(r.connectivity == ConnectivityMatch::Identical);
  CHECK(r.input.positive == in.num_tets());
  CHECK(r.relative_positive == in.num_tets());

  // Move the centre vertex (1,1,1)/2 far outside: some tets flip.
  TetMeshData out = in;
  const std::size_t centre = 1 + 3 * (1 + 3 * 1);
  out.xyz[3 * centre] = 5.0;
  r = check_map(in, out);
  CHECK(!r.certified());
  CHECK(r.relative_negative > 0);
  CHECK(r.num_bad == r.relative_negative + r.relative_zero);
  REQUIRE(!r.first_bad.empty());
  CHECK(std::is_sorted(r.first_bad.begin(), r.first_bad.end()));

  // Put the centre exactly on the plane x = 1 (the face plane holding other vertices of some of its
  // tets): those tets become exactly degenerate and count as zero (invalid).
  out = in;
  out.xyz[3 * centre] = 1.0;
  r = check_map(in, out);
  CHECK(r.relative_zero > 0);
  CHECK(r.output.zero == r.relative_zero);
  CHECK(!r.map_valid());
}

TEST_CASE("connectivity: rotated per-tet order and permuted tets are evaluated in the input's order") {
  const TetMeshData in = vmap_test::kuhn_grid(2);
  TetMeshData out = in;
  // Even rotation of the first three vertices of tet 0, odd swap in tet 1.
  std::swap(out.tets[0], out.tets[1]);
  std::swap(out.tets[1], out.tets[2]);
  std::swap(out.tets[4], out.tets[5]);
  MapCheckReport r = check_map(in, out);
  CHECK(r.connectivity == ConnectivityMatch::Reordered);
  CHECK(r.certified());  // relative check in the input order: unaffected
  MapCheckOptions absolute;
  absolute.absolute = true;
  r = check_map(in, out, nullptr, absolute);
  CHECK(r.output_own_order.negative == 1);  // the odd swap is negative in the output's own order
  CHECK(r.num_bad == 1);
  CHECK(r.first_bad.at(0) == 1);

  // Tets in reverse order.
  TetMeshData permuted = in;
  for (std::size_t t = 0; t < in.num_tets(); ++t)
    for (int k = 0; k < 4; ++k) permuted.tets[4 * t + k] = in.tets[4 * (in.num_tets() - 1 - t) + k];
  r = check_map(in, permuted, nullptr, absolute);
  CHECK(r.connectivity == ConnectivityMatch::Permuted);
  CHECK(r.certified());

  // Mismatches are BadInput with a reason.
  TetMeshData other = in;
  other.tets[0] = other.tets[8] == other.tets[0] ? other.tets[9] : other.tets[8];
  CHECK_THROWS_AS(check_map(in, other), Error);
  TetMeshData fewer = in;
  fewer.tets.resize(fewer.tets.size() - 4);
  try {
    check_map(in, fewer);
    FAIL("expected BadInput");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::BadInput);
    CHECK(std::string(e.what()).find("tet count") != std::string::npos);
  }
  TetMeshData out_of_range = in;
  out_of_range.tets[3] = 1000;
  CHECK_THROWS_AS(check_map(in, out_of_range), Error);
  TetMeshData nan = in;
  nan.xyz[0] = std::nan("");
  CHECK_THROWS_AS(check_map(in, nan), Error);
}

TEST_CASE("boundary map: vertices must sit exactly on the prescribed doubles") {
  const TetMeshData in = vmap_test::kuhn_grid(2);
  BoundaryMap map;
  for (std::uint32_t v = 0; v < in.num_vertices(); ++v) {
    if (v == 13) continue;  // the centre is interior
    map.vids.push_back(v);
    map.xyz.insert(map.xyz.end(), {in.xyz[3 * v], in.xyz[3 * v + 1], in.xyz[3 * v + 2]});
  }
  CHECK(check_map(in, in, &map).certified());
  TetMeshData out = in;
  out.xyz[3 * 2] = std::nextafter(out.xyz[3 * 2], 2.0);  // one ulp off
  const MapCheckReport r = check_map(in, out, &map);
  CHECK(r.boundary_mismatches == 1);
  CHECK(r.first_boundary_mismatches.at(0) == 2);
  CHECK(!r.certified());
  CHECK(r.map_valid());
}

TEST_CASE("rationals: exact conversion agrees with doubles; rational-only degeneracy is found") {
  const TetMeshData in = vmap_test::kuhn_grid(2);
  const std::vector<Rational> rin = rationals_from_doubles(in.xyz);
  CHECK(rin[3] == Rational(0.5));
  MapCheckReport r = check_map_rational(in, rin, in, rin);
  CHECK(r.rational);
  CHECK(r.certified());
  // Centre moved to x = 1 exactly in rationals: same degeneracy as with doubles.
  std::vector<Rational> rout = rin;
  rout[3 * 13] = Rational(1);
  r = check_map_rational(in, rin, in, rout);
  CHECK(r.relative_zero > 0);
  // A position doubles cannot represent: 1/3 along an edge direction, exactly coplanar with a face
  // of the grid (x = 1/3 is not a grid plane, so nothing is degenerate) vs the double 0.333… (valid).
  rout = rin;
  rout[3 * 13] = Rational(1, 3);
  CHECK(check_map_rational(in, rin, in, rout).certified());
  // Wrong lengths are BadInput.
  rout.pop_back();
  CHECK_THROWS_AS(check_map_rational(in, rin, in, rout), Error);
}

TEST_CASE("viewer pairs: bunny; duck; bimba valid; hand 95+3 and max 45+198 invalid; mismatches exit 2") {
  VOLMAP_REQUIRE_DATA(dir, "volmap/viewer-samples");
  const auto tool = volmap_test::tool("volmap-map-check").string();
  for (const char* name : {"bunny", "duck", "bimba"}) {
    const auto r = vmap_test::run(tool + " " + quote((dir / (std::string(name) + "_input.mesh")).string()) + " " +
                                  quote((dir / (std::string(name) + "_output.mesh")).string()) + " --json");
    INFO(name);
    CHECK(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["certified"] == true);
    CHECK(j["num_bad"] == 0);
  }
  struct Bad {
    const char *in, *out;
    int flipped, zero;
  };
  for (const Bad& b : {Bad{"hand_aigerman", "hand_pc_aigerman", 95, 3}, Bad{"max", "max_pc", 45, 198}}) {
    const auto r = vmap_test::run(tool + " " + quote((dir / (std::string(b.in) + ".mesh")).string()) + " " +
                                  quote((dir / (std::string(b.out) + ".mesh")).string()) + " --json");
    INFO(b.in);
    CHECK(r.code == 1);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["relative"]["negative"] == b.flipped);
    CHECK(j["relative"]["zero"] == b.zero);
    CHECK(j["num_bad"] == b.flipped + b.zero);
    CHECK(j["valid"] == false);
    CHECK(j["input_all_positive"] == false);  // these sources use the opposite convention
    CHECK(j["first_bad_tets"].size() == 20);
  }
  // bunny input vs duck output: different meshes.
  auto r = vmap_test::run(tool + " " + quote((dir / "bunny_input.mesh").string()) + " " +
                          quote((dir / "duck_output.mesh").string()) + " --json");
  CHECK(r.code == 2);
  CHECK(nlohmann::json::parse(r.out)["ok"] == false);
  CHECK(vmap_test::run(tool + " " + quote((dir / "bunny_input.mesh").string())).code == 2);
  CHECK(vmap_test::run(tool + " /nonexistent.mesh /nonexistent2.mesh").code == 2);
}

TEST_CASE("duck pair on rationals written from the doubles: same verdict; also 3-file form") {
  VOLMAP_REQUIRE_DATA(in_path, "volmap/viewer-samples/duck_input.mesh");
  VOLMAP_REQUIRE_DATA(out_path, "volmap/viewer-samples/duck_output.mesh");
  const TetMeshData in = read_medit(in_path.string());
  const TetMeshData out = read_medit(out_path.string());
  const fs::path d = scratch();
  write_rationals((d / "in_rat.txt").string(), rationals_from_doubles(in.xyz));
  write_rationals((d / "out_rat.txt").string(), rationals_from_doubles(out.xyz));
  // Read back: identical to the exact doubles.
  CHECK(read_rationals((d / "out_rat.txt").string(), out.num_vertices()) == rationals_from_doubles(out.xyz));
  const auto tool = volmap_test::tool("volmap-map-check").string();
  auto r = vmap_test::run(tool + " " + quote(in_path.string()) + " " + quote(out_path.string()) + " --rationals-in " +
                          quote((d / "in_rat.txt").string()) + " --rationals-out " + quote((d / "out_rat.txt").string()) +
                          " --json");
  CHECK(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  CHECK(j["arithmetic"] == "rational");
  CHECK(j["output"]["positive"] == 72006);
  r = vmap_test::run(tool + " " + quote(in_path.string()) + " " + quote(out_path.string()) + " --rationals-out " +
                     quote((d / "out_rat.txt").string()) + " --json");
  CHECK(r.code == 0);
  // A wrong token count is bad input.
  CHECK(vmap_test::run(tool + " " + quote(in_path.string()) + " " + quote(out_path.string()) + " --rationals-out " +
                       quote((d / "in_rat.txt").string()) + " --rationals-in " + quote(out_path.string()))
            .code == 2);
  fs::remove_all(d);
}

TEST_CASE("volmap-map-check reads legacy VTK maps: the GalaxyMaps example initial map has 2 flipped tets") {
  VOLMAP_REQUIRE_DATA(object, "maps/galaxymaps/example_object.vtk");
  VOLMAP_REQUIRE_DATA(parameter, "maps/galaxymaps/example_parameter.vtk");
  const auto tool = volmap_test::tool("volmap-map-check").string();
  auto r = vmap_test::run(tool + " " + quote(object.string()) + " " + quote(parameter.string()) + " --json");
  CHECK(r.code == 1);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["num_tets"] == 10);
  CHECK(j["output"]["negative"] == 2);
  CHECK(j["output"]["positive"] == 8);
  // The source against itself is valid.
  CHECK(vmap_test::run(tool + " " + quote(object.string()) + " " + quote(object.string())).code == 0);
}

TEST_CASE("tools on malformed or mismatched files: exit 2; one-line reason; no crash") {
  const fs::path d = scratch();
  const TetMeshData grid = vmap_test::kuhn_grid(2);
  write_medit((d / "a.mesh").string(), grid);
  TetMeshData fewer = grid;
  fewer.tets.resize(fewer.tets.size() - 4);
  fewer.tet_labels.resize(fewer.num_tets());
  write_medit((d / "fewer.mesh").string(), fewer);
  TetMeshData other = grid;  // same counts, one tet with a different vertex set
  other.tets[0] = other.tets[0] == 26 ? 25 : 26;
  write_medit((d / "other.mesh").string(), other);
  std::ofstream((d / "garbage.mesh").string()) << "MeshVersionFormatted 1\nDimension 3\nVertices\n2\n0 0 0 0\n";
  const auto check = volmap_test::tool("volmap-map-check").string();
  const auto metrics = volmap_test::tool("volmap-metrics").string();
  for (const char* bad : {"fewer.mesh", "other.mesh", "garbage.mesh"}) {
    INFO(bad);
    auto r = vmap_test::run(check + " " + quote((d / "a.mesh").string()) + " " + quote((d / bad).string()) + " --json");
    CHECK(r.code == 2);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["ok"] == false);
    CHECK(!j["error"].get<std::string>().empty());
    CHECK(vmap_test::run(metrics + " " + quote((d / "a.mesh").string()) + " " + quote((d / bad).string())).code == 2);
  }
  auto r = vmap_test::run(check + " " + quote((d / "a.mesh").string()) + " " + quote((d / "fewer.mesh").string()) + " --json");
  CHECK(nlohmann::json::parse(r.out)["error"].get<std::string>().find("tet count mismatch") != std::string::npos);
  r = vmap_test::run(check + " " + quote((d / "a.mesh").string()) + " " + quote((d / "other.mesh").string()) + " --json");
  CHECK(nlohmann::json::parse(r.out)["error"].get<std::string>().find("connectivity mismatch") != std::string::npos);

  // Boundary maps with bad ids (out of range, interior vertex 13) for both tools.
  std::ofstream((d / "bad_range.txt").string()) << "0 0 0 0\n999 1 1 1\n";
  std::ofstream((d / "interior.txt").string()) << "13 0.5 0.5 0.5\n";
  const auto tutte = volmap_test::tool("volmap-tutte3d").string();
  for (const char* m : {"bad_range.txt", "interior.txt"}) {
    INFO(m);
    CHECK(vmap_test::run(check + " " + quote((d / "a.mesh").string()) + " " + quote((d / "a.mesh").string()) +
                         " --boundary " + quote((d / m).string()))
              .code == 2);
    CHECK(vmap_test::run(tutte + " " + quote((d / "a.mesh").string()) + " " + quote((d / m).string()) + " " +
                         quote((d / "out.mesh").string()))
              .code == 2);
    CHECK(!fs::exists(d / "out.mesh"));
  }
  fs::remove_all(d);
}

TEST_CASE("fused chunked pass: bad tets spread over many chunks give the same report serial and parallel") {
  // 6·24³ = 82944 tets: about 20 chunks of the fused pass. Flip one vertex far from the others and
  // flatten another so that bad tets land in several chunks; counts and the first ids must agree with
  // a per-tet recount, in increasing order, and with the serial run.
  const TetMeshData in = vmap_test::kuhn_grid(24);
  TetMeshData out = in;
  const std::size_t nv = in.num_vertices();
  // Collapse vertex 0 of a few far-apart tets onto its vertex 1: every tet holding that edge becomes
  // exactly degenerate, neighbours may flip.
  for (const std::size_t t : {std::size_t(100), std::size_t(30000), std::size_t(60001), std::size_t(82900)}) {
    const std::uint32_t a = in.tets[4 * t], b = in.tets[4 * t + 1];
    for (int k = 0; k < 3; ++k) out.xyz[3 * a + k] = out.xyz[3 * b + k];
  }
  std::vector<std::int8_t> si(in.num_tets()), so(in.num_tets());
  orient3d_tets(in.xyz.data(), nv, in.tets.data(), in.num_tets(), si.data());
  orient3d_tets(out.xyz.data(), nv, in.tets.data(), in.num_tets(), so.data());
  std::size_t bad = 0;
  std::vector<std::uint64_t> first;
  for (std::size_t t = 0; t < in.num_tets(); ++t) {
    if (si[t] == 0 || so[t] == 0 || si[t] != so[t]) {
      ++bad;
      if (first.size() < 5) first.push_back(t);
    }
  }
  REQUIRE(bad > 0);
  for (const bool parallel : {true, false}) {
    MapCheckOptions o;
    o.parallel = parallel;
    o.max_reported_bad = 5;
    const MapCheckReport r = check_map(in, out, nullptr, o);
    CHECK(r.num_bad == bad);
    CHECK(r.first_bad == first);
    CHECK(r.relative_positive + r.relative_zero + r.relative_negative == in.num_tets());
    CHECK(r.input.positive == in.num_tets());
    CHECK(r.output.positive + r.output.zero + r.output.negative == in.num_tets());
    CHECK(!r.certified());
  }
}

TEST_CASE("blocked check: an output differing from the input's tet array in one far block is paired; absolute catches an odd order") {
  // 82944 tets = 11 blocks of the blocked check. Identity map; the output swaps tets 5 and 70000
  // (Permuted) and lists tet 40000 with v0 and v1 exchanged (odd: negative in its own order).
  const TetMeshData in = vmap_test::kuhn_grid(24);
  TetMeshData out = in;
  for (int k = 0; k < 4; ++k) std::swap(out.tets[4 * 5 + k], out.tets[4 * 70000 + k]);
  std::swap(out.tets[4 * 40000], out.tets[4 * 40000 + 1]);
  for (const bool parallel : {true, false}) {
    MapCheckOptions o;
    o.parallel = parallel;
    MapCheckReport r = check_map(in, out, nullptr, o);
    CHECK(r.connectivity == ConnectivityMatch::Permuted);
    CHECK(r.num_bad == 0);
    CHECK(r.certified());
    o.absolute = true;
    r = check_map(in, out, nullptr, o);
    CHECK(r.num_bad == 1);
    CHECK(r.first_bad == std::vector<std::uint64_t>{40000});
    CHECK(r.output_own_order.negative == 1);
    // A tet whose vertex set is missing from the output is a mismatch, found although 5 of 6 blocks
    // are identical.
    TetMeshData broken = in;
    broken.tets[4 * 81000] = broken.tets[4 * 81000 + 1];
    CHECK_THROWS_AS(check_map(in, broken, nullptr, o), Error);
  }
}
