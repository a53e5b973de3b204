// Polycube domains through the tools: G1 bone and duck mapped onto cross7 and L3 by
// volmap-surface-map, the maps re-checked by volmap-surface-map-check --domain polycube:<cells>, the
// volume maps certified by volmap-map and re-certified independently by volmap-map-check; a U of 5
// cells refused with exit 2 and a one-line reason naming the file and a cell; volmap-dataset
// publishing sphere and polycube maps (suffix pc) of a generated mesh, re-checked here, and with
// --mesh-per-domain each domain's own split mesh beside its map, which volmap-run then maps.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <volmap/io/io.hpp>
#include <volmap/testing/generate.hpp>

#include "test_support.hpp"
#include "vmap_test_util.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using vmap_test::quote;
using vmap_test::run;

namespace {

std::string tool(const char* name) { return quote(volmap_test::tool(name).string()); }

// The stderr of a command (stdout dropped), and its exit code.
vmap_test::RunResult run_stderr(const std::string& command) { return run("(" + command + " 2>&1 >/dev/null)"); }

}  // namespace

TEST_CASE("volmap-surface-map and volmap-map: G1 bone and duck onto cross7 and L3, certified") {
  VOLMAP_REQUIRE_DATA(bone, "volmap/G1/bone.mesh");
  VOLMAP_REQUIRE_DATA(duck, "volmap/G1/duck.mesh");
  const fs::path d = volmap_test::scratch_dir("polycube_g1");
  for (const auto& [name, path] : {std::pair<std::string, fs::path>{"bone", bone}, {"duck", duck}})
    for (const std::string cells : {"cross7", "L3"}) {
      const std::string id = name + "_" + cells;
      CAPTURE(id);
      const std::string map = (d / (id + ".txt")).string(), in = (d / (id + "_in.mesh")).string();
      const std::string out = (d / (id + "_out.mesh")).string(), refined = (d / (id + "_refined.mesh")).string();
      // Both spellings of the domain: polycube --cells X and polycube:X.
      const std::string domain = cells == "L3" ? "polycube --cells L3" : "polycube:" + cells;
      auto r = run(tool("volmap-surface-map") + " " + domain + " " + quote(path.string()) + " " + quote(map) +
                   " --refined " + quote(in) + " --json");
      REQUIRE(r.code == 0);
      const auto sm = nlohmann::json::parse(r.out);
      CHECK(sm["domain"] == "polycube");
      CHECK(sm["check_positive"] == sm["check_triangles"]);
      const std::string source = sm["added_vertices"].get<int>() > 0 ? in : path.string();
      r = run(tool("volmap-surface-map-check") + " " + quote(source) + " " + quote(map) + " --domain polycube:" + cells +
              " --json");
      CHECK(r.code == 0);
      const auto c = nlohmann::json::parse(r.out);
      CHECK(c["negative"] == 0);
      CHECK(c["zero"] == 0);
      CHECK(c["off_domain"] == 0);
      CHECK(c["corners_exact"] == (cells == "L3" ? 16 : 32));
      r = run(tool("volmap-map") + " " + quote(source) + " " + quote(map) + " " + quote(out) + " --refined-input " +
              quote(refined) + " --json");
      CHECK(r.code == 0);
      const auto v = nlohmann::json::parse(r.out);
      CHECK(v["certified"] == true);
      CHECK(v["boundary_exact"] == true);
      MESSAGE(id << ": +" << sm["added_vertices"] << " surface vertices; volume map certified by " << v["certified_by"]
                 << " in " << v["seconds"] << " s");
      const std::string final_source = v["refined"] == true ? refined : source;
      CHECK(run(tool("volmap-map-check") + " " + quote(final_source) + " " + quote(out) + " --absolute --boundary " +
                quote(map))
                .code == 0);
    }
}

