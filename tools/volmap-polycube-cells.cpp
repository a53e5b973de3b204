// volmap-polycube-cells — a star-shaped polycube target for a tet mesh (voxelize_star_polycube), written
// as a cells file for `volmap-surface-map polycube --cells <file>`.
//   volmap-polycube-cells <mesh> <cells.txt> [--resolution 4] [--json]
// Exit 0 written; 2 usage or bad input (incl. no cell centre inside the mesh at this resolution).
#include "support/tool_common.hpp"

#include <volmap/io/atomic_file.hpp>
#include <volmap/surface/polycube_voxelize.hpp>

#include <sstream>

int main(int argc, char** argv) {
  CLI::App app{"Voxelize a tet mesh and keep the strictly star-shaped polycube around its centre, as a cells file.",
               "volmap-polycube-cells"};
  std::string mesh_path, cells_path;
  int resolution = 4;
  bool json = false;
  app.add_option("mesh", mesh_path, "input tet mesh (.mesh/.vtk/.vtu/.msh/.ovm, VOLMAP-positive)")->required();
  app.add_option("cells", cells_path, "output cells file (one `i j k` line per cell)")->required();
  app.add_option("--resolution", resolution, "cells along the longest side of the mesh's bounding box")->check(CLI::Range(1, 64));
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    volmap_tools::RunFiles files;
    volmap_tools::InputMeshes inputs("volmap-polycube-cells", &json);
    volmap::require_tet_mesh_extension(mesh_path);
    files.input(mesh_path, "input mesh");
    volmap::AtomicOutput& out = files.output(cells_path, "output cells file");

    const volmap::TetMeshData mesh = volmap_tools::read_input_tet_mesh(inputs, mesh_path);
    const auto cells = volmap_tools::naming_file(mesh_path, [&] { return volmap::voxelize_star_polycube(mesh, resolution); });
    std::ostringstream text;
    text << "# star-shaped polycube of " << mesh_path << " at resolution " << resolution << " (volmap-polycube-cells)\n";
    for (const auto& c : cells) text << c[0] << " " << c[1] << " " << c[2] << "\n";
    volmap::write_text(out, text.str());
    files.commit();
    if (json) {
      nlohmann::json j{{"mesh", mesh_path}, {"cells_file", cells_path}, {"resolution", resolution}, {"cells", cells.size()}};
      if (!inputs.empty()) j["input_notes"] = inputs.json();
      return volmap_tools::print_json(std::move(j), volmap_tools::kExitOk);
    }
    std::cout << "wrote " << cells_path << ": " << cells.size() << " cells (resolution " << resolution << ")\n";
    return volmap_tools::kExitOk;
  }, &json);
}
