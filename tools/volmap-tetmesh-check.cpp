// volmap-tetmesh-check <in.mesh|.vtk|.vtu|.msh|.ovm> [--fix out.mesh] [--json] [--log checks.csv]
// The seven VOLMAP input checks (volmap-reference.md §8 `tetmesh_checks`, done exactly on every tet):
// orientation, volume, genus, components, manifold, closed, self_intersections. One line per check
// (PASSED/FAILED with figures) or, with --json, one JSON object. The orientation line says in words
// which convention the tets are in (describe_orientation): Gmsh and OpenVolumeMesh files, read as
// they are, are in the opposite one. Reader notes (skipped Gmsh elements, dropped nodes) go to stderr,
// or under "input_notes" with --json.
// --fix out (.mesh/.vtk/.vtu/.msh): when the mesh is coherently opposite (no tet with orient3d > 0),
// writes it with local vertices 0 and 1 swapped in every tet (so every orient3d flips sign; vertex
// order, tet order and labels kept), checks the flipped mesh (the file holds exactly these numbers:
// writers round-trip bit-exactly) and writes it only when it passes every check; refuses (exit 1,
// nothing written) when the signs are mixed or another check still fails. A mesh already in the
// VOLMAP convention is written unchanged (when it passes).
// A surface (.off/.obj/.stl/.ply, read by read_surface) gets the five surface checks instead
// (check_surface: no orientation/volume).
// --log appends VOLMAP's CSV line `name; o; v; g; c; m; b; i` (1/0 per check, same column order; tet
// meshes only). The log and the fixed mesh are written together or not at all.
// Exit codes: 0 all checks pass (after the fix, when one was written), 1 a check failed or --fix
// refused, 2 usage or bad input (one-line reason on stderr).
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/io/atomic_file.hpp>
#include <volmap/io/io.hpp>
#include <volmap/io/io_surface.hpp>
#include <volmap/check/tetmesh_checks.hpp>


#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>

