// volmap/volume/volume_map.hpp — the certified robust volume mapper behind `volmap-map` (docs/mapping.md).
// Pipeline (what is implemented): exact feasibility analysis (§3) and local infeasibility
// certificates (§10; at fixed connectivity a certificate ends the run) → B0 chord splitting of the
// blocking chords (§4, when refinement is allowed) → Tutte 3D (§2, volmap/tutte3d.hpp; or a given
// initial map) → TLC (§6; the whole method with MapMethod::Tlc) → [cascade only] link-kernel
// relocation (§7 pre-step) → TLC with alpha 1e-8 → local FFM (Newton) on the bad region →
// global FFM with regular then rest reference shapes (§5), each followed by link-kernel relocation
// and local FFM → [with refinement: bad-tet flips (§8 step 8) and B1 cone repair (§7) tried after
// every stage that leaves few bad tets, global FFM skipped then] rounds of B1 → link-kernel →
// bad-tet flips → local FFM (small-lift TLC, then global FFM, once each when they stall) →
// validity-preserving quality pass (§5, cascade only). In the
// cascade every link-kernel and local-FFM stage that leaves bad tets is followed by the kernel
// descent (§10). Uncertified runs get a restart from the other start (§8 step 10) and, with
// refinement and a remesher, the whole pipeline again on a new interior (§8 step 11); a result
// that grew the input gets fewer tets where a fill on the same points is valid in both spaces
// (§8 step 14).
// The stages run on one MapState (map_state.hpp, map_stages.hpp); each is judged by the exact count
// of non-positive tets and undone when it makes it worse (StageJudge). A result is certified only
// when check_map (the exact check of the check wing) certifies the returned arrays.
// Conventions: flat TetMeshData, VOLMAP-positive source tets; boundary vertices of the result are
// bit-identical to the map's doubles; with refinement the source is refined only in the interior,
// original vertex ids 0..nv−1 are kept and new vertices appended (the tets of a refined source come
// in no particular order).
#pragma once

#include <volmap/volume/feasibility.hpp>
#include <volmap/volume/infeasibility.hpp>
#include <volmap/volume/interior_remesh.hpp>
#include <volmap/core/mesh_data.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace volmap {

enum class MapMethod { Ffm, Tlc };
enum class StartMap { Tutte, Radial, Fewest };

