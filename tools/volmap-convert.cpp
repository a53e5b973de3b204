// volmap-convert <in> <out> [--json] [--binary] [--vtu-ascii]
// Converts tet meshes between Medit .mesh, legacy VTK .vtk and VTK XML .vtu, chosen by extension
// (case-insensitive), keeping vertex order, tet order and each tet's vertex order; Medit labels are
// carried along. Exit codes: 0 ok, 2 usage or bad input (one-line reason on stderr). The output is
// written atomically: on any error no output file appears.
#include "support/tool_common.hpp"

#include <volmap/io/io.hpp>

#include <chrono>

namespace {
const char* format_name(volmap::TetMeshFormat f) {
  switch (f) {
    case volmap::TetMeshFormat::Medit: return "mesh";
    case volmap::TetMeshFormat::Vtk: return "vtk";
    case volmap::TetMeshFormat::Vtu: return "vtu";
    default: return "unknown";
  }
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Convert a tet mesh between .mesh, .vtk and .vtu (by extension), keeping vertex and tet order.",
               "volmap-convert"};
  std::string input, output;
  bool json = false, binary = false, vtu_ascii = false;
  app.add_option("input", input, "input tet mesh (.mesh, .vtk or .vtu)")->required();
  app.add_option("output", output, "output tet mesh (.mesh, .vtk or .vtu)")->required();
  app.add_flag("--json", json, "print one JSON object with the counts");
  app.add_flag("--binary", binary, "write legacy .vtk as BINARY (default ASCII)");
  app.add_flag("--vtu-ascii", vtu_ascii, "write .vtu as ascii (default appended raw binary)");
  return volmap_tools::run_tool(
      app, argc, argv,
      [&]() {
        const auto in_format = volmap::tet_mesh_format(input);
        const auto out_format = volmap::tet_mesh_format(output);
        if (in_format == volmap::TetMeshFormat::Unknown)
          throw volmap::Error(volmap::ErrorKind::Unsupported, input, 0, "unknown input extension (expected .mesh, .vtk or .vtu)");
        if (out_format == volmap::TetMeshFormat::Unknown)
          throw volmap::Error(volmap::ErrorKind::Unsupported, output, 0, "unknown output extension (expected .mesh, .vtk or .vtu)");
        const auto t0 = std::chrono::steady_clock::now();
        const volmap::TetMeshData mesh = volmap::read_tet_mesh(input);
        const auto t1 = std::chrono::steady_clock::now();
        volmap::TetMeshWriteOptions options;
        options.vtk_binary = binary;
        options.vtu_encoding = vtu_ascii ? volmap::VtuEncoding::Ascii : volmap::VtuEncoding::AppendedRaw;
        volmap::write_tet_mesh(output, mesh, options);
        const auto t2 = std::chrono::steady_clock::now();
        if (json) {
          nlohmann::json j{{"ok", true},
                           {"exit_code", 0},
                           {"input", input},
                           {"output", output},
                           {"input_format", format_name(in_format)},
                           {"output_format", format_name(out_format)},
                           {"vertices", mesh.num_vertices()},
                           {"tets", mesh.num_tets()},
                           {"read_ms", std::chrono::duration<double, std::milli>(t1 - t0).count()},
                           {"write_ms", std::chrono::duration<double, std::milli>(t2 - t1).count()}};
          std::cout << j.dump() << "\n";
        }
        return volmap_tools::kExitOk;
      },
      &json);
}