TEST_CASE("a polycube that is not star-shaped is refused with exit 2, naming the file and a cell") {
  const fs::path d = volmap_test::scratch_dir("polycube_refused");
  const std::string u5 = volmap_test::write_bytes(d / "u5.txt", "# a U of 5 cells\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n2 1 0\n");
  const std::string mesh = (d / "cube.mesh").string();
  volmap::write_medit(mesh, volmap::generate_kuhn_unit_cube(4));
  const std::string map = (d / "map.txt").string();
  for (const std::string& domain : {"polycube:" + u5, "polycube --cells " + quote(u5)}) {
    CAPTURE(domain);
    const auto r = run_stderr(tool("volmap-surface-map") + " " + domain + " " + quote(mesh) + " " + quote(map));
    CHECK(r.code == 2);
    CHECK(r.out.find(u5) != std::string::npos);
    CHECK(r.out.find("not strictly star-shaped") != std::string::npos);
    CHECK(r.out.find("cell (") != std::string::npos);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
    CHECK(!fs::exists(map));
  }
  CHECK(run(tool("volmap-surface-map") + " polycube " + quote(mesh) + " " + quote(map)).code == 2);  // no cells
  CHECK(run(tool("volmap-surface-map") + " cube " + quote(mesh) + " " + quote(map) + " --cells L3").code == 2);
  CHECK(run(tool("volmap-surface-map-check") + " " + quote(mesh) + " " + quote(map) + " --domain polycube:" + quote(u5))
            .code == 2);
}