struct VolumeMapOptions {
  MapMethod method = MapMethod::Ffm;
  bool allow_refinement = true;
  double max_growth = 0.05;        // tets added by B0 + B1 / input tets: the budget B1 patches aim for
  // The budget is a target, not a wall: when a B1 round of the repair phase refuses a patch because
  // it exceeds the budget and non-positive tets remain, the budget grows (doubling, at least 16 tets
  // above what is used) up to this fraction of the input tets, and the round is repeated. A
  // certified map that grew beats an uncertified one.
  double max_growth_last_resort = 0.5;
  double time_limit_seconds = 0;   // 0 = none (soft: checked between and inside stages)
  // Cascade: the stages' time shares are taken from min(time_limit_seconds, this) (0 = the whole limit). A
  // longer limit leaves the planned stages as they are and gives the extra time to further judged
  // rounds of the last phase: more time never ends with more non-positive tets.
  double planning_horizon_seconds = 60;
  bool quality_pass = true;
  int quality_iterations = 300;
  // The quality pass may use at most max(quality_min_seconds, quality_time_ratio × the time spent
  // before it), and never more than the time limit leaves.
  double quality_min_seconds = 0.25;
  double quality_time_ratio = 0.25;
  // ... and stops at the first L-BFGS iteration lowering the energy by less than this fraction of it
  // (0: only the iteration cap and the time share stop it).
  double quality_relative_decrease = 1e-4;
  int max_threads = 0;             // 0 = TBB default; 1 = one core (benchmarks)
  // Cascade (MapMethod::Ffm): the fraction of the remaining time given to the first TLC stage (the
  // small-lift TLC round then gets 0.3 of what is left, FFM the rest). MapMethod::Tlc gives TLC the
  // whole budget.
  double tlc_time_share = 0.5;
  // With refinement allowed (and a time limit): the fraction of the time limit the untangling cascade
  // may use before the B1 cone-repair rounds start (they may use the rest).
  double refine_time_share = 0.5;
  // With refinement allowed: after each cascade stage that leaves at most this many non-positive
  // tets, B1 cone repair is tried at once (a failed attempt changes nothing), and the global FFM
  // stages are skipped.
  std::size_t early_repair_max_bad = 200;
  // With refinement allowed: a TLC stage hands over to that repair once its double count of
  // non-positive tets is at most early_repair_max_bad and has not reached a new minimum for this
  // many energy evaluations (0 = TLC runs to convergence or its time share).
  long tlc_stall_evaluations = 150;
  // Cascade: exact local moves (link kernel, kernel descent) are tried as a finish of TLC's iterate
  // each time its double count of non-positive tets reaches a new low within 1..this (0 = never).
  // Larger is faster and leaves a rougher map for the quality pass (docs/mapping.md §6).
  std::size_t tlc_finish_max_bad = 50;
  // Without refinement: when the cascade's untangling phase leaves at most this many non-positive
  // tets, the global FFM stages give way to local rounds (small-lift TLC, then local FFM on what is
  // left, repeated while they make progress; docs/mapping.md §10). 0 = always the global stages.
  std::size_t local_rounds_max_bad = 200;
  int ffm_max_lbfgs_iterations = 0;    // L-BFGS iterations per FFM outer step; 0 = FfmOptions default
  bool ffm_rest_shape_first = false;   // FFM stages: rest-shape reference before the regular tet
  // Local FFM (Newton, rest of the mesh frozen) on the region of the remaining non-positive tets,
  // run after each global untangling stage that stops short of certification (cascade only).
  bool local_untangle = true;
  // With refinement: the B1 rounds run local FFM on what a repair round left only when at most this
  // many non-positive tets are left (docs/mapping.md §8 step 8: above that it lowered the count in
  // none of 362 calls over the thin_coarse, coarse and surfaces sets).
  std::size_t round_local_max_bad = 5;
  // Kernel descent (§10) after every link-kernel and local FFM stage that leaves non-positive tets
  // (cascade only).
  bool kernel_descent = true;
  // With refinement: flips that remove non-positive tets without a new vertex (bad_tet_flip.hpp)
  // before each B1 repair attempt.
  bool bad_tet_flips = true;
  // Cascade without initial_xyz: the starting map (§2). Tutte: Tutte 3D. Radial: the radial start
  // (radial_start.hpp; Tutte 3D when the boundary image has no verified strict kernel point).
  // Fewest: Tutte, and when the boundary image is not convex also the radial start; the one with
  // fewer exactly non-positive tets is kept (the radial start on a tie: the judge keeps a stage that
  // does not make the count worse).
  StartMap start = StartMap::Fewest;
  // Cascade with StartMap::Fewest when both starts were computed (a non-convex boundary image that
  // Tutte 3D does not map validly) and a time limit is set: the run from the kept start may use
  // this fraction of the limit; when it ends uncertified (and no exact certificate proves the case
  // impossible), a second run from the other start gets the rest, and the certified run, else the
  // one with fewer non-positive tets, is returned. Without a time limit both run to their caps.
  // On a convex image (Tutte alone starts) the first run keeps the whole limit, and the radial start
  // gets what it leaves when it ends uncertified with at least a tenth of the limit left.
  // 1 = never restart.
  double restart_share = 0.5;
  // With refinement: a remesher of the source's interior (interior_remesh.hpp; empty = none). When
  // set, the runs from the input get remesh_share of the time limit; when they end uncertified
  // (and no certificate rules out every map) with at least a tenth of the limit left, the remeshed
  // source, once interior_remesh_problem accepts it, is mapped with the time left (from Tutte 3D;
  // the remesher itself may take at most four fifths of the time left, so that its source can be
  // mapped),
  // and the certified run, else the one with fewer non-positive tets, is returned. A remesh that
  // fails or is refused hands the time left to one more run from where the runs from the input
  // stopped (their source and map as its input and initial map, within what is left of the growth
  // budgets). Growth and the feasibility report always refer to the input (docs/mapping.md §8
  // step 11).
  InteriorRemesher remesh_interior;
  double remesh_share = 0.5;
  // Cascade with refinement, the last resort (docs/mapping.md §8 step 12): when ∂M is star-shaped in the
  // source and in the map's image (star_shaped_boundary.hpp), every run above gets 95 % of the time
  // limit, and if they end uncertified, the whole mesh becomes one cone patch from a kernel point
  // (cone_repair.hpp, whole_mesh_cone): a certified map of poor quality, within
  // max_growth_last_resort (certified_by "whole-mesh-cone", stage "whole-mesh-cone"). The patch
  // may take what is left of the limit, at least the 5 % held back and at least a second (its
  // re-insertions stop there).
  bool whole_mesh_cone = true;
  // With refinement (MapMethod::Ffm), when the runs grew the mesh or ended uncertified: fewer tets
  // (docs/mapping.md §8 step 14). On inputs of at most boundary_fill_max_tets tets a new
  // tetrahedralisation of ∂M valid in both spaces with fewer tets is searched (boundary_fill.hpp:
  // on the input's vertices at the images the map or the certified map gives them, the certified
  // map's added points optional, or one interior point in ∂M's kernels or at a tet centroid) and
  // replaces the result (certified_by "boundary-fill", stage "boundary-fill"); then, on a certified
  // result of any size, the vertices refinement added whose link has a fill with fewer tets valid in
  // both spaces are taken back (vertex_removal.hpp, stage "vertex-removal"), and a small input whose
  // removals took tets back gets the fill search again; last, a certified result that still grew
  // loses the interior edges of degree 3 whose 3-2 flip is valid in both spaces
  // (edge_removal_fewer_tets.hpp, stage "edge-removal"). Every change is kept only when check_map
  // certifies it.
  bool fewer_tets = true;
  std::size_t boundary_fill_max_tets = 2000;
  // Starting map instead of Tutte 3D: 3 doubles per INPUT vertex (possibly tangled). Its boundary
  // entries must equal the map's doubles bit-exactly (else Error(BadInput)). With refinement, the
  // chord-split vertices start at the average of their neighbours (local uniform Laplacian).
  std::vector<double> initial_xyz;
};

