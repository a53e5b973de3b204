// The mapper on the Expansion Cones inputs (OpenVolumeMesh .ovm + *_boundary.txt, star-shaped
// targets): volmap-map refuses the .ovm as read (opposite orientation convention, said in words),
// volmap-tetmesh-check --fix flips it, and volmap-map then certifies the map (refinement allowed);
// volmap-map-check re-certifies the written pair independently with the boundary map.
// thingi10k_81152 (random star) is left out: the mapper does not certify it within its default
// time limit yet (1,962 non-positive tets after 60 s; see the formats branch report).
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "vmap_test_util.hpp"

#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using vmap_test::quote;
using vmap_test::run;

TEST_CASE("volmap-map certifies maps of the Expansion Cones .ovm inputs onto their boundary maps") {
  struct Case {
    const char* mesh;
    const char* map;
    const char* tets;  // as the orientation sentence writes the count
  };
  const Case cases[] = {{"prism_domain", "prism_ball_boundary", "619"},
                        {"notch_domain", "notch_stiff_tet_boundary", "1,850"},
                        {"thingi10k_83715_domain", "thingi10k_83715_tet_boundary", "607"}};
  const std::string check = quote(volmap_test::tool("volmap-tetmesh-check").string());
  const std::string map = quote(volmap_test::tool("volmap-map").string());
  const std::string map_check = quote(volmap_test::tool("volmap-map-check").string());
  const fs::path d = volmap_test::scratch_dir("expansion_cones");
  for (const Case& c : cases) {
    const std::string name = c.mesh;
    CAPTURE(name);
    VOLMAP_REQUIRE_DATA(ovm, std::string("maps/expansion_cones/") + c.mesh + ".ovm");
    VOLMAP_REQUIRE_DATA(boundary, std::string("maps/expansion_cones/") + c.map + ".txt");
    const std::string flipped = (d / (std::string(c.mesh) + ".mesh")).string();
    const std::string out = (d / (std::string(c.mesh) + "_out.mesh")).string();
    const std::string refined = (d / (std::string(c.mesh) + "_refined.mesh")).string();

    // As read, the .ovm is in the opposite convention: refused, and the reason says so.
    auto r = run(map + " " + quote(ovm.string()) + " " + quote(boundary.string()) + " " + quote(out) + " --json");
    CHECK(r.code == 2);
    const auto refused = nlohmann::json::parse(r.out);
    CHECK(refused["error"].get<std::string>().find(std::string("not a valid input tet mesh: all ") + c.tets +
                                                   " tets are in the opposite orientation convention") != std::string::npos);

    REQUIRE(run(check + " " + quote(ovm.string()) + " --fix " + quote(flipped)).code == 0);
    r = run(map + " " + quote(flipped) + " " + quote(boundary.string()) + " " + quote(out) + " --refined-input " +
            quote(refined) + " --json");
    CHECK(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["certified"] == true);
    CHECK(j["negative"] == 0);
    CHECK(j["zero"] == 0);
    CHECK(j["boundary_exact"] == true);
    MESSAGE(name << ": certified by " << j["certified_by"] << " in " << j["seconds"] << " s, " << j["output_tets"]
                   << " tets (input " << std::string(c.tets) << ")");
    const std::string source = j["refined"] == true ? refined : flipped;
    CHECK(run(map_check + " " + quote(source) + " " + quote(out) + " --absolute --boundary " + quote(boundary.string())).code == 0);
  }
}
