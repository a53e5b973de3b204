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
    std::filesystem::create_directories(out_dir);
    nlohmann::json written = nlohmann::json::array();
    for (const auto& name : selected) {
      const auto surface = volmap::make_builtin_shape(name, subdivisions);
      const auto path = (std::filesystem::path(out_dir) / (name + "." + format)).string();
      volmap::write_surface(path, surface);
      written.push_back({{"name", name}, {"path", path}, {"triangles", surface.tris.size() / 3}});
      if (!json) std::cout << path << " (" << surface.tris.size() / 3 << " triangles)\n";
    }
    if (json) std::cout << nlohmann::json{{"ok", true}, {"surfaces", written}}.dump() << "\n";
    return volmap_tools::kExitOk;
  }, &json);
}
