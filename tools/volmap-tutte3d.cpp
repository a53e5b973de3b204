// volmap-tutte3d — the Tutte 3D baseline (mapping.md §2) under VOLMAP's candidate-method contract:
//   volmap-tutte3d <in.mesh> <map.txt> <out.mesh> [--weights uniform] [--json]
// Refuses an input that is not a valid VOLMAP input mesh (input_mesh.hpp) and a map that does not
// match its boundary, solves the uniform Laplacian with the boundary fixed, writes the map atomically
// in the format of out's extension (.mesh/.vtk/.vtu/.msh; even when it inverts tets), then reads the
// written file back and certifies it with check_map (orient3d > 0 for every tet in the input's vertex
// order, boundary vertices bit-identical to the map). Exit 0 iff certified injective, 1 otherwise,
// 2 on bad input.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/io/io.hpp>
#include <volmap/check/map_check.hpp>
#include <volmap/volume/tutte3d.hpp>

#include <chrono>
#include <cstdio>

int main(int argc, char** argv) {
  CLI::App app{"Tutte 3D baseline: uniform Laplacian, boundary fixed by the map; certifies the written map"};
  app.name("volmap-tutte3d");
  std::string in_path, map_path, out_path, weights = "uniform";
  bool json = false;
  app.add_option("in.mesh", in_path, "input tet mesh (.mesh, .vtk, .vtu, .msh or .ovm; a valid VOLMAP input)")->required();
  app.add_option("map.txt", map_path, "boundary map (vid x y z, 0-based)")->required();
  app.add_option("out.mesh", out_path, "output map (.mesh, .vtk, .vtu or .msh by extension; same vertices and tets)")->required();
  app.add_option("--weights", weights, "Laplacian weights (only 'uniform')")->check(CLI::IsMember({"uniform"}));
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    volmap_tools::RunFiles files;
    volmap_tools::InputMeshes inputs("volmap-tutte3d", &json);
    volmap::require_tet_mesh_extension(in_path);
    files.input(in_path, "input mesh");
    files.input(map_path, "boundary map");
    volmap::AtomicOutput& out = files.tet_mesh_output(out_path, "output map");
    const volmap::TetMeshData mesh = volmap_tools::read_input_tet_mesh(inputs, in_path);
    const volmap::BoundaryMap map = volmap::read_boundary_map(map_path);
    volmap::validate_boundary_map(map, mesh, map_path);
    volmap_tools::require_moderate_coordinates(map.xyz, map_path);
    const double read_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

    const volmap::Tutte3dResult result = volmap_tools::naming_file(in_path, [&] { return volmap::tutte3d(mesh, map); });
    volmap::TetMeshData output = mesh;
    output.xyz = result.xyz;
    auto t1 = Clock::now();
    volmap::write_tet_mesh(out, output);
    files.commit();
    const double write_seconds = std::chrono::duration<double>(Clock::now() - t1).count();

    // Certify what is on disk: the written file, read back.
    t1 = Clock::now();
    const volmap::TetMeshData written = volmap::read_tet_mesh(out_path);
    const volmap::MapCheckReport check =
        volmap_tools::naming_file(out_path, [&] { return volmap::check_map(mesh, written, &map); });
    const double check_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
    const bool injective = check.certified();
    const int code = injective ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed;

    if (json) {
      nlohmann::json j;
      if (!inputs.empty()) j["input_notes"] = inputs.json();
      j["injective"] = injective;
      j["certified_on"] = "the written file, read back";
      j["input"] = in_path;
      j["map"] = map_path;
      j["output"] = out_path;
      j["num_vertices"] = mesh.num_vertices();
      j["num_tets"] = mesh.num_tets();
      j["num_edges"] = result.num_edges;
      j["num_free"] = result.num_free;
      j["num_fixed"] = result.num_fixed;
      j["weights"] = weights;
      j["output_positive"] = check.output.positive;
      j["output_zero"] = check.output.zero;
      j["output_negative"] = check.output.negative;
      j["inverted"] = check.output.zero + check.output.negative;
      j["input_positive"] = check.input.positive;
      j["input_non_positive"] = check.num_tets - check.input.positive;
      j["boundary_mismatches"] = check.boundary_mismatches;
      j["first_bad_tets"] = check.first_bad;
      j["seconds"] = {{"read", read_seconds},
                      {"edges", result.timings.edges},
                      {"assembly", result.timings.assembly},
                      {"factorization", result.timings.factorization},
                      {"solve", result.timings.solve},
                      {"write", write_seconds},
                      {"certify", check_seconds}};
      return volmap_tools::print_json(std::move(j), code);
    }
    std::printf("Tutte 3D (uniform): %zu vertices (%zu free, %zu fixed), %zu tets, %zu edges\n",
                mesh.num_vertices(), result.num_free, result.num_fixed, mesh.num_tets(), result.num_edges);
    std::printf("time: edges %.4f s, assembly %.4f s, factorization %.4f s, solve %.4f s\n",
                result.timings.edges, result.timings.assembly, result.timings.factorization,
                result.timings.solve);
    std::printf("written %s; exact check of the written map: %zu positive, %zu zero, %zu negative\n",
                out_path.c_str(), check.output.positive, check.output.zero, check.output.negative);
    if (check.boundary_mismatches) std::printf("boundary mismatches: %zu\n", check.boundary_mismatches);
    std::printf("%s\n", injective ? "injective (certified)" : "NOT injective");
    return code;
  }, &json);
}
