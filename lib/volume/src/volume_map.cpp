// volume_map.cpp — the volmap-map pipeline (see volmap/volume_map.hpp for conventions). Section marks (§N) refer to docs/mapping.md.
#include <volmap/volume/volume_map.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/volume/chord_split.hpp>
#include <volmap/volume/cone_repair.hpp>
#include <volmap/core/error.hpp>
#include <volmap/volume/ffm.hpp>
#include <volmap/predicates.hpp>
#include <volmap/volume/tlc.hpp>
#include <volmap/volume/tutte3d.hpp>

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

namespace volmap {

namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

VolumeMapResult compute_volume_map(const TetMeshData& input, const BoundaryMap& map, const VolumeMapOptions& options) {
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  // With refinement allowed, the untangling cascade gets only a share of the time limit so that B1
  // cone repair (and the short untangling rounds after it) run while time is left.
  const bool b1_rounds = options.allow_refinement && options.method == MapMethod::Ffm;
  double phase_limit = options.time_limit_seconds;
  if (b1_rounds && options.time_limit_seconds > 0) phase_limit = options.refine_time_share * options.time_limit_seconds;
  auto remaining = [&]() -> double {
    if (phase_limit <= 0) return 0;
    return std::max(1e-3, phase_limit - elapsed());
  };
  auto out_of_time = [&] { return phase_limit > 0 && elapsed() >= phase_limit; };

  std::unique_ptr<tbb::global_control> thread_limit;
  if (options.max_threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(options.max_threads));
  VolumeMapResult r;
  const std::size_t nv = input.num_vertices(), nt = input.num_tets();
  r.input_tets = nt;
  r.input_vertices = nv;
  if (!(options.tlc_time_share >= 0 && options.tlc_time_share <= 1))
    throw Error(ErrorKind::BadInput, "", 0, "tlc_time_share must be in [0, 1]");
  if (nt == 0) throw Error(ErrorKind::BadInput, "", 0, "the mesh has no tets");
  if (input.tets.size() != 4 * nt || input.xyz.size() != 3 * nv) throw Error(ErrorKind::BadInput, "", 0, "inconsistent mesh arrays");
  for (std::uint32_t v : input.tets)
    if (v >= nv) throw Error(ErrorKind::BadInput, "", 0, "tet vertex id out of range");

  // Boundary: the map must prescribe exactly the boundary vertices.
  const std::vector<std::uint32_t> bverts = boundary_vertex_ids(input);
  r.on_boundary.assign(nv, 0);
  for (auto v : bverts) r.on_boundary[v] = 1;
  r.target_xyz.assign(3 * nv, 0.0);
  std::vector<std::uint8_t> seen(nv, 0);
  for (std::size_t k = 0; k < map.size(); ++k) {
    const std::uint32_t v = map.vids[k];
    if (v >= nv) throw Error(ErrorKind::BadInput, "", 0, "map vertex id " + std::to_string(v) + " out of range");
    if (!r.on_boundary[v]) throw Error(ErrorKind::BadInput, "", 0, "map vertex " + std::to_string(v) + " is not a boundary vertex");
    if (seen[v]) throw Error(ErrorKind::BadInput, "", 0, "map vertex " + std::to_string(v) + " appears twice");
    seen[v] = 1;
    for (int i = 0; i < 3; ++i) r.target_xyz[3 * std::size_t(v) + i] = map.xyz[3 * k + i];
  }
  for (auto v : bverts)
    if (!seen[v]) throw Error(ErrorKind::BadInput, "", 0, "boundary vertex " + std::to_string(v) + " has no prescribed position");
  const bool has_initial = !options.initial_xyz.empty();
  if (has_initial) {
    if (options.initial_xyz.size() != 3 * nv)
      throw Error(ErrorKind::BadInput, "", 0, "the initial map has " + std::to_string(options.initial_xyz.size() / 3) + " vertices, the mesh " + std::to_string(nv));
    for (auto v : bverts)
      for (int i = 0; i < 3; ++i)
        if (options.initial_xyz[3 * std::size_t(v) + i] != r.target_xyz[3 * std::size_t(v) + i])
          throw Error(ErrorKind::BadInput, "", 0, "the initial map moves boundary vertex " + std::to_string(v) + " away from its prescribed position");
    for (std::size_t v = 0; v < nv; ++v)
      for (int i = 0; i < 3; ++i)
        if (!std::isfinite(options.initial_xyz[3 * v + i]))
          throw Error(ErrorKind::BadInput, "", 0, "the initial map has a non-finite coordinate at vertex " + std::to_string(v));
    r.target_xyz = options.initial_xyz;
  }
  if (count_nonpositive(input.xyz, input.tets) != 0)
    throw Error(ErrorKind::BadInput, "", 0, "the source mesh has tets with orient3d <= 0 (not VOLMAP-positive)");

  r.source = input;
  // Every stage is judged by the exact count; a stage that makes it worse is undone (best kept).
  std::vector<double> best_xyz;
  std::size_t best_bad = std::size_t(-1);
  std::size_t best_tets = 0;
  auto stage_done = [&](const std::string& name, double t0) {
    VolumeMapStage s;
    s.name = name;
    s.seconds = elapsed() - t0;
    s.nonpositive_after = count_nonpositive(r.target_xyz, r.source.tets);
    r.stages.push_back(s);
    if (best_tets == r.source.num_tets() && best_bad != std::size_t(-1) && s.nonpositive_after > best_bad) {
      r.target_xyz = best_xyz;  // undo
      return best_bad;
    }
    best_xyz = r.target_xyz;
    best_bad = s.nonpositive_after;
    best_tets = r.source.num_tets();
    return s.nonpositive_after;
  };

  // §3 feasibility.
  double t0 = elapsed();
  r.feasibility = analyze_feasibility(input, r.on_boundary, r.target_xyz);
  r.stages.push_back({"feasibility", elapsed() - t0, 0});

  // §4 B0: split the blocking chords.
  const std::size_t growth_budget = std::size_t(options.max_growth * double(nt));
  if (options.allow_refinement && (!r.feasibility.blocking_chord_edges.empty() || !r.feasibility.blocking_chord_faces.empty())) {
    t0 = elapsed();
    const ChordSplitResult cs = split_chords(r.source, r.on_boundary, r.feasibility.blocking_chord_edges, r.feasibility.blocking_chord_faces);
    r.chord_edges_split = cs.edges_split;
    r.chord_faces_split = cs.faces_split;
    r.refined = cs.vertices_added > 0;
    r.target_xyz.resize(3 * r.source.num_vertices(), 0.0);
    r.stages.push_back({"chord-split", elapsed() - t0, 0});
  }

  // §2 Tutte 3D, or the given initial map (chord-split vertices placed by a local Laplacian).
  t0 = elapsed();
  std::string start_name = "tutte3d";
  if (has_initial) {
    start_name = "initial";
    if (r.source.num_vertices() > nv) {
      std::vector<std::uint8_t> keep(r.source.num_vertices(), 0);
      std::fill(keep.begin(), keep.begin() + std::ptrdiff_t(nv), std::uint8_t(1));
      solve_uniform_laplacian(keep.size(), unique_tet_edges(r.source), keep, r.target_xyz);
    }
  } else {
    solve_uniform_laplacian(r.on_boundary.size(), unique_tet_edges(r.source), r.on_boundary, r.target_xyz);
  }
  std::size_t bad = stage_done(start_name, t0);
  if (bad == 0) r.certified_by = start_name;
  // A boundary image enclosing a non-positive volume (mirrored map): no map exists at any
  // refinement (the target volumes sum to that volume), so no untangler is run.
  if (r.feasibility.infeasible_with_any_refinement()) {
    r.nonpositive = bad;
    r.certified = false;
    r.certified_by.clear();
    r.seconds = elapsed();
    return r;
  }

  // §6 TLC: the whole method with --method tlc (the published baseline), the first untangler of the
  // default cascade otherwise (measured on G1 bone/duck: converges faster than FFM from Tutte).
  auto link_kernel = [&]() {
    if (bad == 0 || options.method != MapMethod::Ffm || out_of_time()) return;
    t0 = elapsed();
    relocate_into_link_kernels(r.source.tets, r.on_boundary, r.target_xyz, 50);
    bad = stage_done("link-kernel", t0);
    if (bad == 0) r.certified_by = "link-kernel";
  };
  // Local FFM (Newton) on the region of the remaining non-positive tets, the rest frozen.
  auto local_ffm = [&](double share) {
    if (bad == 0 || options.method != MapMethod::Ffm || !options.local_untangle || out_of_time()) return;
    t0 = elapsed();
    LocalUntangleOptions lo;
    const double rem = remaining();
    lo.time_limit_seconds = rem > 0 ? share * rem : 0;
    ffm_local_untangle(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, lo);
    bad = stage_done("ffm-local", t0);
    if (bad == 0) r.certified_by = "ffm-local";
  };
  // B1 cone repair of every cluster, within what is left of the growth budget and half the time left.
  auto run_cone_repair = [&](const std::string& name) {
    t0 = elapsed();
    ConeRepairOptions co;
    const long long used = (long long)r.source.num_tets() - (long long)nt;
    co.max_added_tets = std::size_t(std::max(1LL, (long long)growth_budget - used));
    co.time_limit_seconds = remaining() > 0 ? 0.5 * remaining() : 0;
    const ConeRepairResult cr = cone_repair(r.source, r.on_boundary, r.target_xyz, co);
    r.cone_patches += cr.patches;
    if (cr.patches > 0) r.refined = true;
    bad = stage_done(name, t0);
    if (bad == 0) r.certified_by = "cone-repair";
    return cr;
  };
  // TLC with a 100× smaller lift (alpha 1e-8) from the current map, given `share` of the time left.
  auto small_lift_tlc = [&](const std::string& name, double share) {
    t0 = elapsed();
    TlcOptions t2;
    t2.alpha_ratio = 1e-8;
    const double rem = remaining();
    t2.time_limit_seconds = rem > 0 ? share * rem : 0;
    tlc_untangle(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, t2);
    bad = stage_done(name, t0);
    if (bad == 0) r.certified_by = name;
    link_kernel();
  };
  // Early B1: as soon as a cascade stage leaves few non-positive tets, try the cone repair (it leaves
  // a cluster untouched when it fails) instead of spending the cascade's whole time share on the last
  // few tets (bone cube/star: 9.8 s → under 2 s). A failing attempt can cost seconds on large meshes,
  // so it is not repeated at an unchanged count.
  std::size_t early_b1_stalled_at = std::size_t(-1);  // bad count of the last attempt that patched nothing
  auto try_b1 = [&](const char* after) {
    if (bad == 0 || !b1_rounds || bad > options.early_repair_max_bad || bad >= early_b1_stalled_at) return;
    const ConeRepairResult cr = run_cone_repair(std::string("cone-repair-after-") + after);
    if (cr.patches == 0 || cr.failed_clusters > 0) early_b1_stalled_at = bad;  // retry only after progress elsewhere
  };
  // With refinement, once few tets are left the global FFM stages are skipped: the B1 rounds (cone
  // repair ↔ local FFM) finish such maps, while global FFM from a nearly valid map cost 2–7 s and was
  // undone every time we looked (G1 ramses/gargoyle/camile_hand star: hundreds to 15k bad after it).
  auto few_left_for_b1 = [&] { return b1_rounds && bad <= options.early_repair_max_bad; };
  if (bad > 0 && !out_of_time()) {
    t0 = elapsed();
    TlcOptions to;
    const double rem = remaining();
    to.time_limit_seconds = options.method == MapMethod::Tlc ? rem : (rem > 0 ? options.tlc_time_share * rem : 0);
    tlc_untangle(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, to);
    bad = stage_done("tlc", t0);
    if (bad == 0) r.certified_by = "tlc";
    link_kernel();
    try_b1("tlc");
    // Cascade only: a second TLC round with a 100× smaller lift from the stalled result.
    // Kept with few tets left too: its moves at an equal count are accepted and change the state the
    // cone repair sees (G1 ramses star: 1 → 1 bad, then B1 certified; skipped, B1 stalled at 2).
    if (bad > 0 && options.method == MapMethod::Ffm && !out_of_time()) {
      small_lift_tlc("tlc-small-alpha", 0.3);
      try_b1("tlc-small-alpha");
    }
    local_ffm(0.25);
    try_b1("ffm-local");
  }
  // §5 FFM (regular reference, then rest shape), each followed by the link-kernel pre-step.
  if (bad > 0 && options.method == MapMethod::Ffm && !few_left_for_b1()) {
    std::vector<ReferenceShape> refs = {ReferenceShape::RegularTet, ReferenceShape::RestShape};
    if (options.ffm_rest_shape_first) std::swap(refs[0], refs[1]);
    for (ReferenceShape ref : refs) {
      if (bad == 0 || out_of_time()) break;
      t0 = elapsed();
      FfmOptions fo;
      fo.reference = ref;
      const double rem = remaining();
      fo.time_limit_seconds = rem > 0 && options.local_untangle ? 0.6 * rem : rem;
      fo.stall_outer_iterations = options.local_untangle ? 40 : 0;
      if (options.ffm_max_lbfgs_iterations > 0) fo.max_lbfgs_iterations = options.ffm_max_lbfgs_iterations;
      ffm_untangle(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, fo);
      const std::string name = ref == ReferenceShape::RegularTet ? "ffm-regular" : "ffm-rest";
      bad = stage_done(name, t0);
      if (bad == 0) r.certified_by = name;
      link_kernel();
      try_b1(ref == ReferenceShape::RegularTet ? "ffm-regular" : "ffm-rest");
      local_ffm(0.25);
      try_b1("ffm-local");
    }
  }

  // §7 B1 cone repair of what remains, in rounds: repair → link-kernel relocation → local FFM on the
  // repaired mesh (its connectivity changed) → repair again; when all stall, a small-lift TLC once,
  // then a global FFM once. The net tet growth of B0 + B1 stays within max_growth · input tets.
  if (bad > 0 && b1_rounds) {
    phase_limit = options.time_limit_seconds;
    bool global_tried = false, tlc_retried = false;
    for (int round = 0; round < 8 && bad > 0 && !out_of_time(); ++round) {
      const std::size_t bad_before = bad;
      const ConeRepairResult cr = run_cone_repair("cone-repair");
      link_kernel();
      if (bad == 0 || out_of_time()) break;
      // The repaired mesh is untangled locally first (the rest of the map is valid and stays
      // frozen); a global FFM (it may wander far from the nearly valid map) only once, when the
      // local solve and the repair both stall.
      const std::size_t bad_local = bad;
      local_ffm(0.3);
      if (bad == 0 || out_of_time()) break;
      if (cr.patches == 0 && bad >= bad_before && bad >= bad_local) {
        if (global_tried) break;  // nothing moves any more
        // Stalled: first a short TLC with a small lift over the whole mesh (moves at an equal count
        // are kept and give the cone repair a different state: G1 ramses star, 1 bad left), then
        // once a global FFM.
        if (!tlc_retried) {
          tlc_retried = true;
          small_lift_tlc("tlc-after-repair", 0.25);
          continue;
        }
        global_tried = true;
        t0 = elapsed();
        FfmOptions fo;
        fo.reference = ReferenceShape::RestShape;
        fo.stall_outer_iterations = 40;
        const double rem = remaining();
        fo.time_limit_seconds = rem > 0 ? 0.5 * rem : 0;
        ffm_untangle(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, fo);
        bad = stage_done("ffm-after-repair", t0);
        if (bad == 0) r.certified_by = "ffm-after-repair";
        link_kernel();
      }
    }
  }

  // Quality pass (never breaks validity: kept only when the exact check passes).
  // Not for --method tlc: the baseline reproduces the published method, not TLC + our quality pass.
  if (bad == 0 && options.quality_pass && options.method == MapMethod::Ffm && !out_of_time()) {
    t0 = elapsed();
    double quality_seconds = std::max(options.quality_min_seconds, options.quality_time_ratio * t0);
    if (remaining() > 0) quality_seconds = std::min(quality_seconds, remaining());
    ffm_quality_pass(r.source.xyz, r.source.tets, r.on_boundary, r.target_xyz, ReferenceShape::RestShape,
                     options.quality_iterations, quality_seconds);
    bad = stage_done("quality", t0);
  }

  r.nonpositive = count_nonpositive(r.target_xyz, r.source.tets);
  r.certified = r.nonpositive == 0 && count_nonpositive(r.source.xyz, r.source.tets) == 0;
  if (!r.certified) r.certified_by.clear();
  r.seconds = elapsed();
  return r;
}

}  // namespace volmap