TEST_CASE("volmap-dataset adds sphere and polycube maps to a group") {
  if (!fs::exists(volmap_test::tool("volmap-dataset"))) {
    MESSAGE("skipped: volmap-dataset is not built (needs TetGen)");
    return;
  }
  const fs::path d = volmap_test::scratch_dir("polycube_dataset");
  fs::create_directories(d / "in");
  volmap::write_medit((d / "in" / "cube8.mesh").string(), volmap::generate_kuhn_unit_cube(8));
  const fs::path ds = d / "ds";
  auto r = run(tool("volmap-dataset") + " " + quote((d / "in").string()) + " " + quote(ds.string()) +
               " --group G9 --domains cube,sphere,polycube:L3 --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["added"] == 1);
  const std::string mesh = (ds / "G9" / "cube8.mesh").string();
  REQUIRE(fs::exists(mesh));
  // The published cells describe the polycube the map lies on.
  const std::string cells = (ds / "G9_pc" / "cube8_pc_cells.txt").string();
  REQUIRE(fs::exists(cells));
  CHECK(run(tool("volmap-surface-map-check") + " " + quote(mesh) + " " + quote((ds / "G9_pc" / "cube8_pc.txt").string()) +
            " --domain polycube:" + quote(cells))
            .code == 0);
  CHECK(run(tool("volmap-surface-map-check") + " " + quote(mesh) + " " +
            quote((ds / "G9_sphere" / "cube8_sphere.txt").string()) + " --domain sphere")
            .code == 0);
  CHECK(run(tool("volmap-surface-map-check") + " " + quote(mesh) + " " + quote((ds / "G9_cube" / "cube8_cube.txt").string()) +
            " --domain cube")
            .code == 0);
  // A non-star-shaped polycube is bad input before any work is done.
  const std::string u5 = volmap_test::write_bytes(d / "u5.txt", "0 0 0\n1 0 0\n2 0 0\n0 1 0\n2 1 0\n");
  r = run_stderr(tool("volmap-dataset") + " " + quote((d / "in").string()) + " " + quote((d / "ds2").string()) +
                 " --group G9 --domains polycube:" + quote(u5));
  CHECK(r.code == 2);
  CHECK(r.out.find("not strictly star-shaped") != std::string::npos);
  CHECK(run(tool("volmap-dataset") + " " + quote((d / "in").string()) + " " + quote((d / "ds3").string()) +
            " --group G9 --domains polycube:L3,polycube:cross7")
            .code == 2);
}

TEST_CASE("volmap-dataset --mesh-per-domain: each domain's splits stay in its own mesh, which volmap-run maps") {
  if (!fs::exists(volmap_test::tool("volmap-dataset"))) {
    MESSAGE("skipped: volmap-dataset is not built (needs TetGen)");
    return;
  }
  const fs::path d = volmap_test::scratch_dir("dataset_mesh_per_domain");
  fs::create_directories(d / "in");
  const auto cube = volmap::generate_kuhn_unit_cube(6);
  volmap::write_medit((d / "in" / "cube6.mesh").string(), cube);
  const fs::path ds = d / "ds";
  auto r = run(tool("volmap-dataset") + " " + quote((d / "in").string()) + " " + quote(ds.string()) +
               " --group G9 --domains cube,star,polycube:L3 --mesh-per-domain --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  const auto& surface = j["surfaces"][0];
  // The group mesh is the input itself: no domain's splits in it.
  CHECK(volmap::read_tet_mesh((ds / "G9" / "cube6.mesh").string()).num_tets() == cube.num_tets());
  CHECK(surface["tets"] == cube.num_tets());
  std::size_t own_meshes = 0;
  for (const std::string dom : {"cube", "star", "pc"}) {
    CAPTURE(dom);
    const fs::path own = ds / ("G9_" + dom) / ("cube6_" + dom + ".mesh"), map = ds / ("G9_" + dom) / ("cube6_" + dom + ".txt");
    const fs::path mesh = fs::exists(own) ? own : ds / "G9" / "cube6.mesh";
    own_meshes += fs::exists(own);
    const std::size_t tets = volmap::read_tet_mesh(mesh.string()).num_tets();
    CHECK(surface["domain_tets"][dom] == tets);
    CHECK(fs::exists(own) == (tets != cube.num_tets()));  // published only when the map split edges
    const std::string domain_arg = dom == "pc" ? "polycube:" + quote((ds / "G9_pc" / "cube6_pc_cells.txt").string()) : dom;
    CHECK(run(tool("volmap-surface-map-check") + " " + quote(mesh.string()) + " " + quote(map.string()) + " --domain " + domain_arg)
              .code == 0);
    // volmap-run takes the case's own mesh (the input tets it reports are that mesh's).
    const fs::path out = d / ("run_" + dom);
    REQUIRE(run(tool("volmap-run") + " " + quote(ds.string()) + " --method tutte3d --domains " + dom + " --out " + quote(out.string()) +
                " > /dev/null 2>&1")
                .code <= 1);
    std::ifstream results(out / "results.jsonl");
    std::string line;
    REQUIRE(std::getline(results, line));
    CHECK(nlohmann::json::parse(line)["tets_in"] == tets);
  }
  CHECK(own_meshes >= 1);  // the L3 polycube and the star need boundary splits on this grid
}

TEST_CASE("volmap-polycube-cells: a generated L-shaped mesh gives its 12 cells, mapped by volmap-surface-map") {
  const fs::path d = volmap_test::scratch_dir("polycube_cells");
  // 4 x 4 x 1 unit cubes without the block x, y in [2, 4]: an L of 12 cells (star-shaped).
  const auto mesh = volmap::generate_kuhn_grid(4, 4, 1, [](std::size_t i, std::size_t j, std::size_t) { return i < 2 || j < 2; });
  const std::string mesh_path = (d / "L.mesh").string(), cells = (d / "L_cells.txt").string();
  volmap::write_tet_mesh(mesh_path, mesh);
  auto r = run(tool("volmap-polycube-cells") + " " + quote(mesh_path) + " " + quote(cells) + " --resolution 4 --json");
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["cells"] == 12);
  CHECK(j["ok"] == true);
  // The cells file is a valid polycube domain for the surface mapper.
  r = run(tool("volmap-surface-map") + " polycube --cells " + quote(cells) + " " + quote(mesh_path) + " " +
          quote((d / "L_map.txt").string()) + " --refined " + quote((d / "L_in.mesh").string()) + " --json");
  CHECK(r.code == 0);
  // Bad resolution: exit 2, nothing written; the output may not be the input.
  const std::string other = (d / "other.txt").string();
  CHECK(run_stderr(tool("volmap-polycube-cells") + " " + quote(mesh_path) + " " + quote(other) + " --resolution 0").code == 2);
  CHECK_FALSE(fs::exists(other));
  CHECK(run_stderr(tool("volmap-polycube-cells") + " " + quote(mesh_path) + " " + quote(mesh_path)).code == 2);
}
