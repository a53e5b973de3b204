// volmap-view — writes ONE self-contained HTML page to inspect a tet mesh, a volume map or a
// boundary map in the browser (offline, from file://):
//   volmap-view <in.mesh> <out.mesh> [-o view.html] [--energy mips3d]   volume map (two linked views)
//   volmap-view <in.mesh> --map boundary.txt [-o view.html]              boundary map (mapped surface)
//   volmap-view <in.mesh> [-o view.html]                                 one mesh
// Per-tet values (VOLMAP energies and quality from volmap/metrics.hpp, Jacobian singular values and
// volumes; see view_metrics_adapter.hpp) are computed in C++; inverted/degenerate flags are exact (volmap predicates, batch orient3d_tets). The viewer
// bundle (viewer/dist/viewer.js: three.js + viewer code, built by `npm ci && npm run build` in
// viewer/) is read at run time from --bundle, else $VOLMAP_VIEWER_BUNDLE, else the installed copy
// next to this executable (<bin>/../share/volmap/viewer/viewer.js, the relative path given by CMake
// as VOLMAP_VIEW_INSTALLED_BUNDLE) when it exists, else the path of this source tree baked in at
// compile time (<repo>/viewer/dist/viewer.js, from __FILE__: the build tree).
// Exit: 0 ok, 2 usage / bad input / bundle missing.
#include "support/tool_common.hpp"
#include "support/view_metrics_adapter.hpp"

#include <volmap/core/boundary_faces.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates.hpp>
#include "support/view_export.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace fs = std::filesystem;
using namespace volmap;

namespace {

#ifndef VOLMAP_VIEW_INSTALLED_BUNDLE
#define VOLMAP_VIEW_INSTALLED_BUNDLE "../share/volmap/viewer/viewer.js"
#endif

std::string source_tree_bundle_path() {
  // __FILE__ is the absolute path of this source file under CMake: <repo>/tools/volmap-view.cpp.
  const fs::path source(__FILE__);
  return (source.parent_path().parent_path() / "viewer" / "dist" / "viewer.js").string();
}

// The installed bundle relative to this executable (/proc/self/exe); empty when it is not there
// (e.g. in the build tree, where the executable is build/bin/volmap-view).
std::string installed_bundle_path() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || exe.empty()) return {};
  const fs::path bundle = (exe.parent_path() / VOLMAP_VIEW_INSTALLED_BUNDLE).lexically_normal();
  return fs::is_regular_file(bundle, ec) ? bundle.string() : std::string();
}

std::string default_bundle_path() {
  const std::string installed = installed_bundle_path();
  return installed.empty() ? source_tree_bundle_path() : installed;
}

std::string read_bundle(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw Error(ErrorKind::Io, path, 0,
                "viewer bundle not found: build it with `npm ci && npm run build` in viewer/ "
                "(or pass --bundle / set VOLMAP_VIEWER_BUNDLE)");
  }
  return read_text_file(path);  // JavaScript: text, vetted like every input
}

// VOLMAP-signed volume: orient3d(a,b,c,d) = det[a-d; b-d; c-d] = 6 V (display only, not a sign
// decision: flags come from the exact predicate).
double signed_volume(const double* a, const double* b, const double* c, const double* d) {
  const double ax = a[0] - d[0], ay = a[1] - d[1], az = a[2] - d[2];
  const double bx = b[0] - d[0], by = b[1] - d[1], bz = b[2] - d[2];
  const double cx = c[0] - d[0], cy = c[1] - d[1], cz = c[2] - d[2];
  return (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6.0;
}

std::vector<double> volumes(const TetMeshData& m, const std::vector<double>& xyz) {
  std::vector<double> v(m.num_tets());
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const std::uint32_t* tv = &m.tets[4 * t];
    v[t] = signed_volume(&xyz[3 * tv[0]], &xyz[3 * tv[1]], &xyz[3 * tv[2]], &xyz[3 * tv[3]]);
  }
  return v;
}

// Exact signs of every tet of (tets, xyz) via the batch predicate.
std::vector<std::int8_t> exact_signs(const TetMeshData& m, const std::vector<double>& xyz, const std::string& what) {
  std::vector<std::int8_t> signs(m.num_tets());
  const TetSignCounts c = orient3d_tets(xyz.data(), xyz.size() / 3, m.tets.data(), m.num_tets(), signs.data());
  if (!c.ok) throw Error(ErrorKind::BadInput, what, 0, std::string("cannot orient tets: ") + c.error);
  return signs;
}

