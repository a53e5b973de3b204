// volmap-view end to end: runs the built tool on small generated data (and on the viewer samples
// when ../shared/data is present) and inspects the page: embedded data, inlined bundle, no external
// URL, exit codes. The browser side is tested headless by viewer/test/run.sh.
#include <doctest/doctest.h>

#include <volmap/io/io.hpp>
#include <volmap/core/boundary_faces.hpp>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "view_test_support.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Run {
  int code;
  std::string out;
  std::string err;
};

Run run_view(const std::string& args, const fs::path& dir) {
  const auto out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = volmap_test::tool("volmap-view").string() + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, view_test::read_all(out.string()), view_test::read_all(err.string())};
}

fs::path scratch(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("volmap_test_view_tool_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// A fake bundle with a marker, so these tests do not need node; the real bundle is checked below.
fs::path fake_bundle(const fs::path& dir) {
  const auto p = dir / "bundle.js";
  std::ofstream(p) << "window.__volmap_fake_bundle = 'marker-7f3a';\n";
  return p;
}

}  // namespace

TEST_CASE("volmap-view writes one self-contained page for a volume map") {
  const auto dir = scratch("map");
  const auto in = view_test::grid_mesh(3);
  const auto out = view_test::twisted(in, true);
  volmap::write_medit((dir / "in.mesh").string(), in);
  volmap::write_medit((dir / "out.mesh").string(), out);
  const auto html_path = dir / "view.html";
  const Run r = run_view(q(dir / "in.mesh") + " " + q(dir / "out.mesh") + " -o " + q(html_path) + " --energy conformal --json --bundle " +
                         q(fake_bundle(dir)), dir);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["ok"] == true);
  CHECK(j["mode"] == "volume-map");
  CHECK(j["num_tets"] == in.num_tets());
  CHECK(j["num_inverted"].get<int>() > 0);  // the pushed vertex inverts some tets
  // A map onto itself scaled by 100 and twisted: conformal energy of valid tets stays >= 1.
  CHECK(j["fields"]["conformal"]["min"].get<double>() >= 1.0);

  const std::string html = view_test::read_all(html_path.string());
  CHECK(fs::file_size(html_path) == j["bytes"].get<std::uintmax_t>());
  CHECK(html.find("marker-7f3a") != std::string::npos);
  CHECK(html.find("id=\"volmap-meta\"") != std::string::npos);
  CHECK(html.find("id=\"volmap-data\"") != std::string::npos);
  CHECK(html.find("\"initial_field\":\"conformal\"") != std::string::npos);
  CHECK(html.find("\"num_inverted\":" + std::to_string(j["num_inverted"].get<int>())) != std::string::npos);
  CHECK(view_test::external_references(html) == 0);
  // The blob holds at least the coordinates (2 x f32 x 3 per vertex) and the tets (u32 x 4).
  const std::string blob = view_test::base64_decode(
      view_test::between(html, "<script type=\"application/octet-stream\" id=\"volmap-data\">", "</script>"));
  CHECK(blob.size() >= 4 * (6 * in.num_vertices() + 4 * in.num_tets()));
  fs::remove_all(dir);
}

