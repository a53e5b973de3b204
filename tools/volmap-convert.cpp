// volmap-convert <in> <out> [--json] [--binary] [--vtu-ascii]
// Converts tet meshes between Medit .mesh, legacy VTK .vtk, VTK XML .vtu and Gmsh .msh (4.1 written;
// 2.2/4.1 read), and reads OpenVolumeMesh .ovm, chosen by extension (case-insensitive), keeping
// vertex order, tet order and each tet's vertex order (so no orientation is changed: the line printed
// says which convention the tets are in); Medit labels are carried along. A format tool: it copies
// any readable mesh, valid or not (volmap-tetmesh-check judges it). What a reader skipped or
// renumbered (Gmsh's lower-dimensional elements, unused nodes) is noted on stderr, or under
// "input_notes" with --json. Exit codes: 0 ok, 2 usage or bad input (one-line reason on stderr). The
// output is written atomically: on any error no output file appears; it never replaces its input.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/check/orientation.hpp>
#include <volmap/core/count_text.hpp>
#include <volmap/io/io.hpp>

#include <chrono>
#include <cstdio>

int main(int argc, char** argv) {
  CLI::App app{"Convert a tet mesh between .mesh, .vtk, .vtu and .msh, or from .ovm (by extension), keeping vertex and tet order.",
               "volmap-convert"};
  std::string input, output;
  bool json = false, binary = false, vtu_ascii = false;
  app.add_option("input", input, "input tet mesh (.mesh, .vtk, .vtu, .msh or .ovm)")->required();
  app.add_option("output", output, "output tet mesh (.mesh, .vtk, .vtu or .msh)")->required();
  app.add_flag("--json", json, "print one JSON object with the counts");
  app.add_flag("--binary", binary, "write legacy .vtk as BINARY and .msh as binary MSH 4.1 (default ASCII)");
  app.add_flag("--vtu-ascii", vtu_ascii, "write .vtu as ascii (default appended raw binary)");
  return volmap_tools::run_tool(
      app, argc, argv,
      [&]() {
        volmap_tools::RunFiles files;
        volmap::require_tet_mesh_extension(input);
        files.input(input, "input mesh");
        volmap::AtomicOutput& out = files.tet_mesh_output(output, "output mesh");
        const auto t0 = std::chrono::steady_clock::now();
        volmap_tools::InputMeshes inputs("volmap-convert", &json);
        const volmap::TetMeshData mesh = inputs.read(input);
        const auto t1 = std::chrono::steady_clock::now();
        volmap::TetMeshWriteOptions options;
        options.vtk_binary = binary;
        options.msh_encoding = binary ? volmap::MshEncoding::Binary : volmap::MshEncoding::Ascii;
        options.vtu_encoding = vtu_ascii ? volmap::VtuEncoding::Ascii : volmap::VtuEncoding::AppendedRaw;
        volmap::write_tet_mesh(out, mesh, options);
        files.commit();
        const auto t2 = std::chrono::steady_clock::now();
        const volmap::TetSignCounts signs =
            volmap::orient3d_tets(mesh.xyz.data(), mesh.num_vertices(), mesh.tets.data(), mesh.num_tets(), nullptr);
        const std::string orientation = signs.ok ? volmap::describe_orientation(signs) : std::string(signs.error);
        if (json) {
          nlohmann::json j{{"input", input},
                           {"output", output},
                           {"input_format", volmap::tet_mesh_format_name(volmap::tet_mesh_format(input))},
                           {"output_format", volmap::tet_mesh_format_name(volmap::tet_mesh_format(output))},
                           {"vertices", mesh.num_vertices()},
                           {"tets", mesh.num_tets()},
                           {"orientation", {{"class", volmap::to_string(volmap::classify_orientation(signs))},
                                            {"positive", signs.positive}, {"negative", signs.negative},
                                            {"zero", signs.zero}, {"summary", orientation}}},
                           {"read_ms", std::chrono::duration<double, std::milli>(t1 - t0).count()},
                           {"write_ms", std::chrono::duration<double, std::milli>(t2 - t1).count()}};
          if (!inputs.empty()) j["input_notes"] = inputs.json();
          return volmap_tools::print_json(j, volmap_tools::kExitOk);
        } else {
          std::printf("%s -> %s: %s, %s; %s\n", input.c_str(), output.c_str(),
                      volmap::count_of(mesh.num_vertices(), "vertex", "vertices").c_str(),
                      volmap::count_of(mesh.num_tets(), "tet").c_str(), orientation.c_str());
        }
        return volmap_tools::kExitOk;
      },
      &json);
}
