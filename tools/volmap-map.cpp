// volmap-map — certified robust volume mapper (docs/mapping.md), candidate-method contract:
//   volmap-map <in.mesh> <map.txt> <out.mesh> [--method ffm|tlc] [--refined-input path]
//              [--rationals path] [--max-growth 0.05] [--no-refine] [--time-limit s] [--threads n] [--json]
//              [--tlc-share 0.5] [--ffm-inner n] [--ffm-rest-first] [--no-local] [--no-kernel-descent]   (cascade tuning, see volume_map.hpp)
//              [--initial init.(mesh|vtk|vtu)]
// in.mesh may be .mesh/.vtk/.vtu/.msh/.ovm and must be a valid VOLMAP input (input_mesh.hpp: what
// volmap-tetmesh-check accepts), else exit 2 naming the file and the problem; an input in the
// opposite convention, as Gmsh and OpenVolumeMesh files are, is refused with the sentence of
// describe_orientation (flip it first with volmap-tetmesh-check --fix). --initial starts from
// a given (possibly tangled) map instead of Tutte 3D: same vertex count and the same tets in the same
// order as the input, boundary vertices bit-identical to the prescribed map (else exit 2). A map
// positional of `-` takes the boundary map from the initial file's boundary vertices (requires
// --initial).
// out.mesh and --refined-input are written in the format of their extension (.mesh/.vtk/.vtu/.msh) with
// the (refined) input's vertices and tets in the same order; every double in shortest round-trip
// form, so the file reads back bit-identically. Refinement (chord splits, cone repair) happens only
// when --refined-input is given (the refined source is written there; the pair has identical
// connectivity); without it the connectivity is fixed (as with --no-refine).
// --method ffm (default) runs the cascade of volmap/volume_map.hpp (Tutte or --initial → TLC → link-kernel →
// local FFM (Newton) on the bad region → global FFM with stall hand-over → local FFM);
// --method tlc runs only Tutte → TLC (Du et al. 2020 baseline, judged by the same exact check).
// With --refined-input, B0 (chord flips and splits, docs/mapping.md §4) and B1 (cone repair, §7) may refine the source,
// and, when this build has TetGen, the last resort remeshes the interior (§8 step 11; --no-remesh: never):
// the runs from the input get half the time limit, an uncertified result the remeshed source with the rest.
// When the boundary is star-shaped in both spaces, an uncertified result becomes one cone patch over the
// whole boundary (§8 step 12; --no-whole-cone: never): certified, of poor quality. A result that grew
// the mesh then gets fewer tets where a new fill valid in both spaces has fewer, and loses the
// degree-3 interior edges whose 3-2 flip is valid in both spaces (§8 step 14; --no-fewer-tets: never).
// All outputs are prepared before the run (paths distinct from every input and from each other)
// and committed together. Certification: the written files are read back and check_map (exact
// orient3d, boundary bit-identical to the map, input positive) runs on exactly those numbers.
// When no map can exist, `infeasible` (JSON) says so: scope "any-refinement" (the boundary image
// encloses a non-positive volume) or "this-connectivity" with the exact local certificates of
// volmap/volume/infeasibility.hpp (kind, simplex, constraint tets, multipliers); exit 1 then.
// Exit: 0 certified; 1 ran but not injective (the outputs are STILL written with the best map found,
// so it can be inspected; it must not be used as a valid map); 2 usage or bad input.
#include "support/allocation_policy.hpp"
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/check/map_check.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates_rational.hpp>
#include <volmap/volume/volume_map.hpp>
#ifdef VOLMAP_HAVE_TETGEN
#include <volmap/tetgen/remesh.hpp>
#endif

#include <algorithm>
#include <cstdio>