namespace {

using Json = nlohmann::json;

std::string lower_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool is_surface_extension(const std::string& ext) { return ext == "off" || ext == "obj" || ext == "stl" || ext == "ply"; }

Json checks_json(const std::vector<volmap::CheckItem>& checks) {
  Json j = Json::object();
  for (const auto& c : checks) j[c.key] = Json{{"passed", c.passed}, {"detail", c.detail}};
  return j;
}

Json self_intersections_json(const volmap::SelfIntersectionResult& r) {
  Json pairs = Json::array();
  for (const auto& p : r.first_pairs) pairs.push_back({p.first, p.second});
  Json coincident = Json::array();
  for (const auto& p : r.first_coincident) coincident.push_back({p.first, p.second});
  return Json{{"intersecting_pairs", r.intersecting_pairs}, {"first_pairs", pairs},
              {"coincident_vertex_pairs", r.coincident_vertices}, {"first_coincident", coincident},
              {"degenerate_triangles", r.degenerate_triangles}, {"first_degenerate", r.first_degenerate},
              {"candidate_pairs", r.candidate_pairs}};
}

Json tet_report_json(const volmap::TetMeshCheckReport& r) {
  const auto& t = r.topology;
  return Json{{"all_passed", r.all_passed()},
              {"vertices", r.num_vertices},
              {"tets", r.num_tets},
              {"orientation",
               {{"class", volmap::to_string(r.orientation)},
                {"positive", r.signs.positive},
                {"negative", r.signs.negative},
                {"zero", r.signs.zero},
                {"summary", r.check("orientation").detail}}},
              {"checks", checks_json(r.checks)},
              {"topology",
               {{"boundary_faces", t.num_boundary_faces},
                {"boundary_edges", t.num_boundary_edges},
                {"boundary_vertices", t.num_boundary_vertices},
                {"boundary_euler", t.boundary_euler},
                {"boundary_genus", t.boundary_genus_defined ? Json(t.boundary_genus) : Json(nullptr)},
                {"boundary_components", t.num_boundary_components},
                {"tet_components", t.num_tet_components},
                {"unused_vertices", t.num_unused_vertices},
                {"degenerate_tets", t.num_degenerate_tets},
                {"nonmanifold_faces", t.num_nonmanifold_faces},
                {"inconsistent_faces", t.num_inconsistent_faces},
                {"border_edges", t.num_border_edges},
                {"overshared_edges", t.num_overshared_edges},
                {"nonmanifold_boundary_vertices", t.num_nonmanifold_boundary_vertices}}},
              {"self_intersections", self_intersections_json(r.self_intersections)}};
}

void print_checks(const std::vector<volmap::CheckItem>& checks) {
  for (const auto& c : checks)
    std::printf("%-19s %s  %s\n", c.key.c_str(), c.passed ? "PASSED" : "FAILED", c.detail.c_str());
}

// The current content of a --log file ("" when it does not exist yet), ending with a newline.
std::string read_log(const std::string& path) {
  std::string content;
  if (!std::filesystem::exists(path)) return content;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw volmap::Error(volmap::ErrorKind::Io, path, 0, "cannot read the log to append to");
  char buffer[65536];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) content.append(buffer, n);
  std::fclose(f);
  if (!content.empty() && content.back() != '\n') content += '\n';
  return content;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Run the seven VOLMAP checks on a tet mesh (orientation, volume, genus, components, manifold, "
               "closed, self-intersections), exactly on every tet. Surfaces (.off/.obj/.stl/.ply) get the five "
               "surface checks.",
               "volmap-tetmesh-check"};
  std::string input, fix_output;
  bool json = false;
  app.add_option("input", input, "tet mesh (.mesh, .vtk, .vtu, .msh, .ovm) or surface (.off, .obj, .stl, .ply)")->required();
  app.add_option("--fix", fix_output,
                 "write the mesh flipped to the VOLMAP convention (v0<->v1 in every tet) when it is coherently "
                 "opposite (a mesh already positive is written unchanged); refused (exit 1, nothing written) when "
                 "orientation is mixed; the exit code is then the written mesh's verdict");
  app.add_flag("--json", json, "print one JSON object");
  std::string log_csv;
  app.add_option("--log", log_csv,
                 "append one line in VOLMAP tetmesh_checks' CSV format `name; o; v; g; c; m; b; i` (1 = passed) "
                 "to this file (rewritten atomically)");
  return volmap_tools::run_tool(
      app, argc, argv,
      [&]() -> int {
        const auto t0 = std::chrono::steady_clock::now();
        const bool surface_input = is_surface_extension(lower_extension(input));
        if (surface_input && (!fix_output.empty() || !log_csv.empty()))
          throw volmap::Error(volmap::ErrorKind::Unsupported, input, 0, "--fix and --log apply to tet meshes only");
        if (!surface_input) volmap::require_tet_mesh_extension(input);
        volmap_tools::RunFiles files;
        files.input(input, "input");
        volmap::AtomicOutput* fix_out = fix_output.empty() ? nullptr : &files.tet_mesh_output(fix_output, "--fix output");
        volmap::AtomicOutput* log_out = log_csv.empty() ? nullptr : &files.output(log_csv, "--log file");  // appended to
        std::string log_line = std::filesystem::path(input).filename().string();
        auto finish = [&](bool ok, Json j) {
          if (log_out) volmap::write_text(*log_out, read_log(log_csv) + log_line + "\n");
          files.commit();
          return json ? volmap_tools::print_json(std::move(j), ok ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed)
                      : (ok ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed);
        };

        if (surface_input) {
          const volmap::SurfaceData surface = volmap::read_surface(input);
          const auto r = volmap::check_surface(surface);
          const bool ok = r.all_passed();
          Json j;
          if (json) {
            const auto& st = r.topology;
            j = Json{{"input", input}, {"kind", "surface"},
                     {"all_passed", ok}, {"vertices", st.num_vertices}, {"triangles", st.num_triangles},
                     {"checks", checks_json(r.checks)},
                     {"topology", {{"euler", st.euler}, {"genus", st.genus_defined ? Json(st.genus) : Json(nullptr)},
                                   {"components", st.num_components}, {"edges", st.num_edges},
                                   {"border_edges", st.num_border_edges}, {"overshared_edges", st.num_overshared_edges},
                                   {"nonmanifold_vertices", st.num_nonmanifold_vertices},
                                   {"inconsistent_edges", st.num_inconsistent_edges}}},
                     {"self_intersections", self_intersections_json(r.self_intersections)},
                     {"time_ms", ms_since(t0)}};
          } else {
            std::printf("%s: surface, %zu vertices, %zu triangles\n", input.c_str(), r.topology.num_vertices,
                        r.topology.num_triangles);
            print_checks(r.checks);
            std::printf("%s\n", ok ? "all surface checks PASSED" : "surface checks FAILED");
          }
          return finish(ok, std::move(j));
        }

        volmap_tools::InputMeshes inputs("volmap-tetmesh-check", &json);
        volmap::TetMeshData mesh = inputs.read(input);
        const double read_ms = ms_since(t0);
        const auto report = volmap_tools::naming_file(input, [&] { return volmap::check_tet_mesh(mesh); });
        const double check_ms = ms_since(t0) - read_ms;
        bool ok = report.all_passed();
        // VOLMAP's column order: orientation, volume, genus, components, manifold, borders, intersections.
        for (const char* key : {"orientation", "volume", "genus", "components", "manifold", "closed", "self_intersections"})
          log_line += std::string("; ") + (report.check(key).passed ? "1" : "0");
        Json j;
        if (json) j = Json{{"input", input}, {"kind", "tet_mesh"}, {"report", tet_report_json(report)}};
        if (json && !inputs.empty()) j["input_notes"] = inputs.json();
        if (!json) {
          std::printf("%s: %zu vertices, %zu tets\n", input.c_str(), report.num_vertices, report.num_tets);
          print_checks(report.checks);
          std::printf("%s%s\n", fix_output.empty() ? "" : "input: ", ok ? "all checks PASSED" : "checks FAILED");
        }

        if (fix_out) {
          Json fix;
          fix["output"] = fix_output;
          if (report.orientation == volmap::OrientationClass::Mixed ||
              report.orientation == volmap::OrientationClass::Empty) {
            const std::string why = volmap::describe_orientation(report.signs, "--fix");
            fix_out->drop();
            fix["written"] = false;
            fix["reason"] = "refused: " + why;
            if (!json) std::printf("fix: refused, %s; nothing written\n", why.c_str());
            ok = false;
          } else {
            // The flipped mesh is checked before it is written (written files round-trip exactly) and
            // written only when it passes every check: a "fixed" file is a valid input.
            const bool flip = report.orientation == volmap::OrientationClass::CoherentlyOpposite;
            if (flip) volmap::flip_all_tets(mesh);
            const auto after = volmap::check_tet_mesh(mesh);
            ok = after.all_passed();
            if (ok)
              volmap::write_tet_mesh(*fix_out, mesh);
            else
              fix_out->drop();
            fix["written"] = ok;
            fix["flipped_tets"] = flip ? report.num_tets : 0;
            fix["report"] = tet_report_json(after);
            if (!ok) fix["reason"] = "refused: the flipped mesh still fails a check";
            if (!json) {
              std::printf("fix: %s with v0<->v1 swapped in all %zu tets; check of that mesh:\n",
                          flip ? "the mesh" : "the mesh (already in the VOLMAP convention, not flipped)",
                          flip ? report.num_tets : std::size_t(0));
              print_checks(after.checks);
              std::printf("%s\n", ok ? ("fixed mesh: all checks PASSED, wrote " + fix_output).c_str()
                                      : "fixed mesh: checks FAILED; nothing written");
            }
          }
          if (json) j["fix"] = fix;
        }
        if (json) {
          j["read_ms"] = read_ms;
          j["check_ms"] = check_ms;
        }
        return finish(ok, std::move(j));
      },
      &json);
}
