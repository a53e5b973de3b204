// volmap-convert <in> <out> [--json] [--binary] [--vtu-ascii]
// Converts tet meshes between Medit .mesh, legacy VTK .vtk, VTK XML .vtu and Gmsh .msh (4.1 written;
// 2.2/4.1 read), and reads OpenVolumeMesh .ovm, chosen by extension (case-insensitive), keeping
// vertex order, tet order and each tet's vertex order (so no orientation is changed: the line printed
// says which convention the tets are in); Medit labels are carried along. What a reader skipped or
// renumbered (Gmsh's lower-dimensional elements, unused nodes) is noted on stderr, or under
// "input_notes" with --json. Exit codes: 0 ok, 2 usage or bad input (one-line reason on stderr). The
// output is written atomically: on any error no output file appears.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/check/orientation.hpp>
#include <volmap/core/count_text.hpp>
#include <volmap/io/io.hpp>

#include <chrono>
#include <cstdio>

int main(int argc, char** argv) {
  CLI::App app{"Convert a tet mesh between .mesh, .vtk and .vtu (by extension), keeping vertex and tet order.",
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
        const auto in_format = volmap::tet_mesh_format(input);
        const auto out_format = volmap::tet_mesh_format(output);
        if (in_format == volmap::TetMeshFormat::Unknown)
          throw volmap::Error(volmap::ErrorKind::Unsupported, input, 0, "unknown input extension (expected .mesh, .vtk, .vtu, .msh or .ovm)");
        if (out_format == volmap::TetMeshFormat::Unknown || out_format == volmap::TetMeshFormat::Ovm)
          throw volmap::Error(volmap::ErrorKind::Unsupported, output, 0, "unsupported output extension (expected .mesh, .vtk, .vtu or .msh)");
        const auto t0 = std::chrono::steady_clock::now();
        volmap_tools::InputMeshes inputs("volmap-convert", &json);
        const volmap::TetMeshData mesh = inputs.read(input);
        const auto t1 = std::chrono::steady_clock::now();
        volmap::TetMeshWriteOptions options;
        options.vtk_binary = binary;
        options.msh_encoding = binary ? volmap::MshEncoding::Binary : volmap::MshEncoding::Ascii;
        options.vtu_encoding = vtu_ascii ? volmap::VtuEncoding::Ascii : volmap::VtuEncoding::AppendedRaw;
        volmap::write_tet_mesh(output, mesh, options);
        const auto t2 = std::chrono::steady_clock::now();
        const volmap::TetSignCounts signs =
            volmap::orient3d_tets(mesh.xyz.data(), mesh.num_vertices(), mesh.tets.data(), mesh.num_tets(), nullptr);
        const std::string orientation = signs.ok ? volmap::describe_orientation(signs) : std::string(signs.error);
        if (json) {
          nlohmann::json j{{"ok", true},
                           {"exit_code", 0},
                           {"input", input},
                           {"output", output},
                           {"input_format", volmap::tet_mesh_format_name(in_format)},
                           {"output_format", volmap::tet_mesh_format_name(out_format)},
                           {"vertices", mesh.num_vertices()},
                           {"tets", mesh.num_tets()},
                           {"orientation", {{"class", volmap::to_string(volmap::classify_orientation(signs))},
                                            {"positive", signs.positive}, {"negative", signs.negative},
                                            {"zero", signs.zero}, {"summary", orientation}}},
                           {"read_ms", std::chrono::duration<double, std::milli>(t1 - t0).count()},
                           {"write_ms", std::chrono::duration<double, std::milli>(t2 - t1).count()}};
          if (!inputs.empty()) j["input_notes"] = inputs.json();
          std::cout << j.dump() << "\n";
        } else {
          std::printf("%s -> %s: %s, %s; %s\n", input.c_str(), output.c_str(),
                      volmap::count_of(mesh.num_vertices(), "vertex", "vertices").c_str(),
                      volmap::count_of(mesh.num_tets(), "tet").c_str(), orientation.c_str());
        }
        return volmap_tools::kExitOk;
      },
      &json);
}
