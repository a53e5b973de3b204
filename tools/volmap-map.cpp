// volmap-map — certified robust volume mapper (docs/mapping.md; issue 6), candidate-method contract:
//   volmap-map <in.mesh> <map.txt> <out.mesh> [--method ffm|tlc] [--refined-input path]
//              [--rationals path] [--max-growth 0.05] [--no-refine] [--time-limit s] [--threads n] [--json]
//              [--tlc-share 0.5] [--ffm-inner n] [--ffm-rest-first] [--no-local] [--no-kernel-descent]   (cascade tuning, see volume_map.hpp)
//              [--initial init.(mesh|vtk|vtu)]
// in.mesh may also be .vtk/.vtu/.msh/.ovm; its tets must be VOLMAP-positive (an input in the opposite
// convention, as Gmsh and OpenVolumeMesh files are, is refused with exit 2 and the sentence of
// describe_orientation: flip it first with volmap-tetmesh-check --fix). --initial starts from a given (possibly tangled)
// map instead of Tutte 3D: same vertex count and the same tets in the same order as the input, boundary
// vertices bit-identical to the prescribed map (else exit 2). A map positional of `-` takes the boundary
// map from the initial file's boundary vertices (requires --initial).
// out.mesh has the (refined) input's vertices and tets in the same order, boundary vertices bit-exactly
// at the map's doubles, every other coordinate printed with %.17g. Refinement (chord splits, cone
// repair) happens only when --refined-input is given (the refined source is written there; the pair
// has identical connectivity); without it the connectivity is fixed (as with --no-refine).
// --method ffm (default) runs the cascade of volmap/volume_map.hpp (Tutte or --initial → TLC → link-kernel →
// local FFM (Newton) on the bad region → global FFM with stall hand-over → local FFM);
// --method tlc runs only Tutte → TLC (Du et al. 2020 baseline, judged by the same exact check).
// Cone-repair refinement (B1) is not implemented yet: with --refined-input only B0 chord splits refine.
// Certification re-reads the written files and runs the exact check on exactly those numbers.
// When no map can exist, `infeasible` (JSON) says so: scope "any-refinement" (the boundary image
// encloses a non-positive volume) or "this-connectivity" with the exact local certificates of
// volmap/volume/infeasibility.hpp (kind, simplex, constraint tets, multipliers); exit 1 then.
// Exit: 0 certified; 1 ran but not injective (out.mesh is STILL written with the best map found, so
// it can be inspected; it must not be used as a valid map); 2 usage or bad input.
#include "support/input_mesh.hpp"
#include "support/tool_common.hpp"