// The page stores coordinates as float32: larger ones cannot be shown (they would become infinite).
void require_float_range(const std::vector<double>& xyz, const std::string& path) {
  for (double c : xyz)
    if (std::abs(c) > static_cast<double>(std::numeric_limits<float>::max())) {
      char buf[48];
      std::snprintf(buf, sizeof buf, "%.3g", c);
      throw Error(ErrorKind::Unsupported, path, 0,
                  std::string("coordinate ") + buf + " is beyond the float range (3.4e38) the page stores");
    }
}

ViewField field_from(const std::string& key, const std::string& label, double lower, double upper,
                     std::vector<double> values, bool worse_high, bool valid_only) {
  ViewField f;
  f.key = key;
  f.label = label;
  f.lower = lower;
  f.upper = upper;
  f.values = std::move(values);
  f.worse_high = worse_high;
  f.valid_only = valid_only;
  f.volume_weighted = worse_high;  // energies: |volume|-weighted (VOLMAP E); quality: plain mean (VOLMAP avg)
  return f;
}

// Every option of the tool.
struct Args {
  std::vector<std::string> inputs;
  std::string output = "view.html", energy, map_path, bundle_path, title;
  double upper = 100;
  bool json = false;
};

void add_options(CLI::App& app, Args& a) {
  app.add_option("meshes", a.inputs, "<in.mesh> [<out.mesh>]: source mesh and, for a volume map, the mapped mesh "
                                     "(.mesh, .vtk or .vtu)")
      ->required()->expected(1, 2);
  app.add_option("-o,--output", a.output, "HTML page to write")->capture_default_str();
  app.add_option("--energy", a.energy, "field coloured at load: conformal, dirichlet, symdir, arap, mips3d, "
                                       "quality_out, quality_in (default: mips3d for a volume map, quality_in otherwise)");
  app.add_option("--map", a.map_path, "boundary map (vid x y z) of <in.mesh>: boundary-map mode without <out.mesh>");
  app.add_option("--upper", a.upper, "upper clamp of the energies (VOLMAP metrics default 100, at least 6)")
      ->capture_default_str()
      ->check(volmap_tools::finite_range(6.0, 1e300));
  app.add_option("--bundle", a.bundle_path, "viewer bundle (default: $VOLMAP_VIEWER_BUNDLE or " + default_bundle_path() + ")");
  app.add_option("--title", a.title, "page title (default: the input file names)");
  app.add_flag("--json", a.json, "print one JSON object (output, bytes, counts, timings)");
}

// The source mesh's part of the view: positions, tets, volumes (the flags follow per mode).
ViewData source_view(const Args& a, const TetMeshData& source) {
  ViewData view;
  view.source_name = fs::path(a.inputs[0]).filename().string();
  view.source_xyz = source.xyz;
  view.tets = source.tets;
  view.volume_in = volumes(source, source.xyz);
  view.num_boundary_faces = boundary_half_faces(source).size();
  view.flags.assign(source.num_tets(), 0);
  return view;
}

