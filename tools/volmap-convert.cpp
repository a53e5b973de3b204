// volmap-convert <in> <out> [--json] [--binary] [--vtu-ascii]
// Converts tet meshes between Medit .mesh, legacy VTK .vtk and VTK XML .vtu, chosen by extension
// (case-insensitive), keeping vertex order, tet order and each tet's vertex order; Medit labels are
// carried along. A format tool: it copies any readable mesh, valid or not (volmap-tetmesh-check
// judges it). Exit codes: 0 ok, 2 usage or bad input (one-line reason on stderr). The output is
// written atomically: on any error no output file appears; it never replaces its input.
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
        volmap_tools::RunFiles files;
        volmap::require_tet_mesh_extension(input);
        files.input(input, "input mesh");
        volmap::AtomicOutput& out = files.tet_mesh_output(output, "output mesh");
        const auto t0 = std::chrono::steady_clock::now();
        const volmap::TetMeshData mesh = volmap::read_tet_mesh(input);
        const auto t1 = std::chrono::steady_clock::now();
        volmap::TetMeshWriteOptions options;
        options.vtk_binary = binary;
        options.vtu_encoding = vtu_ascii ? volmap::VtuEncoding::Ascii : volmap::VtuEncoding::AppendedRaw;
        volmap::write_tet_mesh(out, mesh, options);
        files.commit();
        const auto t2 = std::chrono::steady_clock::now();
        if (json) {
          return volmap_tools::print_json({{"input", input},
                                           {"output", output},
                                           {"input_format", format_name(volmap::tet_mesh_format(input))},
                                           {"output_format", format_name(volmap::tet_mesh_format(output))},
                                           {"vertices", mesh.num_vertices()},
                                           {"tets", mesh.num_tets()},
                                           {"read_ms", std::chrono::duration<double, std::milli>(t1 - t0).count()},
                                           {"write_ms", std::chrono::duration<double, std::milli>(t2 - t1).count()}},
                                          volmap_tools::kExitOk);
        }
        return volmap_tools::kExitOk;
      },
      &json);
}
