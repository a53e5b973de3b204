// volmap-tetrahedralize <surface.{obj,off,stl,ply}> <out.mesh> [--quality 1.414 | --coarse] [--max-volume V] [--json]
// Checks the surface (closed, manifold, one component, genus 0, no self-intersections), tetrahedralizes it with TetGen
// (p q<quality> Y, boundary preserved; --coarse: p Y, no quality refinement) and writes a VOLMAP-positive Medit mesh.
// Exit 0 = written; 1 = surface refused (topology) or TetGen failed (self-intersections, ...); 2 = usage/IO.
#include "support/tool_common.hpp"

#include <volmap/io/io.hpp>
#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>

#include <chrono>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"Tetrahedralize a closed genus-0 surface with TetGen into a VOLMAP-positive .mesh",
               "volmap-tetrahedralize"};
  std::string in_path, out_path;
  volmap::TetrahedralizeOptions opt;
  bool json = false;
  app.add_option("surface", in_path, "input surface (.obj, .off, .stl ASCII/binary, .ply ASCII/binary)")->required();
  app.add_option("out", out_path, "output Medit .mesh")->required();
  app.add_option("--quality", opt.quality, "radius-edge ratio bound (TetGen q), default 1.414");
  app.add_option("--max-volume", opt.max_volume, "maximum tet volume (TetGen a), default none");
  app.add_flag("--coarse", opt.coarse, "no quality refinement (TetGen without q): few tets, most touching the boundary")
      ->excludes("--quality");
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    const volmap::TriangleSurface s = volmap::read_triangle_surface(in_path);
    const std::string problem = volmap::surface_topology_problem(s);
    if (!problem.empty()) throw volmap::Error(volmap::ErrorKind::Failed, in_path, 0, "surface refused: " + problem);
    // The full surface check (exact self-intersections) of tetmesh_checks before TetGen sees it.
    const volmap::SurfaceCheckReport report = volmap::check_triangle_surface(s.xyz, s.tris);
    if (!report.all_passed()) {
      std::string why;
      for (const auto& c : report.checks)
        if (!c.passed) why += (why.empty() ? "" : "; ") + c.key + ": " + c.detail;
      throw volmap::Error(volmap::ErrorKind::Failed, in_path, 0, "surface refused: " + why);
    }
    const volmap::TetMeshData m = volmap::tetrahedralize_surface(s, opt);
    volmap::write_medit(out_path, m);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (json) {
      std::cout << nlohmann::json{{"ok", true}, {"exit_code", 0}, {"surface_vertices", s.num_vertices()},
                                  {"surface_triangles", s.num_triangles()}, {"vertices", m.num_vertices()},
                                  {"tets", m.num_tets()}, {"output", out_path}, {"seconds", seconds}}
                       .dump()
                << "\n";
    } else {
      std::cout << in_path << ": " << s.num_vertices() << " vertices, " << s.num_triangles() << " triangles -> "
                << m.num_vertices() << " vertices, " << m.num_tets() << " tets (" << seconds << " s), wrote "
                << out_path << "\n";
    }
    return volmap_tools::kExitOk;
  }, &json);
}