// Volume-map mode: flags relative to the source tet, as VOLMAP's volume_mapping_check (a mapped tet
// is inverted when its exact orientation differs from its source tet's, degenerate when either is
// zero; for the usual VOLMAP-positive sources this is "orient3d(output tet) < 0 / == 0", metrics
// rule 1), and the per-tet Jacobian singular values, energies and quality of the metrics module.
// Returns how many target coordinates of boundary vertices differ from --map (0 without it).
std::size_t add_volume_map(ViewData& view, const Args& a, const TetMeshData& source, const std::vector<std::int8_t>& source_signs,
                           const BoundaryMap* map) {
  const TetMeshData target = read_tet_mesh(a.inputs[1]);
  require_float_range(target.xyz, a.inputs[1]);
  if (target.num_vertices() != source.num_vertices() || target.tets != source.tets) {
    throw Error(ErrorKind::BadInput, a.inputs[1], 0,
                "not a map of " + a.inputs[0] + ": the tets differ (" + std::to_string(target.num_tets()) + " vs " +
                    std::to_string(source.num_tets()) + " tets, " + std::to_string(target.num_vertices()) + " vs " +
                    std::to_string(source.num_vertices()) + " vertices, same order required)");
  }
  view.mode = ViewMode::VolumeMap;
  view.target_name = fs::path(a.inputs[1]).filename().string();
  view.target_xyz = target.xyz;
  view.volume_out = volumes(source, target.xyz);
  const std::vector<std::int8_t> target_signs = exact_signs(source, target.xyz, a.inputs[1]);
  for (std::size_t t = 0; t < source.num_tets(); ++t) {
    const int si = source_signs[t], so = target_signs[t];
    view.flags[t] = static_cast<std::uint8_t>((so != 0 && si != 0 && so != si ? kViewInverted : 0) |
                                              (so == 0 || si == 0 ? kViewDegenerate : 0) |
                                              (si <= 0 ? kViewSourceNonPositive : 0));
  }
  const volmap_view::ViewMetrics m = volmap_view::compute_view_metrics(source, target.xyz, source_signs, a.upper);
  view.sigma = m.sigma;
  auto energy = [&](Energy e) { return m.energy[static_cast<int>(e)]; };
  view.fields.push_back(field_from("conformal", "Conformal", 1, a.upper, energy(Energy::Conformal), true, true));
  view.fields.push_back(field_from("dirichlet", "Dirichlet", 3, a.upper, energy(Energy::Dirichlet), true, true));
  view.fields.push_back(field_from("symdir", "Symmetric Dirichlet", 6, a.upper, energy(Energy::SymmetricDirichlet), true, true));
  view.fields.push_back(field_from("arap", "ARAP", 0, a.upper, energy(Energy::Arap), true, true));
  view.fields.push_back(field_from("mips3d", "MIPS3D", 1, a.upper, energy(Energy::Mips3d), true, true));
  view.fields.push_back(field_from("quality_out", "quality 3r/R (target)", 0, 1, m.quality_out, false, false));
  view.fields.push_back(field_from("quality_in", "quality 3r/R (source)", 0, 1, m.quality_in, false, false));
  std::size_t mismatches = 0;
  if (map)
    for (std::size_t i = 0; i < map->size(); ++i) {
      const std::uint32_t v = map->vids[i];
      for (int c = 0; c < 3; ++c) mismatches += target.xyz[3 * v + c] != map->xyz[3 * i + c] ? 1 : 0;
    }
  return mismatches;
}

// Mesh mode, or boundary-map mode with --map: the source's own exact signs, the mapped boundary
// vertices as the target (the others NaN), and the source quality.
void add_mesh_or_boundary_map(ViewData& view, const Args& a, const TetMeshData& source, const std::vector<std::int8_t>& source_signs,
                              const BoundaryMap* map) {
  view.mode = map ? ViewMode::BoundaryMap : ViewMode::Mesh;
  for (std::size_t t = 0; t < source.num_tets(); ++t) {
    view.flags[t] = (source_signs[t] < 0 ? kViewInverted : 0) | (source_signs[t] == 0 ? kViewDegenerate : 0) |
                    (source_signs[t] <= 0 ? kViewSourceNonPositive : 0);
  }
  if (map) {
    view.target_name = fs::path(a.map_path).filename().string();
    view.target_xyz.assign(source.xyz.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < map->size(); ++i)
      for (int c = 0; c < 3; ++c) view.target_xyz[3 * map->vids[i] + c] = map->xyz[3 * i + c];
  }
  view.fields.push_back(field_from("quality_in", "quality 3r/R", 0, 1, volmap_view::tet_quality(source, source.xyz), false, false));
}

// The field coloured at load: --energy, else MIPS3D for a volume map and the source quality otherwise.
std::string initial_field(const ViewData& view, const std::string& requested) {
  const std::string energy = !requested.empty() ? requested : view.mode == ViewMode::VolumeMap ? "mips3d" : "quality_in";
  std::string keys;
  for (const auto& f : view.fields) {
    if (f.key == energy) return energy;
    keys += (keys.empty() ? "" : ", ") + f.key;
  }
  throw Error(ErrorKind::BadInput, "--energy " + energy + " is not available here (choose one of: " + keys + ")");
}

struct PageReport {
  ViewSummary summary;
  InputMeshVerdict verdict;
  std::size_t bytes = 0, map_mismatches = 0;
  double seconds = 0;
};