struct VolumeMapStage {
  std::string name;
  double seconds = 0;
  std::size_t nonpositive_after = 0;  // exact count after the stage
  std::size_t tets_after = 0;         // source tets after the stage (growth per stage)
  std::string failure;                // non-empty when the stage threw: its work was undone
};

struct VolumeMapResult {
  TetMeshData source;               // the (possibly refined) source mesh
  std::vector<double> target_xyz;   // 3 per vertex of `source`
  std::vector<std::uint8_t> locked;  // 1 per vertex of `source`: the boundary (targets prescribed)
  bool certified = false;           // check_map certified (source, target_xyz) against the map
  bool refined = false;             // source != input
  std::size_t nonpositive = 0;      // exact count at the end
  std::size_t input_tets = 0, input_vertices = 0;
  std::size_t chord_edges_split = 0, chord_faces_split = 0, cone_patches = 0;
  std::size_t chord_edges_removed = 0, chord_faces_flipped = 0;  // B0 flips (no new vertex)
  std::size_t chord_cone_patches = 0;                              // B0 cone patches (one new vertex each)
  std::size_t chord_splits_refused = 0;                            // B0 simplices with no verified split point (left)
  std::size_t bad_tet_flips = 0;                                   // flips that removed non-positive tets (bad_tet_flip.hpp)
  std::size_t growth_budget_escalations = 0;                       // times B1's budget grew (max_growth_last_resort)
  std::size_t cone_search_widenings = 0;  // times B1's region search was widened (ConeRepairOptions::search_escalations)
  std::string certified_by;         // stage that produced the certified map
  StartMap start = StartMap::Tutte;  // the starting map this result was untangled from
  // StartMap::Fewest: the start a restart would use (the one not kept; Radial when Tutte alone
  // started on a convex image)
  std::optional<StartMap> other_start;
  bool restarted = false;            // two runs (see restart_share); stages lists both, "restart" between
  bool remeshed = false;             // the result maps the remeshed source (stage "remesh" before its runs)
  FeasibilityReport feasibility;    // on the input
  // Exact local certificates that no strictly positive map exists at the input connectivity
  // (infeasibility.hpp, each verified). Without refinement a non-empty list ends the run before
  // any untangler (the result is then not certified, and nothing else could be).
  std::vector<InfeasibilityCertificate> infeasibility;
  std::vector<VolumeMapStage> stages;
  double seconds = 0;
  double growth() const { return input_tets ? double(source.num_tets()) / double(input_tets) - 1.0 : 0.0; }
};

// Throws Error(BadInput) when the map does not match the mesh's boundary or a source tet is not
// strictly positive.
VolumeMapResult compute_volume_map(const TetMeshData& source, const BoundaryMap& map, const VolumeMapOptions& options = {});

}  // namespace volmap
