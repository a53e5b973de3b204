// volmap::view_export: the self-contained HTML page of volmap-view (data packing, base64, summary
// figures, refusal of bad inputs). The tool end-to-end is in test_view_tool.cpp.
#include <doctest/doctest.h>

#include <volmap/core/error.hpp>
#include "support/view_export.hpp"

#include "view_test_support.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

using namespace volmap;

namespace {

// A ViewData with hand-made per-tet values (not metrics: this tests the packing only).
ViewData synthetic_view(int n) {
  const auto in = view_test::grid_mesh(n);
  const auto out = view_test::twisted(in, true);
  ViewData d;
  d.mode = ViewMode::VolumeMap;
  d.title = "grid <test> & co";
  d.source_name = "in.mesh";
  d.target_name = "out.mesh";
  d.source_xyz = in.xyz;
  d.target_xyz = out.xyz;
  d.tets = in.tets;
  const std::size_t nt = in.num_tets();
  d.flags.assign(nt, 0);
  d.volume_in.resize(nt);
  d.volume_out.resize(nt);
  d.sigma.resize(3 * nt);
  ViewField f;
  f.key = "mips3d";
  f.label = "MIPS3D";
  f.lower = 1;
  f.upper = 100;
  f.values.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tv = &in.tets[4 * t];
    const int s = orient3d(&out.xyz[3 * tv[0]], &out.xyz[3 * tv[1]], &out.xyz[3 * tv[2]], &out.xyz[3 * tv[3]]);
    d.flags[t] = s < 0 ? kViewInverted : s == 0 ? kViewDegenerate : 0;
    d.volume_in[t] = 1.0 / (6.0 * n * n * n);
    d.volume_out[t] = double(t % 7 + 1);
    d.sigma[3 * t] = 3;
    d.sigma[3 * t + 1] = 2;
    d.sigma[3 * t + 2] = 1;
    f.values[t] = 1.0 + double(t % 10);
  }
  d.fields.push_back(f);
  d.initial_field = "mips3d";
  return d;
}

}  // namespace

TEST_CASE("base64 matches the RFC 4648 test vectors") {
  auto enc = [](const char* s) { return base64_encode(reinterpret_cast<const std::uint8_t*>(s), std::strlen(s)); };
  CHECK(enc("") == "");
  CHECK(enc("f") == "Zg==");
  CHECK(enc("fo") == "Zm8=");
  CHECK(enc("foo") == "Zm9v");
  CHECK(enc("foob") == "Zm9vYg==");
  CHECK(enc("fooba") == "Zm9vYmE=");
  CHECK(enc("foobar") == "Zm9vYmFy");
  const std::uint8_t all[3] = {0xff, 0xfe, 0x00};
  CHECK(base64_encode(all, 3) == "//4A");
}

TEST_CASE("the page embeds the data as typed arrays that decode back to the inputs") {
  const ViewData d = synthetic_view(3);
  const std::string bundle = "window.__bundle_marker = 42;";
  const std::string html = build_view_html(d, bundle);
  CHECK(html.find("window.__bundle_marker = 42;") != std::string::npos);
  CHECK(view_test::external_references(html) == 0);
  // The title is escaped in <title> and in the JSON header.
  CHECK(html.find("grid &lt;test&gt; &amp; co") != std::string::npos);
  CHECK(html.find("<test>") == std::string::npos);

  const std::string meta = view_test::between(html, "<script type=\"application/json\" id=\"volmap-meta\">", "</script>");
  REQUIRE(!meta.empty());
  CHECK(meta.find("\"format\":\"volmap-view-1\"") != std::string::npos);
  CHECK(meta.find("\"mode\":\"volume-map\"") != std::string::npos);
  CHECK(meta.find("\"num_tets\":" + std::to_string(d.num_tets())) != std::string::npos);
  const std::string blob64 = view_test::between(html, "<script type=\"application/octet-stream\" id=\"volmap-data\">", "</script>");
  const std::string blob = view_test::base64_decode(blob64);
  CHECK(meta.find("\"byte_length\":" + std::to_string(blob.size())) != std::string::npos);

  // "tets" follows "source_xyz" (f32, 3*nv) at the next 4-byte boundary: read it back.
  const std::size_t tets_offset = 4 * d.source_xyz.size();
  CHECK(meta.find("\"tets\":{\"type\":\"u32\",\"offset\":" + std::to_string(tets_offset) + ",\"count\":" +
                  std::to_string(d.tets.size()) + "}") != std::string::npos);
  REQUIRE(blob.size() >= tets_offset + 4 * d.tets.size());
  std::vector<std::uint32_t> tets(d.tets.size());
  std::memcpy(tets.data(), blob.data() + tets_offset, 4 * tets.size());
  CHECK(tets == d.tets);
  float x0 = 0;
  std::memcpy(&x0, blob.data() + 4 * 4, 4);  // source vertex 1, x
  CHECK(x0 == static_cast<float>(d.source_xyz[4]));
}