namespace {

// Every option of the tool, with the library's defaults.
struct Args {
  std::string in_path, map_path, out_path, refined_path, rationals_path, initial_path, method = "ffm", start = "fewest";
  double max_growth = 0.05, max_growth_cap = volmap::VolumeMapOptions{}.max_growth_last_resort, time_limit = 60;
  double quality_tol = volmap::VolumeMapOptions{}.quality_relative_decrease, tlc_share = volmap::VolumeMapOptions{}.tlc_time_share;
  double remesh_quality = 3.0;  // InteriorRemeshOptions::quality
  bool no_refine = false, no_restart = false, no_remesh = false, no_whole_cone = false, no_fewer_tets = false, no_quality = false,
       json = false;
  bool ffm_rest_first = false, no_local = false, no_kernel_descent = false, no_flips = false, no_local_rounds = false;
  int threads = 0, ffm_inner = 0;
};

void add_options(CLI::App& app, Args& a) {
  using volmap_tools::finite_non_negative;
  app.add_option("input", a.in_path, "source tet mesh (.mesh/.vtk/.vtu/.msh/.ovm, a valid VOLMAP input)")->required();
  app.add_option("map", a.map_path, "boundary map `vid x y z` (0-based), or - to take it from --initial")->required();
  app.add_option("output", a.out_path, "output tet mesh (.mesh/.vtk/.vtu/.msh by extension; same tets/vertices as the (refined) input)")->required();
  app.add_option("--method", a.method, "ffm (default: Tutte → FFM → repair) or tlc (Du et al. 2020 baseline)")
      ->check(CLI::IsMember({"ffm", "tlc"}));
  app.add_option("--refined-input", a.refined_path, "where to write the refined source (.mesh/.vtk/.vtu/.msh); refinement (chord splits, cone repair) is enabled only with this path");
  app.add_option("--rationals", a.rationals_path, "also write the output coordinates as exact rationals (VOLMAP num/den)");
  app.add_option("--max-growth", a.max_growth, "tet growth budget of the cone repair (fraction of input tets)")
      ->check(finite_non_negative());
  app.add_option("--max-growth-last-resort", a.max_growth_cap,
                 "when patches within --max-growth cannot repair the last bad tets, the budget grows up to this fraction (default 0.5; = --max-growth: never)")
      ->check(finite_non_negative());
  app.add_option("--start", a.start, "starting map: tutte (Tutte 3D), radial (Tutte inside the boundary image projected onto a sphere about a kernel point, mapped back cone by cone), or fewest (default: Tutte, and on a non-convex boundary image also radial, keeping the one with fewer bad tets)")
      ->check(CLI::IsMember({"tutte", "radial", "fewest"}));
  app.add_flag("--no-restart", a.no_restart, "with --start fewest: never restart from the other start (default: when both starts were computed and the first run is not certified in half the time limit, the other start gets the rest; on a convex image, where Tutte starts alone, the radial start gets what an uncertified first run leaves, if at least a tenth of the limit)");
  app.add_flag("--no-refine", a.no_refine, "fixed connectivity (never refine)");
  app.add_flag("--no-remesh", a.no_remesh,
               "refinement: never remesh the interior (default, when built with TetGen: runs from the input get half the time "
               "limit; if they end uncertified, the interior is re-tetrahedralised keeping the boundary and every input "
               "vertex, and mapped with the rest; when TetGen refuses, the rest continues the runs from the input)");
  app.add_flag("--no-whole-cone", a.no_whole_cone,
               "refinement: never replace the whole mesh by one cone patch (default: when the boundary is star-shaped in the "
               "source and in the map's image, the runs get 95 % of the time limit and an uncertified result becomes the "
               "cones from a kernel point over the boundary: certified, poor quality; certified_by whole-mesh-cone)");
  app.add_flag("--no-fewer-tets", a.no_fewer_tets,
               "refinement: keep the runs' result as it is (default: when it grew the mesh, vertices the refinement added are "
               "taken back where a fill of their link valid in both spaces has fewer tets, and on inputs of at most 2000 tets "
               "the whole boundary is re-filled when that has fewer tets, then interior edges of degree 3 are flipped 3-2 where both "
               "new tets are positive in both spaces; every change re-checked exactly)");
  app.add_option("--remesh-quality", a.remesh_quality, "refinement: TetGen radius-edge bound of the interior remesh (default 3)")
      ->check(volmap_tools::finite_range(1.0, 1e6));
  app.add_flag("--no-quality", a.no_quality, "skip the validity-preserving quality pass");
  app.add_option("--quality-tol", a.quality_tol, "quality pass: stop at the first iteration lowering the energy by less than this fraction (0 = run to the iteration cap or the time share)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--time-limit", a.time_limit, "soft time limit in seconds for the whole run, reading and writing included (default 60; 0 = none: every stage then runs to its own iteration cap, which can take many minutes)")
      ->check(finite_non_negative());
  app.add_option("--threads", a.threads, "worker threads (0 = all cores)")->check(CLI::Range(0, 4096));
  app.add_option("--tlc-share", a.tlc_share, "cascade: fraction of the remaining time given to the first TLC stage")
      ->check(volmap_tools::finite_range(0.0, 1.0));
  app.add_option("--ffm-inner", a.ffm_inner, "cascade: L-BFGS iterations per FFM outer step (0 = default)")
      ->check(CLI::Range(0, 1 << 30));
  app.add_flag("--ffm-rest-first", a.ffm_rest_first, "cascade: run FFM with the rest-shape reference before the regular tet");
  app.add_flag("--no-kernel-descent", a.no_kernel_descent, "cascade: skip the kernel-descent stages (exact single-vertex moves driven by the bad tets)");
  app.add_flag("--no-flips", a.no_flips, "refinement: skip the flips that remove non-positive tets without a new vertex");
  app.add_flag("--no-local", a.no_local, "cascade: skip the local FFM (Newton) stages on the bad region");
  app.add_flag("--no-local-rounds", a.no_local_rounds, "fixed connectivity: with few bad tets left, run the global FFM stages instead of rounds of small-lift TLC and local FFM");
  app.add_option("--initial", a.initial_path, "start from this map (same vertices/tets as the input; boundary = the prescribed map) instead of Tutte 3D");
  app.add_flag("--json", a.json, "print one JSON object");
}

// The outputs of one run, prepared (checked against the inputs and each other) before any work.
struct Outputs {
  volmap::AtomicOutput* map = nullptr;
  volmap::AtomicOutput* refined = nullptr;    // only with --refined-input
  volmap::AtomicOutput* rationals = nullptr;  // only with --rationals
};

Outputs prepare_files(const Args& a, volmap_tools::RunFiles& files) {
  if (a.map_path == "-" && a.initial_path.empty())
    throw volmap::Error(volmap::ErrorKind::BadInput, "map `-` needs --initial (the boundary map is taken from it)");
  volmap::require_tet_mesh_extension(a.in_path);
  if (!a.initial_path.empty()) volmap::require_tet_mesh_extension(a.initial_path);
  files.input(a.in_path, "input mesh");
  if (a.map_path != "-") files.input(a.map_path, "boundary map");
  files.input(a.initial_path, "--initial map");
  Outputs out;
  out.map = &files.tet_mesh_output(a.out_path, "output map");
  if (!a.refined_path.empty()) out.refined = &files.tet_mesh_output(a.refined_path, "--refined-input");
  if (!a.rationals_path.empty()) out.rationals = &files.output(a.rationals_path, "--rationals");
  return out;
}

// --initial: the same vertices and tets as the input, in the same order.
std::vector<double> read_initial_map(volmap_tools::InputMeshes& inputs, const Args& a, const volmap::TetMeshData& input) {
  const volmap::TetMeshData initial = inputs.read(a.initial_path);
  if (initial.num_vertices() != input.num_vertices() || initial.tets != input.tets)
    throw volmap::Error(volmap::ErrorKind::BadInput, a.initial_path, 0,
                        "the initial map must have the input's vertices and the same tets in the same order (" +
                            std::to_string(initial.num_vertices()) + " vertices / " + std::to_string(initial.num_tets()) + " tets vs " +
                            std::to_string(input.num_vertices()) + " / " + std::to_string(input.num_tets()) + ")");
  volmap_tools::require_moderate_coordinates(initial.xyz, a.initial_path);
  return initial.xyz;
}

// The boundary map from its file, or (map `-`) the initial map's boundary vertices.
volmap::BoundaryMap read_boundary_map_arg(const Args& a, const volmap::TetMeshData& input, const std::vector<double>& initial_xyz) {
  volmap::BoundaryMap map;
  if (a.map_path == "-") {
    for (std::uint32_t v : volmap::boundary_vertex_ids(input)) {
      map.vids.push_back(v);
      for (int i = 0; i < 3; ++i) map.xyz.push_back(initial_xyz[3 * std::size_t(v) + i]);
    }
    return map;
  }
  map = volmap::read_boundary_map(a.map_path);
  volmap::validate_boundary_map(map, input, a.map_path);
  volmap_tools::require_moderate_coordinates(map.xyz, a.map_path);
  return map;
}

// The mapper's options. It gets the limit less what reading and validating took, and four times as
// much for writing the outputs and reading them back for the final check (that took 3.3 times the
// reading on the 24k-77k-tet thin cases); at least 1 % of the limit is held back, since the stage
// running at the deadline finishes its step (limbs_thin → star ended at 60.06 s of 60 with a reserve
// of 5 × 20 ms).
volmap::VolumeMapOptions mapping_options(const Args& a, bool refine, double seconds_so_far) {
  volmap::VolumeMapOptions opt;
  opt.method = a.method == "tlc" ? volmap::MapMethod::Tlc : volmap::MapMethod::Ffm;
  opt.allow_refinement = refine;
  opt.max_growth = a.max_growth;
  opt.max_growth_last_resort = a.max_growth_cap;
  const double reserve = std::max(5 * seconds_so_far, 0.01 * a.time_limit);
  opt.time_limit_seconds = a.time_limit > 0 ? std::max(1e-3, a.time_limit - reserve) : 0;
  opt.max_threads = a.threads;
  opt.quality_pass = !a.no_quality;
  opt.start = a.start == "tutte" ? volmap::StartMap::Tutte : a.start == "radial" ? volmap::StartMap::Radial : volmap::StartMap::Fewest;
  opt.restart_share = a.no_restart ? 1.0 : opt.restart_share;
  opt.quality_relative_decrease = a.quality_tol;
  opt.tlc_time_share = a.tlc_share;
  opt.ffm_max_lbfgs_iterations = a.ffm_inner;
  opt.ffm_rest_shape_first = a.ffm_rest_first;
  opt.local_untangle = !a.no_local;
  if (a.no_local_rounds) opt.local_rounds_max_bad = 0;
  opt.kernel_descent = !a.no_kernel_descent;
  opt.bad_tet_flips = !a.no_flips;
  opt.whole_mesh_cone = !a.no_whole_cone;
  opt.fewer_tets = !a.no_fewer_tets;
#ifdef VOLMAP_HAVE_TETGEN
  if (refine && !a.no_remesh)
    opt.remesh_interior = [quality = a.remesh_quality](const volmap::TetMeshData& source, double seconds) {
      return volmap::remesh_interior(source, volmap::InteriorRemeshOptions{quality, seconds});
    };
#endif
  return opt;
}

void write_outputs(const Outputs& out, const volmap::VolumeMapResult& r, volmap_tools::RunFiles& files) {
  volmap::TetMeshData target = r.source;
  target.xyz = r.target_xyz;
  volmap::write_tet_mesh(*out.map, target);
  if (out.refined) {
    if (r.refined)
      volmap::write_tet_mesh(*out.refined, r.source);
    else
      out.refined->drop();  // nothing was refined: the input is the source
  }
  if (out.rationals) volmap::write_rationals(*out.rationals, volmap::rationals_from_doubles(target.xyz));
  files.commit();
}

// Certifies exactly what was written: the files, read back, through the one map check.
struct Verdict {
  volmap::TetMeshData written;
  volmap::MapCheckReport check;
  bool certified = false;
};

Verdict check_written(const Args& a, const volmap::VolumeMapResult& r, const volmap::TetMeshData& input, const volmap::BoundaryMap& map) {
  Verdict v;
  v.written = volmap::read_tet_mesh(a.out_path);
  const volmap::TetMeshData written_src = r.refined ? volmap::read_tet_mesh(a.refined_path) : input;
  v.check = volmap_tools::naming_file(a.out_path, [&] { return volmap::check_map(written_src, v.written, &map); });
  v.certified = v.check.certified() && v.check.connectivity == volmap::ConnectivityMatch::Identical;
  return v;
}

// Why no map exists, when the run proved it: `infeasible` of the JSON (null when not proven).
nlohmann::json infeasibility_json(const volmap::VolumeMapResult& r) {
  if (r.feasibility.infeasible_with_any_refinement())
    return {{"scope", "any-refinement"},
            {"reason", "the boundary map encloses a non-positive volume: no injective map exists at any refinement"}};
  if (r.refined || r.infeasibility.empty()) return nullptr;
  nlohmann::json certificates = nlohmann::json::array();
  for (const auto& c : r.infeasibility) {
    std::vector<std::string> multipliers;
    for (const auto& m : c.multipliers) multipliers.push_back(m.str());
    nlohmann::json certificate = {{"kind", volmap::infeasibility_kind_name(c.kind)}, {"simplex", c.simplex}, {"tet", c.tet},
                                  {"constraint_tets", c.constraint_tets}, {"multipliers", multipliers}, {"text", volmap::describe(c)}};
    if (!c.boundary_face.empty()) certificate["boundary_face"] = c.boundary_face;
    if (!c.ring.empty()) certificate["ring"] = c.ring;
    certificates.push_back(std::move(certificate));
  }
  return {{"scope", "this-connectivity"},
          {"reason", "exact local certificate: no map with every tet positive exists at the input connectivity"},
          {"certificates", certificates}};
}

nlohmann::json result_json(const Args& a, const volmap::VolumeMapResult& r, const Verdict& v) {
  nlohmann::json stages = nlohmann::json::array();
  for (const auto& s : r.stages) {
    nlohmann::json stage = {{"name", s.name}, {"seconds", s.seconds}, {"nonpositive_after", s.nonpositive_after},
                            {"tets_after", s.tets_after}};
    if (!s.failure.empty()) stage["failure"] = s.failure;
    stages.push_back(stage);
  }
  nlohmann::json j{{"certified", v.certified},
                   {"certified_on", "the written files, read back (check_map)"},
                   {"method", a.method},
                   {"certified_by", r.certified_by},
                   {"start", r.start == volmap::StartMap::Radial ? "radial" : "tutte"},
                   {"restarted", r.restarted},
                   {"remeshed", r.remeshed},
                   {"input_tets", r.input_tets},
                   {"input_vertices", r.input_vertices},
                   {"output_tets", v.written.num_tets()},
                   {"output_vertices", v.written.num_vertices()},
                   {"growth", r.growth()},
                   {"refined", r.refined},
                   {"positive", v.check.output.positive},
                   {"zero", v.check.output.zero},
                   {"negative", v.check.output.negative},
                   {"boundary_exact", v.check.boundary_mismatches == 0},
                   {"chord_edges", r.feasibility.chord_edges.size()},
                   {"blocking_chord_edges", r.feasibility.blocking_chord_edges.size()},
                   {"chord_faces", r.feasibility.chord_faces.size()},
                   {"blocking_chord_faces", r.feasibility.blocking_chord_faces.size()},
                   {"fixed_nonpositive_tets", r.feasibility.fixed_nonpositive_tets.size()},
                   {"fixed_link_vertices", r.feasibility.fixed_link_vertices.size()},
                   {"boundary_volume_sign", r.feasibility.boundary_volume_sign},
                   {"chord_edges_split", r.chord_edges_split},
                   {"chord_faces_split", r.chord_faces_split},
                   {"chord_edges_removed", r.chord_edges_removed},
                   {"chord_faces_flipped", r.chord_faces_flipped},
                   {"chord_cone_patches", r.chord_cone_patches},
                   {"chord_splits_refused", r.chord_splits_refused},
                   {"growth_budget_escalations", r.growth_budget_escalations},
                   {"cone_search_widenings", r.cone_search_widenings},
                   {"cone_patches", r.cone_patches},
                   {"bad_tet_flips", r.bad_tet_flips},
                   {"seconds", r.seconds},
                   {"stages", stages}};
  if (nlohmann::json why = infeasibility_json(r); !why.is_null()) j["infeasible"] = std::move(why);
  return j;
}

void print_text_report(const Args& a, const volmap::VolumeMapResult& r, const Verdict& v) {
  std::printf("%s: %s (%zu tets, %zu non-positive, growth %.4f, %s, %.2f s)\n", a.out_path.c_str(),
              v.certified ? "certified injective" : "NOT injective", v.written.num_tets(), v.check.output.zero + v.check.output.negative,
              r.growth(), v.certified ? r.certified_by.c_str() : "-", r.seconds);
  if (r.feasibility.infeasible_with_any_refinement()) {
    std::printf("  the boundary map encloses a non-positive volume: no injective map exists at any refinement\n");
  } else if (!r.refined && !r.infeasibility.empty()) {
    std::printf("  infeasible at the input connectivity (exact local certificates):\n");
    for (const auto& c : r.infeasibility) std::printf("    %s\n", volmap::describe(c).c_str());
  } else if (!v.certified && a.refined_path.empty() && !a.no_refine) {
    std::printf("  refinement was off: give --refined-input <path> to allow chord splits and cone repair\n");
  }
  for (const auto& s : r.stages)
    std::printf("  %-22s %8.3f s  non-positive after: %zu  tets: %zu%s%s\n", s.name.c_str(), s.seconds, s.nonpositive_after, s.tets_after,
                s.failure.empty() ? "" : "  (failed, undone: ", s.failure.empty() ? "" : (s.failure + ")").c_str());
}

}  // namespace

