// volmap-surface-map <cube|tet|pyr|octa|star|sphere|custom|polycube> <in.mesh> <out_map.txt>
//                    [--domain file] [--cells <cells file|cross7|L3>] [--cell-size S]
//                    [--refined out.mesh] [--volmap-precision] [--reference-splits]
//                    [--reference-placement] [--json]
// `polycube:<cells>` is the same as `polycube --cells <cells>` (<volmap/surface/polycube.hpp>).
// Maps the boundary of a genus-0 tet mesh (a valid VOLMAP input: input_mesh.hpp) onto a base domain
// (see <volmap/surface/surface_map.hpp>), checks the map exactly and only then writes it (shortest
// round-trip doubles, sorted by vid) and, when edges were split, the refined tet mesh the map refers
// to (default name: <out_map without extension>_in.mesh; format by extension), both together.
// --volmap-precision writes VOLMAP's 6 decimals instead; the rounded map is read back from the
// written file and checked exactly again (same check, tolerance for 6-decimal points) and refused
// (exit 1, nothing written) when rounding breaks it.
// Exit 0 = map written; 1 = mapping or verification failed (nothing written); 2 = bad input.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/surface/domain.hpp>
#include <volmap/surface/polycube.hpp>
#include <volmap/io/io.hpp>
#include <volmap/surface/surface_map.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"Map the boundary of a tet mesh onto a base domain; the map is verified exactly before it "
               "is written.",
               "volmap-surface-map"};
  std::string domain_name, mesh_path, map_path, domain_file, refined_path, cells;
  double cell_size = volmap::kDefaultPolycubeCellSize;
  bool json = false, volmap_precision = false, reference_splits = false, reference_placement = false;
  app.add_option("domain", domain_name,
                 "cube, tet, pyr, octa, star, sphere, custom (with --domain) or polycube (with --cells; or "
                 "polycube:<cells>)")
      ->required();
  app.add_option("mesh", mesh_path, "input tet mesh (.mesh/.vtk/.vtu/.msh/.ovm, a valid VOLMAP input)")->required();
  app.add_option("map", map_path, "output boundary map")->required();
  app.add_option("--domain", domain_file, "custom domain file (n / nm / a lines)");
  app.add_option("--cells", cells, "polycube cells: a file of 'i j k' lines, or cross7 / L3");
  app.add_option("--cell-size", cell_size, "polycube cell edge length (default 100)")->check(volmap_tools::finite_positive());
  app.add_option("--refined", refined_path,
                 "where to write the refined tet mesh (.mesh/.vtk/.vtu/.msh) when edges are split (default "
                 "<map without extension>_in.mesh)");
  app.add_flag("--volmap-precision", volmap_precision,
               "write 6 decimals like VOLMAP's maps (re-checked exactly on the rounded numbers)");
  app.add_flag("--reference-splits", reference_splits,
               "split chords by VOLMAP's reference rule only (every edge joining two arc vertices, after each "
               "arc; its split counts). Default: split only the chords that block an arc or whose ends lie on "
               "one straight side of the domain; the reference rule runs too and the map whose mesh has "
               "fewer tets is kept");
  app.add_flag("--reference-placement", reference_placement,
               "place the nodes by the reference's probes only. Default: when the splits add more than 1 % "
               "to the tets, the map is searched again with the probes turned by each of the 23 other "
               "rotations of the bounding box, then, while it still adds more than 1 %, with the probes "
               "pulled towards the box centre (90 % of their offset down to 10 %) and rotated; the map "
               "whose mesh has the fewest tets is kept");
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    const bool sphere = domain_name == "sphere" || domain_name == "SPHERE";
    if (domain_name.rfind(volmap::kPolycubePrefix, 0) == 0) {
      if (!cells.empty()) throw volmap::Error(volmap::ErrorKind::BadInput, "give the polycube cells once");
      cells = domain_name.substr(volmap::kPolycubePrefix.size());
      domain_name = "polycube";
    }
    const bool polycube = domain_name == "polycube";
    if (!cells.empty() && !polycube) throw volmap::Error(volmap::ErrorKind::BadInput, "--cells is for the polycube domain");
    if (polycube && cells.empty())
      throw volmap::Error(volmap::ErrorKind::BadInput, "polycube domain needs --cells <file|cross7|L3>");
    const bool custom = domain_name == "custom" || domain_name == "CUSTOM";
    if (custom && domain_file.empty())
      throw volmap::Error(volmap::ErrorKind::BadInput, "custom domain needs --domain <file>");
    if (!custom && !domain_file.empty())
      throw volmap::Error(volmap::ErrorKind::BadInput, domain_file, 0, "--domain is for the custom domain only (got '" + domain_name + "')");
    const volmap::Domain domain = polycube ? volmap::polycube_domain(cells, cell_size)
                                  : custom ? volmap::parse_custom_domain(volmap::read_text_file(domain_file, 1 << 16), domain_file)
                                  : sphere ? volmap::builtin_domain("cube")  // unused: map_surface_to_sphere makes its own cube map
                                           : volmap::builtin_domain(domain_name);
    // The refined mesh exists only when the mapper splits edges, but its path is prepared (and
    // checked) now like every output, and dropped when nothing was split.
    std::string refined_out = refined_path;
    if (refined_out.empty()) {
      const auto dot = map_path.rfind('.');
      const auto slash = map_path.rfind('/');
      refined_out = (dot != std::string::npos && (slash == std::string::npos || dot > slash) ? map_path.substr(0, dot) : map_path) +
                    "_in.mesh";
    }
    volmap_tools::RunFiles files;
    volmap_tools::InputMeshes inputs("volmap-surface-map", &json);
    volmap::require_tet_mesh_extension(mesh_path);
    files.input(mesh_path, "input mesh");
    files.input(domain_file, "--domain file");
    if (polycube && cells != "cross7" && cells != "L3") files.input(cells, "--cells file");
    volmap::AtomicOutput& map_out = files.output(map_path, "output map");
    volmap::AtomicOutput& refined = files.tet_mesh_output(refined_out, "refined mesh");

    const volmap::TetMeshData mesh = volmap_tools::read_input_tet_mesh(inputs, mesh_path);
    volmap::SurfaceMapOptions options;
    options.reference_chord_splits = reference_splits;
    options.search_placements = !reference_placement;
    volmap::SurfaceMapResult r = volmap_tools::naming_file(mesh_path, [&] {
      if (sphere)
        return volmap::map_surface_to_sphere(
            mesh, {volmap::kSphereCentre[0], volmap::kSphereCentre[1], volmap::kSphereCentre[2]}, volmap::kSphereRadius, options);
      return volmap::map_surface_to_domain(mesh, domain, options);
    });
    if (volmap_precision) {
      // Write the rounded map, read the written file back and check exactly what was written.
      volmap::write_boundary_map(map_out, r.map, volmap::MapPrecision::Volmap6);
      map_out.finish();
      const volmap::BoundaryMap written = volmap::read_boundary_map(map_out.temporary_path());
      volmap::SurfaceMapCheckOptions opt;
      if (sphere) {
        // the same criterion as volmap-surface-map-check --domain sphere
        opt.sphere_centre = {volmap::kSphereCentre[0], volmap::kSphereCentre[1], volmap::kSphereCentre[2]};
        opt.sphere_radius = volmap::kSphereRadius;
      }
      const volmap::SurfaceMapCheckResult c = volmap::check_surface_map(r.mesh, written, sphere ? nullptr : &domain, opt);
      if (!c.ok)
        throw volmap::Error(volmap::ErrorKind::Failed, map_path, 0,
                            "the map rounded to 6 decimals fails the exact check: " + c.reason);
      r.check = c;
    } else {
      volmap::write_boundary_map(map_out, r.map, volmap::MapPrecision::Full);
    }
    if (r.added_vertices > 0)
      volmap::write_tet_mesh(refined, r.mesh);
    else
      refined.drop(), refined_out.clear();
    files.commit();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (json) {
      nlohmann::json j{{"domain", sphere ? std::string("sphere") : domain.name},
                       {"map", map_path},
                       {"refined_mesh", refined_out.empty() ? nlohmann::json(nullptr) : nlohmann::json(refined_out)},
                       {"input_vertices", mesh.num_vertices()},
                       {"added_vertices", r.added_vertices},
                       {"tets", r.mesh.num_tets()},
                       {"boundary_vertices", r.map.size()},
                       {"node_vertices", r.node_vertices},
                       {"collided_nodes", r.collided_nodes},
                       {"attempt", r.attempt},
                       {"failed_attempts", r.failed_attempts},
                       {"check_positive", r.check.positive},
                       {"check_triangles", r.check.boundary_triangles},
                       {"precision", volmap_precision ? "volmap6" : "full"},
                       {"seconds", seconds}};
      if (!inputs.empty()) j["input_notes"] = inputs.json();
      return volmap_tools::print_json(std::move(j), volmap_tools::kExitOk);
    }
    std::cout << "domain " << (sphere ? "sphere" : domain.name) << ": " << r.map.size() << " boundary vertices, +"
              << r.added_vertices << " vertices, exact check " << r.check.positive << "/" << r.check.boundary_triangles
              << " positive; wrote " << map_path << (refined_out.empty() ? "" : " and " + refined_out) << " ("
              << seconds << " s)\n";
    return volmap_tools::kExitOk;
  }, &json);
}
