// volmap-tetrahedralize <surface.{obj,off,stl,ply}> <out.{mesh,vtk,vtu,msh}> [--quality 1.414 | --coarse]
//                       [--max-volume V] [--json]
// Checks the surface (closed, manifold, one component, genus 0, no self-intersections, extent within
// what TetGen's arithmetic handles), tetrahedralizes it with TetGen (p q<quality> Y, boundary
// preserved; --coarse: p Y, no quality refinement), checks the result is a valid VOLMAP input
// (input_mesh.hpp) and writes it in the format of out's extension.
// Exit 0 = written; 1 = surface refused (topology) or TetGen failed (self-intersections, ...); 2 = usage/IO.
#include "support/tool_common.hpp"

#include <volmap/io/io.hpp>
#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

namespace {

// TetGen works with squared lengths and fixed relative tolerances: coordinates whose bounding box is
// smaller than 1e-100 or larger than 1e100 underflow or overflow there (the exact checks above do
// not mind). Throws Error(Unsupported) naming `path`.
void require_tetgen_scale(const volmap::TriangleSurface& s, const std::string& path) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t v = 0; v < s.num_vertices(); ++v)
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], s.xyz[3 * v + c]), hi[c] = std::max(hi[c], s.xyz[3 * v + c]);
  double extent = 0, magnitude = 0;
  for (int c = 0; c < 3; ++c) {
    extent = std::max(extent, hi[c] - lo[c]);
    magnitude = std::max({magnitude, std::abs(lo[c]), std::abs(hi[c])});
  }
  if (!(extent >= 1e-100) || !(magnitude <= 1e100)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "the surface spans %.3g with coordinates up to %.3g: TetGen needs extents in [1e-100, 1e100] "
                  "(it squares lengths); rescale the surface", extent, magnitude);
    throw volmap::Error(volmap::ErrorKind::Unsupported, path, 0, buf);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Tetrahedralize a closed genus-0 surface with TetGen into a VOLMAP-positive tet mesh",
               "volmap-tetrahedralize"};
  std::string in_path, out_path;
  volmap::TetrahedralizeOptions opt;
  bool json = false;
  app.add_option("surface", in_path, "input surface (.obj, .off, .stl ASCII/binary, .ply ASCII/binary)")->required();
  app.add_option("out", out_path, "output tet mesh (.mesh, .vtk, .vtu or .msh by extension)")->required();
  app.add_option("--quality", opt.quality, "radius-edge ratio bound (TetGen q), default 1.414, at least 1")
      ->check(volmap_tools::finite_range(1.0, 1e300));
  app.add_option("--max-volume", opt.max_volume, "maximum tet volume (TetGen a), default none (0)")
      ->check(volmap_tools::finite_non_negative());
  app.add_flag("--coarse", opt.coarse, "no quality refinement (TetGen without q): few tets, most touching the boundary")
      ->excludes("--quality");
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    volmap_tools::RunFiles files;
    files.input(in_path, "input surface");
    volmap::AtomicOutput& out = files.tet_mesh_output(out_path, "output mesh");
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
    require_tetgen_scale(s, in_path);
    const volmap::TetMeshData m = volmap_tools::naming_file(in_path, [&] { return volmap::tetrahedralize_surface(s, opt); });
    // What is written must be a valid VOLMAP input (what volmap-tetmesh-check accepts).
    const volmap::InputMeshVerdict verdict = volmap::judge_input_mesh(m);
    if (!verdict.valid)
      throw volmap::Error(volmap::ErrorKind::Failed, in_path, 0,
                          "TetGen's mesh of this surface is not a valid VOLMAP input: " + verdict.reason());
    volmap::write_tet_mesh(out, m);
    files.commit();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (json) {
      return volmap_tools::print_json({{"surface_vertices", s.num_vertices()}, {"surface_triangles", s.num_triangles()},
                                       {"vertices", m.num_vertices()}, {"tets", m.num_tets()}, {"output", out_path},
                                       {"seconds", seconds}},
                                      volmap_tools::kExitOk);
    }
    std::cout << in_path << ": " << s.num_vertices() << " vertices, " << s.num_triangles() << " triangles -> "
              << m.num_vertices() << " vertices, " << m.num_tets() << " tets (" << seconds << " s), wrote "
              << out_path << "\n";
    return volmap_tools::kExitOk;
  }, &json);
}