TEST_CASE("summary figures follow the VOLMAP metrics rules (valid tets, clamp, |V_out| weights)") {
  ViewData d;
  d.mode = ViewMode::VolumeMap;
  d.source_xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  d.target_xyz = d.source_xyz;
  d.tets = {0, 1, 2, 3, 1, 2, 3, 4, 0, 2, 1, 3, 0, 1, 2, 4};
  d.flags = {0, 0, kViewInverted, 0};
  d.volume_in = {1, 1, 1, 1};
  d.volume_out = {1, -3, 5, 2};  // |V| weights; tet 2 is inverted and must not count
  ViewField f;
  f.key = "conformal";
  f.label = "Conformal";
  f.lower = 1;
  f.upper = 100;
  f.values = {2, 0.5 /* clamps to 1 */, 7, std::numeric_limits<double>::infinity() /* -> 100 */};
  d.fields.push_back(f);
  const ViewSummary s = summarize_view(d);
  CHECK(s.num_inverted == 1);
  CHECK(s.num_degenerate == 0);
  REQUIRE(s.fields.size() == 1);
  CHECK(s.fields[0].count == 3);
  CHECK(s.fields[0].min == 1);
  CHECK(s.fields[0].max == 100);
  CHECK(s.fields[0].weighted_mean == doctest::Approx((2 * 1 + 1 * 3 + 100 * 2) / 6.0));

  d.flags = {kViewInverted, kViewInverted, kViewInverted, kViewDegenerate};
  const ViewSummary none = summarize_view(d);
  CHECK(none.fields[0].count == 0);
  CHECK(std::isnan(none.fields[0].weighted_mean));
  CHECK(none.num_degenerate == 1);
}

TEST_CASE("bad view data and un-inlinable bundles are refused") {
  ViewData d = synthetic_view(2);
  CHECK_THROWS_AS(build_view_html(d, ""), Error);
  CHECK_THROWS_AS(build_view_html(d, "var s = '</SCRIPT>';"), Error);
  ViewData bad_id = d;
  bad_id.tets[5] = static_cast<std::uint32_t>(d.num_vertices());
  CHECK_THROWS_AS(build_view_html(bad_id, "x"), Error);
  ViewData bad_field = d;
  bad_field.fields[0].values.pop_back();
  CHECK_THROWS_AS(build_view_html(bad_field, "x"), Error);
  ViewData bad_target = d;
  bad_target.target_xyz.resize(3);
  CHECK_THROWS_AS(build_view_html(bad_target, "x"), Error);
  ViewData mesh_with_target = d;
  mesh_with_target.mode = ViewMode::Mesh;
  CHECK_THROWS_AS(build_view_html(mesh_with_target, "x"), Error);
}

TEST_CASE("write_view_html writes the page atomically") {
  const auto dir = std::filesystem::temp_directory_path() / "volmap_test_view";
  std::filesystem::create_directories(dir);
  const auto path = (dir / "synthetic.html").string();
  write_view_html(path, synthetic_view(2), "console.log(1);");
  const std::string html = view_test::read_all(path);
  CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
  CHECK(html.find("console.log(1);") != std::string::npos);
  CHECK_THROWS_AS(write_view_html((dir / "missing-folder" / "x.html").string(), synthetic_view(2), "x"), Error);
  std::filesystem::remove_all(dir);
}
