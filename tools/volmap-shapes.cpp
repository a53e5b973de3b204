// volmap-shapes — write the built-in genus-0 demo surfaces (procedural, no downloads).
//   volmap-shapes <out_dir> [--names ellipsoid,bumpy,... | --thin] [--subdivisions 3] [--format off] [--json]
#include "support/tool_common.hpp"

#include <volmap/io/io_surface.hpp>
#include "support/shapes.hpp"

#include <filesystem>

int main(int argc, char** argv) {
  CLI::App app{"Write procedurally generated closed genus-0 surfaces (the demo's built-in data).", "volmap-shapes"};
  std::string out_dir, names, format = "off";
  int subdivisions = 3;
  bool json = false, thin = false;
  app.add_option("out_dir", out_dir, "folder to write <name>.<format> into (created)")->required();
  auto* names_option = app.add_option(
      "--names", names, "comma-separated subset of: ellipsoid,bumpy,peanut,rounded_box,spiky,banana (demo) or thin-feature shapes");
  app.add_flag("--thin", thin, "all thin-feature shapes (tentacles, limbs, fins, plate, spiky_star, dumbbell, calibration_cube, variants)")
      ->excludes(names_option);
  app.add_option("--subdivisions", subdivisions, "icosphere subdivisions (20*4^s triangles)")->check(CLI::Range(0, 7));
  app.add_option("--format", format, "off, obj, stl or ply")->check(CLI::IsMember({"off", "obj", "stl", "ply"}));
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    std::vector<std::string> selected;
    std::string cur;
    for (char c : names + ",") {
      if (c == ',') {
        if (!cur.empty()) selected.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    if (selected.empty()) selected = thin ? volmap::thin_shape_names() : volmap::builtin_shape_names();
    // Every surface is made first (unknown names refused before anything is created), then all files
    // are written together (none on any error).
    std::vector<volmap::SurfaceData> surfaces;
    for (const auto& name : selected) surfaces.push_back(volmap::make_builtin_shape(name, subdivisions));
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (!std::filesystem::is_directory(out_dir))
      throw volmap::Error(volmap::ErrorKind::Io, out_dir, 0,
                          "cannot create the output folder" + (ec ? ": " + ec.message() : std::string()));
    volmap_tools::RunFiles files;
    nlohmann::json written = nlohmann::json::array();
    for (std::size_t k = 0; k < selected.size(); ++k) {
      const auto path = (std::filesystem::path(out_dir) / (selected[k] + "." + format)).string();
      volmap::write_surface(files.output(path, "surface " + selected[k]), surfaces[k]);
      written.push_back({{"name", selected[k]}, {"path", path}, {"triangles", surfaces[k].num_triangles()}});
    }
    files.commit();
    if (json) return volmap_tools::print_json({{"surfaces", written}}, volmap_tools::kExitOk);
    for (const auto& w : written)
      std::cout << w["path"].get<std::string>() << " (" << w["triangles"].get<std::size_t>() << " triangles)\n";
    return volmap_tools::kExitOk;
  }, &json);
}
