// The user's pipeline on a generated thin-feature shape, through the real executables:
// volmap-shapes --thin → volmap-tetrahedralize --coarse → volmap-surface-map → volmap-map. The coarse
// thin calibration cube onto the star: B0 alone needs +13 % tets, so B1's 5 % budget leaves room for
// no patch and one tet stays inverted; the budget grows (max_growth_last_resort) and the map
// certifies. With the escalation switched off the same case is not certified (exit 1), and nothing
// claims otherwise: the independent volmap-map-check agrees with each verdict.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "vmap_test_util.hpp"

#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using vmap_test::quote;
using vmap_test::run;

namespace {
std::string tool(const char* name) { return quote(volmap_test::tool(name).string()); }
}  // namespace

TEST_CASE("coarse thin calibration cube onto the star: from Tutte 3D certified only because B1's growth budget may grow") {
  if (!fs::exists(volmap_test::tool("volmap-tetrahedralize"))) {
    MESSAGE("skipped: volmap-tetrahedralize is not built (needs TetGen)");
    return;
  }
  const fs::path d = volmap_test::scratch_dir("thin_pipeline");
  REQUIRE(run(tool("volmap-shapes") + " " + quote((d / "shapes").string()) + " --thin --format off > /dev/null").code == 0);
  const std::string mesh = (d / "cc.mesh").string(), map = (d / "cc_star.txt").string(), in = (d / "cc_star_in.mesh").string();
  REQUIRE(run(tool("volmap-tetrahedralize") + " " + quote((d / "shapes" / "calibration_cube_thin.off").string()) + " " +
              quote(mesh) + " --coarse > /dev/null")
              .code == 0);
  REQUIRE(run(tool("volmap-surface-map") + " star " + quote(mesh) + " " + quote(map) + " --refined " + quote(in) + " > /dev/null")
              .code == 0);
  const std::string source = fs::exists(in) ? in : mesh;

  auto map_case = [&](const std::string& tag, double time_limit, const std::string& options) {
    const std::string out = (d / (tag + "_out.mesh")).string(), refined = (d / (tag + "_refined.mesh")).string();
    const auto r = run(tool("volmap-map") + " " + quote(source) + " " + quote(map) + " " + quote(out) + " --refined-input " +
                       quote(refined) + " --threads 1 --time-limit " + std::to_string(time_limit) + " --json " + options);
    const auto j = nlohmann::json::parse(r.out);
    const int check = fs::exists(out) ? run(tool("volmap-map-check") + " " + quote(refined) + " " + quote(out) + " > /dev/null").code : 1;
    return std::make_tuple(r.code, j, check);
  };

  // From Tutte 3D the patches that finish the map need the larger budget. The radial start (the
  // default here: the star is not convex) leaves a map that certifies within the 5 % budget.
  const auto [code_radial, j_radial, check_radial] = map_case("radial", 60, "--max-growth-last-resort 0.05");
  CHECK(code_radial == 0);
  CHECK(check_radial == 0);
  CHECK(j_radial["growth_budget_escalations"] == 0);

  const auto [code, j, check] = map_case("escalated", 60, "--start tutte");
  CHECK(code == 0);
  CHECK(j["certified"] == true);
  CHECK(check == 0);
  CHECK(j["growth_budget_escalations"].get<int>() >= 1);
  CHECK(j["growth"].get<double>() <= 0.5);

  // Fails whatever the time it is given: a short limit keeps the test short.
  const auto [code_off, j_off, check_off] = map_case("capped", 5, "--start tutte --max-growth-last-resort 0.05");
  CHECK(code_off == 1);
  CHECK(j_off["certified"] == false);
  CHECK(j_off["growth_budget_escalations"] == 0);
  CHECK(check_off != 0);
}
