// volmap-surface-map <cube|tet|pyr|octa|star|sphere|custom> <in.mesh> <out_map.txt> [--domain file]
//                    [--refined out.mesh] [--volmap-precision] [--json]
// Maps the boundary of a genus-0 tet mesh onto a base domain (see <volmap/surface_map.hpp>), checks
// the map exactly and only then writes it (%.17g, sorted by vid) and, when edges were split, the
// refined tet mesh the map refers to (default name: <out_map without extension>_in.mesh).
// --volmap-precision writes VOLMAP's 6 decimals instead; the rounded map is read back from disk and
// checked exactly again (same check, tolerance for 6-decimal points) and refused (exit 1, nothing
// written) when rounding breaks it.
// Exit 0 = map written; 1 = mapping or verification failed (nothing written); 2 = bad input.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/surface/domain.hpp>
#include <volmap/io/io.hpp>
#include <volmap/surface/surface_map.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"Map the boundary of a tet mesh onto a base domain; the map is verified exactly before it "
               "is written.",
               "volmap-surface-map"};
  std::string domain_name, mesh_path, map_path, domain_file, refined_path;
  bool json = false, volmap_precision = false;
  app.add_option("domain", domain_name, "cube, tet, pyr, octa, star, sphere or custom (with --domain)")->required();
  app.add_option("mesh", mesh_path, "input tet mesh (.mesh/.vtk/.vtu/.msh/.ovm, VOLMAP-positive)")->required();
  app.add_option("map", map_path, "output boundary map")->required();
  app.add_option("--domain", domain_file, "custom domain file (n / nm / a lines)");
  app.add_option("--refined", refined_path, "where to write the refined tet mesh when edges are split");
  app.add_flag("--volmap-precision", volmap_precision,
               "write 6 decimals like VOLMAP's maps (re-checked exactly on the rounded numbers)");
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    const bool sphere = domain_name == "sphere" || domain_name == "SPHERE";
    volmap::Domain domain;
    if (domain_name == "custom" || domain_name == "CUSTOM") {
      if (domain_file.empty())
        throw volmap::Error(volmap::ErrorKind::BadInput, "", 0, "custom domain needs --domain <file>");
      domain = volmap::read_custom_domain(domain_file);
    } else if (sphere) {
      domain = volmap::builtin_domain("cube");  // star-shaped source map, projected afterwards
    } else {
      domain = volmap::builtin_domain(domain_name);
    }
    volmap_tools::InputMeshes inputs("volmap-surface-map", &json);
    const volmap::TetMeshData mesh = inputs.read(mesh_path);
    volmap::SurfaceMapResult r =
        volmap_tools::naming_file(mesh_path, [&] { return volmap::map_surface_to_domain(mesh, domain); });
    if (sphere)
      r = volmap::project_to_sphere(r, {volmap::kSphereCentre[0], volmap::kSphereCentre[1], volmap::kSphereCentre[2]},
                                    volmap::kSphereRadius);
    if (volmap_precision) {
      // Write the rounded map beside the output, read it back and check exactly what was written.
      const std::string tmp = map_path + ".volmap6.tmp";
      volmap::write_boundary_map(tmp, r.map, volmap::MapPrecision::Volmap6);
      volmap::SurfaceMapCheckResult c;
      try {
        const volmap::BoundaryMap written = volmap::read_boundary_map(tmp);
        volmap::SurfaceMapCheckOptions opt;
        if (sphere) {  // the same criterion as volmap-surface-map-check --domain sphere
          opt.sphere_centre = {volmap::kSphereCentre[0], volmap::kSphereCentre[1], volmap::kSphereCentre[2]};
          opt.sphere_radius = volmap::kSphereRadius;
        }
        c = volmap::check_surface_map(r.mesh, written, sphere ? nullptr : &domain, opt);
      } catch (...) {
        std::remove(tmp.c_str());
        throw;
      }
      if (!c.ok) {
        std::remove(tmp.c_str());
        throw volmap::Error(volmap::ErrorKind::Failed, map_path, 0,
                            "the map rounded to 6 decimals fails the exact check: " + c.reason);
      }
      r.check = c;
      if (std::rename(tmp.c_str(), map_path.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw volmap::Error(volmap::ErrorKind::Io, map_path, 0, "cannot rename the checked map into place");
      }
    }
    std::string refined_out;
    if (r.added_vertices > 0) {
      refined_out = refined_path;
      if (refined_out.empty()) {
        const auto dot = map_path.rfind('.');
        const auto slash = map_path.rfind('/');
        refined_out = (dot != std::string::npos && (slash == std::string::npos || dot > slash) ? map_path.substr(0, dot)
                                                                                                : map_path) +
                      "_in.mesh";
      }
      volmap::write_medit(refined_out, r.mesh);
    }
    if (!volmap_precision) volmap::write_boundary_map(map_path, r.map, volmap::MapPrecision::Full);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (json) {
      nlohmann::json j{{"ok", true},
                       {"exit_code", 0},
                       {"domain", sphere ? std::string("sphere") : domain.name},
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
      std::cout << j.dump() << "\n";
    } else {
      std::cout << "domain " << (sphere ? "sphere" : domain.name) << ": " << r.map.size() << " boundary vertices, +"
                << r.added_vertices << " vertices, exact check " << r.check.positive << "/" << r.check.boundary_triangles
                << " positive; wrote " << map_path << (refined_out.empty() ? "" : " and " + refined_out) << " ("
                << seconds << " s)\n";
    }
    return volmap_tools::kExitOk;
  }, &json);
}