int main(int argc, char** argv) {
  volmap_tools::reuse_freed_memory();
  CLI::App app{"volmap-map: certified volume map of a tet mesh onto a domain with a fixed boundary map", "volmap-map"};
  Args a;
  add_options(app, a);
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    const volmap::TimeBudget run_clock;
    volmap_tools::RunFiles files;
    volmap_tools::InputMeshes inputs("volmap-map", &a.json);
    const Outputs out = prepare_files(a, files);

    const volmap::TetMeshData input = volmap_tools::read_input_tet_mesh(inputs, a.in_path);
    volmap_tools::require_moderate_coordinates(input.xyz, a.in_path);
    const std::vector<double> initial_xyz = a.initial_path.empty() ? std::vector<double>{} : read_initial_map(inputs, a, input);
    const volmap::BoundaryMap map = read_boundary_map_arg(a, input, initial_xyz);

    volmap::VolumeMapOptions opt = mapping_options(a, /*refine=*/!a.no_refine && out.refined, run_clock.elapsed());
    opt.initial_xyz = initial_xyz;
    const volmap::VolumeMapResult r = volmap_tools::naming_file(a.in_path, [&] { return volmap::compute_volume_map(input, map, opt); });

    write_outputs(out, r, files);
    const Verdict v = check_written(a, r, input, map);
    const int code = v.certified ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed;
    if (a.json) {
      nlohmann::json j = result_json(a, r, v);
      if (!inputs.empty()) j["input_notes"] = inputs.json();
      return volmap_tools::print_json(std::move(j), code);
    }
    print_text_report(a, r, v);
    return code;
  }, &a.json);
}