#include <volmap/check/orientation.hpp>
#include <volmap/core/boundary_faces.hpp>
#include <volmap/io/io.hpp>
#include <volmap/predicates_rational.hpp>
#include <volmap/volume/volume_map.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  CLI::App app{"volmap-map: certified volume map of a tet mesh onto a domain with a fixed boundary map", "volmap-map"};
  std::string in_path, map_path, out_path, refined_path, rationals_path, initial_path, method = "ffm";
  double max_growth = 0.05, time_limit = 60;
  bool no_refine = false, json = false, no_quality = false;
  int threads = 0, ffm_inner = 0;
  double tlc_share = volmap::VolumeMapOptions{}.tlc_time_share;
  bool ffm_rest_first = false, no_local = false, no_kernel_descent = false;
  app.add_option("input", in_path, "source tet mesh (.mesh/.vtk/.vtu/.msh/.ovm, VOLMAP-positive)")->required();
  app.add_option("map", map_path, "boundary map `vid x y z` (0-based), or - to take it from --initial")->required();
  app.add_option("output", out_path, "output .mesh (same tets/vertices as the (refined) input)")->required();
  app.add_option("--method", method, "ffm (default: Tutte → FFM → repair) or tlc (Du et al. 2020 baseline)")
      ->check(CLI::IsMember({"ffm", "tlc"}));
  app.add_option("--refined-input", refined_path, "where to write the refined source; refinement (chord splits, cone repair) is enabled only with this path");
  app.add_option("--rationals", rationals_path, "also write the output coordinates as exact rationals (VOLMAP num/den)");
  app.add_option("--max-growth", max_growth, "tet growth budget of the cone repair (fraction of input tets)");
  app.add_flag("--no-refine", no_refine, "fixed connectivity (never refine)");
  app.add_flag("--no-quality", no_quality, "skip the validity-preserving quality pass");
  app.add_option("--time-limit", time_limit, "soft time limit in seconds (default 60; 0 = none: every stage then runs to its own iteration cap, which can take many minutes)");
  app.add_option("--threads", threads, "worker threads (0 = all cores)");
  app.add_option("--tlc-share", tlc_share, "cascade: fraction of the remaining time given to the first TLC stage")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--ffm-inner", ffm_inner, "cascade: L-BFGS iterations per FFM outer step (0 = default)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--ffm-rest-first", ffm_rest_first, "cascade: run FFM with the rest-shape reference before the regular tet");
  app.add_flag("--no-kernel-descent", no_kernel_descent, "cascade: skip the kernel-descent stages (exact single-vertex moves driven by the bad tets)");
  app.add_flag("--no-local", no_local, "cascade: skip the local FFM (Newton) stages on the bad region");
  app.add_option("--initial", initial_path, "start from this map (same vertices/tets as the input; boundary = the prescribed map) instead of Tutte 3D");
  app.add_flag("--json", json, "print one JSON object");
  return volmap_tools::run_tool(app, argc, argv, [&]() -> int {
    volmap_tools::InputMeshes inputs("volmap-map", &json);
    const volmap::TetMeshData input = inputs.read(in_path);
    const volmap::TetSignCounts input_signs =
        volmap::orient3d_tets(input.xyz.data(), input.num_vertices(), input.tets.data(), input.num_tets(), nullptr);
    if (input_signs.ok && (input_signs.negative > 0 || input_signs.zero > 0))
      throw volmap::Error(volmap::ErrorKind::BadInput, in_path, 0,
                          "the source mesh must be VOLMAP-positive: " + volmap::describe_orientation(input_signs));
    for (const std::string* output : {&out_path, &refined_path, &rationals_path})  // before the long run
      if (!output->empty()) volmap_tools::require_output_folder(*output);
    volmap::VolumeMapOptions opt;
    if (!initial_path.empty()) {
      const volmap::TetMeshData initial = inputs.read(initial_path);
      if (initial.num_vertices() != input.num_vertices() || initial.tets != input.tets)
        throw volmap::Error(volmap::ErrorKind::BadInput, initial_path, 0,
                            "the initial map must have the input's vertices and the same tets in the same order (" +
                                std::to_string(initial.num_vertices()) + " vertices / " + std::to_string(initial.num_tets()) + " tets vs " +
                                std::to_string(input.num_vertices()) + " / " + std::to_string(input.num_tets()) + ")");
      opt.initial_xyz = initial.xyz;
    }
    volmap::BoundaryMap map;
    if (map_path == "-") {
      if (initial_path.empty()) throw volmap::Error(volmap::ErrorKind::BadInput, "", 0, "map `-` needs --initial (the boundary map is taken from it)");
      for (std::uint32_t v : volmap::boundary_vertex_ids(input)) {
        map.vids.push_back(v);
        for (int i = 0; i < 3; ++i) map.xyz.push_back(opt.initial_xyz[3 * std::size_t(v) + i]);
      }
    } else {
      map = volmap::read_boundary_map(map_path);
      volmap::validate_boundary_map(map, input, map_path);
    }
    opt.method = method == "tlc" ? volmap::MapMethod::Tlc : volmap::MapMethod::Ffm;
    opt.allow_refinement = !no_refine && !refined_path.empty();
    opt.max_growth = max_growth;
    opt.time_limit_seconds = time_limit;
    opt.max_threads = threads;
    opt.quality_pass = !no_quality;
    opt.tlc_time_share = tlc_share;
    opt.ffm_max_lbfgs_iterations = ffm_inner;
    opt.ffm_rest_shape_first = ffm_rest_first;
    opt.local_untangle = !no_local;
    opt.kernel_descent = !no_kernel_descent;
    const volmap::VolumeMapResult r = volmap::compute_volume_map(input, map, opt);

    volmap::TetMeshData out = r.source;
    out.xyz = r.target_xyz;
    volmap::write_medit(out_path, out);
    if (r.refined) volmap::write_medit(refined_path, r.source);
    if (!rationals_path.empty()) {
      std::vector<volmap::Rational> q(out.xyz.size());
      for (std::size_t i = 0; i < q.size(); ++i) q[i] = volmap::Rational(out.xyz[i]);
      volmap::write_rationals(rationals_path, q);
    }

    // Certify exactly what was written.
    const volmap::TetMeshData written = volmap::read_medit(out_path);
    const volmap::TetMeshData written_src = r.refined ? volmap::read_medit(refined_path) : input;
    bool same_connectivity = written.tets == written_src.tets && written.num_vertices() == written_src.num_vertices();
    bool boundary_exact = true;
    for (std::size_t k = 0; k < map.size() && boundary_exact; ++k)
      for (int i = 0; i < 3; ++i)
        if (written.xyz[3 * std::size_t(map.vids[k]) + i] != map.xyz[3 * k + i]) boundary_exact = false;
    const auto out_signs = volmap::orient3d_tets(written.xyz.data(), written.num_vertices(), written.tets.data(), written.num_tets(), nullptr);
    const auto src_signs = volmap::orient3d_tets(written_src.xyz.data(), written_src.num_vertices(), written_src.tets.data(), written_src.num_tets(), nullptr);
    const bool certified = same_connectivity && boundary_exact && out_signs.ok && src_signs.ok && out_signs.zero == 0 &&
                           out_signs.negative == 0 && src_signs.zero == 0 && src_signs.negative == 0;

    if (json) {
      nlohmann::json stages = nlohmann::json::array();
      for (const auto& s : r.stages) {
        nlohmann::json stage = {{"name", s.name}, {"seconds", s.seconds}, {"nonpositive_after", s.nonpositive_after},
                                {"tets_after", s.tets_after}};
        if (!s.failure.empty()) stage["failure"] = s.failure;
        stages.push_back(stage);
      }
      nlohmann::json j{{"ok", certified},
                       {"certified", certified},
                       {"method", method},
                       {"certified_by", r.certified_by},
                       {"input_tets", r.input_tets},
                       {"input_vertices", r.input_vertices},
                       {"output_tets", written.num_tets()},
                       {"output_vertices", written.num_vertices()},
                       {"growth", r.growth()},
                       {"refined", r.refined},
                       {"positive", out_signs.positive},
                       {"zero", out_signs.zero},
                       {"negative", out_signs.negative},
                       {"boundary_exact", boundary_exact},
                       {"chord_edges", r.feasibility.chord_edges.size()},
                       {"blocking_chord_edges", r.feasibility.blocking_chord_edges.size()},
                       {"chord_faces", r.feasibility.chord_faces.size()},
                       {"blocking_chord_faces", r.feasibility.blocking_chord_faces.size()},
                       {"fixed_nonpositive_tets", r.feasibility.fixed_nonpositive_tets.size()},
                       {"fixed_link_vertices", r.feasibility.fixed_link_vertices.size()},
                       {"boundary_volume_sign", r.feasibility.boundary_volume_sign},
                       {"chord_edges_split", r.chord_edges_split},
                       {"chord_faces_split", r.chord_faces_split},
                       {"cone_patches", r.cone_patches},
                       {"seconds", r.seconds},
                       {"stages", stages}};
      if (!inputs.empty()) j["input_notes"] = inputs.json();
      if (r.feasibility.infeasible_with_any_refinement())
        j["infeasible"] = {{"scope", "any-refinement"},
                           {"reason", "the boundary map encloses a non-positive volume: no injective map exists at any refinement"}};
      else if (!r.refined && !r.infeasibility.empty()) {
        nlohmann::json certificates = nlohmann::json::array();
        for (const auto& c : r.infeasibility) {
          std::vector<std::string> multipliers;
          for (const auto& m : c.multipliers) multipliers.push_back(m.str());
          certificates.push_back({{"kind", volmap::infeasibility_kind_name(c.kind)}, {"simplex", c.simplex}, {"tet", c.tet},
                                  {"constraint_tets", c.constraint_tets}, {"multipliers", multipliers}, {"text", volmap::describe(c)}});
        }
        j["infeasible"] = {{"scope", "this-connectivity"},
                           {"reason", "exact local certificate: no map with every tet positive exists at the input connectivity"},
                           {"certificates", certificates}};
      }
      std::printf("%s\n", j.dump().c_str());
    } else {
      std::printf("%s: %s (%zu tets, %zu non-positive, growth %.4f, %s, %.2f s)\n", out_path.c_str(),
                  certified ? "certified injective" : "NOT injective", written.num_tets(), out_signs.zero + out_signs.negative,
                  r.growth(), certified ? r.certified_by.c_str() : "-", r.seconds);
      if (r.feasibility.infeasible_with_any_refinement())
        std::printf("  the boundary map encloses a non-positive volume: no injective map exists at any refinement\n");
      else if (!r.refined && !r.infeasibility.empty()) {
        std::printf("  infeasible at the input connectivity (exact local certificates):\n");
        for (const auto& c : r.infeasibility) std::printf("    %s\n", volmap::describe(c).c_str());
      }
      else if (!certified && refined_path.empty() && !no_refine)
        std::printf("  refinement was off: give --refined-input <path> to allow chord splits and cone repair\n");
      for (const auto& s : r.stages)
        std::printf("  %-22s %8.3f s  non-positive after: %zu  tets: %zu%s%s\n", s.name.c_str(), s.seconds, s.nonpositive_after, s.tets_after,
                    s.failure.empty() ? "" : "  (failed, undone: ", s.failure.empty() ? "" : (s.failure + ")").c_str());
    }
    return certified ? volmap_tools::kExitOk : volmap_tools::kExitCheckFailed;
  }, &json);
}