nlohmann::json page_json(const Args& a, const ViewData& view, const PageReport& p) {
  nlohmann::json j{{"output", a.output},
                   {"bytes", p.bytes},
                   {"mode", view.mode == ViewMode::VolumeMap ? "volume-map" : view.mode == ViewMode::BoundaryMap ? "boundary-map" : "mesh"},
                   {"num_vertices", view.num_vertices()},
                   {"num_tets", view.num_tets()},
                   {"num_inverted", p.summary.num_inverted},
                   {"num_degenerate", p.summary.num_degenerate},
                   {"bundle", a.bundle_path},
                   {"valid_input", p.verdict.valid},
                   {"seconds", p.seconds}};
  if (!p.verdict.valid) j["input_problem"] = p.verdict.reason();
  if (!a.map_path.empty() && a.inputs.size() == 2) j["map_coordinate_mismatches"] = p.map_mismatches;
  for (const auto& f : p.summary.fields) {
    j["fields"][f.key] = {{"count", f.count},
                          {"min", std::isfinite(f.min) ? nlohmann::json(f.min) : nlohmann::json()},
                          {"max", std::isfinite(f.max) ? nlohmann::json(f.max) : nlohmann::json()},
                          {"weighted_mean", std::isfinite(f.weighted_mean) ? nlohmann::json(f.weighted_mean) : nlohmann::json()}};
  }
  return j;
}

void print_text_report(const Args& a, const ViewData& view, const PageReport& p) {
  if (!p.verdict.valid)
    std::cout << "volmap-view: note: " << a.inputs[0] << " is not a valid input tet mesh: " << p.verdict.reason() << "\n";
  std::cout << "volmap-view: wrote " << a.output << " (" << p.bytes << " bytes, " << view.num_tets() << " tets, "
            << p.summary.num_inverted << " inverted, " << p.summary.num_degenerate << " degenerate) in " << p.seconds
            << " s\n";
  if (!a.map_path.empty() && a.inputs.size() == 2 && p.map_mismatches)
    std::cout << "volmap-view: note: " << p.map_mismatches << " target coordinates differ from the boundary map\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"volmap-view: write one self-contained HTML page (offline, file://) to inspect a tet mesh, "
               "a volume map (in + out) or a boundary map (in + --map) in the browser",
               "volmap-view"};
  Args a;
  add_options(app, a);
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    if (a.bundle_path.empty()) {
      const char* env = std::getenv("VOLMAP_VIEWER_BUNDLE");
      a.bundle_path = env && *env ? env : default_bundle_path();
    }
    volmap_tools::RunFiles files;
    for (const std::string& in : a.inputs) require_tet_mesh_extension(in);
    files.input(a.inputs[0], "input mesh");
    if (a.inputs.size() == 2) files.input(a.inputs[1], "mapped mesh");
    files.input(a.map_path, "--map file");
    files.input(a.bundle_path, "viewer bundle");
    AtomicOutput& page = files.output(a.output, "output page");
    const std::string bundle = read_bundle(a.bundle_path);
    if (bundle.empty()) throw Error(ErrorKind::Io, a.bundle_path, 0, "the viewer bundle is empty (build viewer/: npm ci && npm run build)");

    const TetMeshData source = read_tet_mesh(a.inputs[0]);
    require_float_range(source.xyz, a.inputs[0]);
    if (source.num_tets() == 0) throw Error(ErrorKind::BadInput, a.inputs[0], 0, "has no tets: nothing to show");
    PageReport report;
    // A viewer shows broken meshes too (that is what it is for), but says so.
    report.verdict = volmap_tools::naming_file(a.inputs[0], [&] { return judge_input_mesh(source); });
    ViewData view = source_view(a, source);
    const std::vector<std::int8_t> source_signs = exact_signs(source, source.xyz, a.inputs[0]);
    BoundaryMap map;
    if (!a.map_path.empty()) {
      map = read_boundary_map(a.map_path);
      validate_boundary_map(map, source, a.map_path);
      require_float_range(map.xyz, a.map_path);
    }
    const BoundaryMap* given_map = a.map_path.empty() ? nullptr : &map;
    if (a.inputs.size() == 2)
      report.map_mismatches = add_volume_map(view, a, source, source_signs, given_map);
    else
      add_mesh_or_boundary_map(view, a, source, source_signs, given_map);
    view.initial_field = initial_field(view, a.energy);
    view.title = a.title.empty() ? view.source_name + (view.target_name.empty() ? "" : " → " + view.target_name) : a.title;

    const std::string html = volmap_tools::naming_file(a.bundle_path, [&] { return build_view_html(view, bundle); });
    write_text(page, html);
    files.commit();
    report.summary = summarize_view(view);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report.bytes = html.size();
    if (a.json) return volmap_tools::print_json(page_json(a, view, report), volmap_tools::kExitOk);
    print_text_report(a, view, report);
    return volmap_tools::kExitOk;
  }, &a.json);
}
