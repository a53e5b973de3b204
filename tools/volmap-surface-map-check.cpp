// volmap-surface-map-check <in.mesh> <map.txt> [--domain name|polycube:<cells>|file] [--cell-size S] [--json]
// The exact surface-map sanity check (see <volmap/surface/surface_map_check.hpp>) of a valid VOLMAP
// input mesh (input_mesh.hpp; else exit 2 naming it). Exit 0 = valid,
// 1 = check failed (inverted/degenerate cones, coverage, off-domain points, corners), 2 = bad input.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/surface/domain.hpp>
#include <volmap/surface/polycube.hpp>
#include <volmap/io/io.hpp>
#include <volmap/surface/surface_map.hpp>
#include <volmap/surface/surface_map_check.hpp>

#include <chrono>
#include <iostream>
#include <optional>

int main(int argc, char** argv) {
  CLI::App app{"Exact surface-map check: every boundary triangle's image forms a positive cone with the "
               "kernel point; the map covers each boundary vertex once; optionally lies on a domain.",
               "volmap-surface-map-check"};
  std::string mesh_path, map_path, domain_arg;
  bool json = false, either_sign = false;
  double tolerance = 0, cell_size = volmap::kDefaultPolycubeCellSize;
  app.add_option("mesh", mesh_path, "input tet mesh (.mesh/.vtk/.vtu/.msh/.ovm)")->required();
  app.add_option("map", map_path, "boundary map: one 'vid x y z' line per boundary vertex")->required();
  app.add_option("--domain", domain_arg,
                 "cube|tet|pyr|octa|star|sphere, polycube:<cells file|cross7|L3> or a custom domain file: also "
                 "check that points lie on the domain and corners hit their targets exactly");
  app.add_option("--cell-size", cell_size, "polycube cell edge length (default 100)")->check(volmap_tools::finite_positive());
  app.add_option("--tolerance", tolerance, "max distance from the domain boundary (default 0: 1e-9 x domain "
                                           "size, 1e-6 for maps written with 6 decimals)")
      ->check(volmap_tools::finite_non_negative());
  app.add_flag("--accept-either-sign", either_sign, "accept all-negative cones too (VOLMAP's behaviour)");
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<volmap::Domain> domain;
    const bool sphere = domain_arg == "sphere" || domain_arg == "SPHERE";
    if (domain_arg.rfind(volmap::kPolycubePrefix, 0) == 0)
      domain = volmap::polycube_domain(domain_arg.substr(volmap::kPolycubePrefix.size()), cell_size);
    else if (!domain_arg.empty() && !sphere)
      domain = volmap_tools::domain_from_name_or_file(domain_arg);
    volmap_tools::InputMeshes inputs("volmap-surface-map-check", &json);
    const volmap::TetMeshData mesh = volmap_tools::read_input_tet_mesh(inputs, mesh_path);
    const volmap::BoundaryMap map = volmap::read_boundary_map(map_path);
    volmap::SurfaceMapCheckOptions opt;
    opt.position_tolerance = tolerance;
    opt.accept_either_sign = either_sign;
    if (sphere) {  // the sphere of volmap-surface-map (centre (50,50,50), radius 50); kernel = centroid
      opt.sphere_centre = {volmap::kSphereCentre[0], volmap::kSphereCentre[1], volmap::kSphereCentre[2]};
      opt.sphere_radius = volmap::kSphereRadius;
    }
    const auto r = volmap_tools::naming_file(
        map_path, [&] { return volmap::check_surface_map(mesh, map, domain ? &*domain : nullptr, opt); });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const int code = r.ok ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed;
    if (json) {
      nlohmann::json j{{"boundary_vertices", r.boundary_vertices},
                       {"boundary_triangles", r.boundary_triangles},
                       {"map_entries", r.map_entries},
                       {"missing", r.missing},
                       {"not_boundary", r.not_boundary},
                       {"duplicates", r.duplicates},
                       {"positive", r.positive},
                       {"zero", r.zero},
                       {"negative", r.negative},
                       {"kernel", {r.kernel[0], r.kernel[1], r.kernel[2]}},
                       {"seconds", seconds}};
      if (r.domain_checked) {
        j["domain"] = sphere ? std::string("sphere") : domain->name;
        j["off_domain"] = r.off_domain;
        j["max_domain_distance"] = r.max_domain_distance;
        j["tolerance"] = r.tolerance;
        j["corners_expected"] = r.corners_expected;
        j["corners_exact"] = r.corners_exact;
      }
      if (!r.ok) j["reason"] = r.reason;
      if (!inputs.empty()) j["input_notes"] = inputs.json();
      return volmap_tools::print_json(std::move(j), code);
    } else {
      std::cout << "boundary: " << r.boundary_vertices << " vertices, " << r.boundary_triangles << " triangles; map: "
                << r.map_entries << " entries\n";
      std::cout << "cones: " << r.positive << " positive, " << r.zero << " zero, " << r.negative << " negative\n";
      if (r.domain_checked)
        std::cout << "domain " << (sphere ? std::string("sphere") : domain->name) << ": " << r.off_domain << " points off (max distance "
                  << r.max_domain_distance << ", tolerance " << r.tolerance << "), corners exact "
                  << r.corners_exact << "/" << r.corners_expected << "\n";
      std::cout << (r.ok ? "Check result: SUCCESS" : "Check result: FAIL (" + r.reason + ")") << "\n";
    }
    if (!r.ok) std::cerr << "volmap-surface-map-check: " << map_path << ": " << r.reason << "\n";
    return code;
  }, &json);
}