TEST_CASE("volmap-view inlines the real viewer bundle (three.js) and loads nothing from outside") {
  const fs::path bundle = fs::path(VOLMAP_SOURCE_DIR) / "viewer" / "dist" / "viewer.js";
  if (!fs::exists(bundle)) {
    MESSAGE("skipped: viewer/dist/viewer.js is absent (run `npm ci && npm run build` in viewer/)");
    return;
  }
  const auto dir = scratch("bundle");
  const auto in = view_test::grid_mesh(2);
  volmap::write_medit((dir / "in.mesh").string(), in);
  // Default bundle path: baked in at compile time, no --bundle.
  const Run r = run_view(q(dir / "in.mesh") + " -o " + q(dir / "mesh.html"), dir);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const std::string html = view_test::read_all((dir / "mesh.html").string());
  const std::string js = view_test::read_all(bundle.string());
  CHECK(js.size() > 100000);  // three.js is in it
  CHECK(html.find(js) != std::string::npos);
  CHECK(view_test::external_references(html) == 0);
  CHECK(html.find("\"mode\":\"mesh\"") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("an installed volmap-view reads the installed bundle from ../share/volmap/viewer next to its bin/") {
  // The default GNUInstallDirs layout of `cmake --install`: <prefix>/bin and <prefix>/share.
  const auto dir = scratch("installed");
  const auto prefix = dir / "prefix";
  fs::create_directories(prefix / "bin");
  fs::create_directories(prefix / "share" / "volmap" / "viewer");
  fs::copy_file(volmap_test::tool("volmap-view"), prefix / "bin" / "volmap-view");
  std::ofstream(prefix / "share" / "volmap" / "viewer" / "viewer.js") << "window.__volmap_installed = 'marker-5c1e';\n";
  volmap::write_medit((dir / "in.mesh").string(), view_test::grid_mesh(2));
  const std::string cmd = "env -u VOLMAP_VIEWER_BUNDLE " + q(prefix / "bin" / "volmap-view") + " " + q(dir / "in.mesh") +
                          " -o " + q(dir / "mesh.html") + " --json >" + q(dir / "stdout.txt") + " 2>" + q(dir / "stderr.txt");
  const int status = std::system(cmd.c_str());
  REQUIRE_MESSAGE((WIFEXITED(status) && WEXITSTATUS(status) == 0), view_test::read_all((dir / "stderr.txt").string()));
  const auto j = nlohmann::json::parse(view_test::read_all((dir / "stdout.txt").string()));
  CHECK(fs::path(j["bundle"].get<std::string>()) == fs::canonical(prefix / "share" / "volmap" / "viewer" / "viewer.js"));
  CHECK(view_test::read_all((dir / "mesh.html").string()).find("marker-5c1e") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("volmap-view boundary-map mode embeds the mapped positions of boundary vertices") {
  const auto dir = scratch("bmap");
  const auto in = view_test::grid_mesh(3);
  const auto moved = view_test::twisted(in, false);
  volmap::BoundaryMap map;
  for (std::uint32_t v : volmap::boundary_vertex_ids(in)) {
    map.vids.push_back(v);
    map.xyz.insert(map.xyz.end(), {moved.xyz[3 * v], moved.xyz[3 * v + 1], moved.xyz[3 * v + 2]});
  }
  volmap::write_medit((dir / "in.mesh").string(), in);
  volmap::write_boundary_map((dir / "map.txt").string(), map);
  const Run r = run_view(q(dir / "in.mesh") + " --map " + q(dir / "map.txt") + " -o " + q(dir / "b.html") + " --energy quality_in --json --bundle " +
                         q(fake_bundle(dir)), dir);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["mode"] == "boundary-map");
  CHECK(j["num_inverted"] == 0);
  const std::string html = view_test::read_all((dir / "b.html").string());
  CHECK(html.find("\"target_xyz\":{\"type\":\"f32\"") != std::string::npos);
  CHECK(html.find("\"target_name\":\"map.txt\"") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("volmap-view refuses bad input with exit 2 and a one-line reason") {
  const auto dir = scratch("bad");
  const auto in = view_test::grid_mesh(2);
  const auto other = view_test::grid_mesh(3);
  volmap::write_medit((dir / "in.mesh").string(), in);
  volmap::write_medit((dir / "other.mesh").string(), other);
  const std::string bundle = " --bundle " + q(fake_bundle(dir));
  const std::string o = " -o " + q(dir / "x.html");
  Run r = run_view(q(dir / "missing.mesh") + o + bundle, dir);
  CHECK(r.code == 2);
  r = run_view(q(dir / "in.mesh") + " " + q(dir / "other.mesh") + o + bundle, dir);
  CHECK(r.code == 2);
  CHECK(r.err.find("not a map") != std::string::npos);
  r = run_view(q(dir / "in.mesh") + " " + q(dir / "in.mesh") + " --energy nonsense" + o + bundle, dir);
  CHECK(r.code == 2);
  CHECK(r.err.find("mips3d") != std::string::npos);  // lists the available fields
  r = run_view(q(dir / "in.mesh") + o + " --bundle " + q(dir / "no-bundle.js"), dir);
  CHECK(r.code == 2);
  CHECK(r.err.find("npm ci") != std::string::npos);
  r = run_view("", dir);
  CHECK(r.code == 2);
  CHECK(!fs::exists(dir / "x.html"));
  r = run_view("--help", dir);
  CHECK(r.code == 0);
  fs::remove_all(dir);
}

TEST_CASE("volmap-view on the viewer samples: VOLMAP figures and exact inverted counts") {
  VOLMAP_REQUIRE_DATA(bunny_in, "volmap/viewer-samples/bunny_input.mesh");
  VOLMAP_REQUIRE_DATA(bunny_out, "volmap/viewer-samples/bunny_output.mesh");
  const auto dir = scratch("samples");
  const std::string bundle = " --bundle " + q(fake_bundle(dir));
  Run r = run_view(q(bunny_in) + " " + q(bunny_out) + " -o " + q(dir / "bunny.html") + " --json" + bundle, dir);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  auto j = nlohmann::json::parse(r.out);
  // volmap-reference.md §7/§9: the reference metrics tool on the bunny pair.
  CHECK(j["num_tets"] == 98840);
  CHECK(j["num_inverted"] == 0);
  CHECK(j["fields"]["conformal"]["weighted_mean"].get<double>() == doctest::Approx(2.01942).epsilon(5e-6));
  CHECK(j["fields"]["conformal"]["min"].get<double>() == doctest::Approx(1.00379).epsilon(5e-6));
  CHECK(j["fields"]["mips3d"]["weighted_mean"].get<double>() == doctest::Approx(6.88193).epsilon(5e-6));
  CHECK(j["fields"]["mips3d"]["min"].get<double>() == doctest::Approx(1.00859).epsilon(5e-6));

  // The page's singular values of J (view adapter, eigenvalues of JᵀJ) reproduce the metrics module's
  // per-tet MIPS3D and Conformal (computed from the invariants of JᵀJ) on every tet.
  {
    const std::string html = view_test::read_all((dir / "bunny.html").string());
    const auto meta = nlohmann::json::parse(view_test::between(html, "id=\"volmap-meta\">", "</script>"));
    const std::string blob = view_test::base64_decode(view_test::between(html, "id=\"volmap-data\">", "</script>"));
    auto floats = [&](const std::string& name) {
      const auto& a = meta["arrays"][name];
      std::vector<float> v(a["count"].get<std::size_t>());
      std::memcpy(v.data(), blob.data() + a["offset"].get<std::size_t>(), 4 * v.size());
      return v;
    };
    const auto sigma = floats("sigma"), mips = floats("field_mips3d"), conf = floats("field_conformal");
    REQUIRE(sigma.size() == 3 * mips.size());
    std::size_t disagree = 0, saturated = 0;
    for (std::size_t t = 0; t < mips.size(); ++t) {
      const double s1 = sigma[3 * t], s2 = sigma[3 * t + 1], s3 = sigma[3 * t + 2];
      const double m = std::min(100.0, (s1 / s2 + s2 / s1) * (s3 / s1 + s1 / s3) * (s2 / s3 + s3 / s2) / 8);
      const double c = std::min(100.0, (s1 * s1 + s2 * s2 + s3 * s3) / (3 * std::cbrt(s1 * s1 * s2 * s2 * s3 * s3)));
      disagree += std::fabs(m - mips[t]) > 1e-3 * m || std::fabs(c - conf[t]) > 1e-3 * c ? 1 : 0;
      saturated += mips[t] >= 100 ? 1 : 0;
      disagree += s1 >= s2 && s2 >= s3 && s3 > 0 ? 0 : 1;  // sorted, positive (no flat tet here)
    }
    CHECK(disagree == 0);
    MESSAGE("bunny pair: " << saturated << " of " << mips.size() << " tets have MIPS3D clamped at 100");
  }

  // The hand and max polycube pairs are all-negative; relative to the source (volmap-map-check's oracle):
  // hand 95 inverted + 3 degenerate, max 45 + 198.
  const auto hand_in = volmap_test::data_file("volmap/viewer-samples/hand_aigerman.mesh");
  const auto hand_out = volmap_test::data_file("volmap/viewer-samples/hand_pc_aigerman.mesh");
  if (!hand_in.empty() && !hand_out.empty()) {
    r = run_view(q(hand_in) + " " + q(hand_out) + " -o " + q(dir / "hand.html") + " --json" + bundle, dir);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    j = nlohmann::json::parse(r.out);
    CHECK(j["num_inverted"] == 95);
    CHECK(j["num_degenerate"] == 3);
  }
  const auto max_in = volmap_test::data_file("volmap/viewer-samples/max.mesh");
  const auto max_out = volmap_test::data_file("volmap/viewer-samples/max_pc.mesh");
  if (!max_in.empty() && !max_out.empty()) {
    r = run_view(q(max_in) + " " + q(max_out) + " -o " + q(dir / "max.html") + " --json" + bundle, dir);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    j = nlohmann::json::parse(r.out);
    CHECK(j["num_inverted"] == 45);
    CHECK(j["num_degenerate"] == 198);
  }
  fs::remove_all(dir);
}
