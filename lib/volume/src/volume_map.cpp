// volume_map.cpp — the volmap-map pipeline (docs/mapping.md §8; conventions in volume_map.hpp): the
// schedule of the stages over one MapState. Every stage is judged by one StageJudge (a stage that
// makes the exact count worse is undone) and draws its time from one TimeBudget: the schedule is
// planned over min(time limit, planning horizon); with refinement the untangling cascade may use the
// first refine_time_share of that plan and the B1 rounds the rest; time beyond the plan goes to
// further judged rounds only. Section marks (§N) refer to docs/mapping.md.
#include <volmap/volume/volume_map.hpp>

#include <volmap/check/map_check.hpp>
#include <volmap/core/error.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/volume/bad_tet_flip.hpp>
#include <volmap/volume/bad_tet_split.hpp>
#include <volmap/volume/boundary_fill.hpp>
#include <volmap/volume/cone_repair.hpp>
#include <volmap/volume/map_stages.hpp>
#include <volmap/volume/star_shaped_boundary.hpp>
#include <volmap/volume/vertex_removal.hpp>
#include <volmap/volume/edge_removal_fewer_tets.hpp>

#include <tbb/global_control.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <string>
#include <utility>

namespace volmap {

namespace {

// What §3 and §4 made of the input: the same for every start, so a restart from the other start
// takes it over instead of analysing and editing the input again (on a 131k-tet coarse limb mesh
// onto the star that was 14 s of the 60).
struct PreparedSource {
  TetMesh mesh;
  std::vector<std::array<double, 3>> target;
  std::vector<std::uint8_t> locked;
  FeasibilityReport feasibility;
  std::vector<InfeasibilityCertificate> infeasibility;
  ChordSplitResult chords;
  bool chords_edited = false;  // the chord-split stage ran
};

class VolumeMapper {
 public:
  // prepared: a PreparedSource of the same input and map from an earlier run, or null.
  VolumeMapper(const TetMeshData& input, const BoundaryMap& map, const VolumeMapOptions& options, const PreparedSource* prepared)
      : options_(options), map_(map), total_(options.time_limit_seconds), attempt_(total_), state_(input, map, options.initial_xyz), judge_(state_),
        input_has_tet_labels_(!input.tet_labels.empty()), input_has_vertex_labels_(!input.vertex_labels.empty()), prepared_(prepared) {
    b1_rounds_ = options.allow_refinement && options.method == MapMethod::Ffm;
    plan_schedule();
    growth_budget_ = std::size_t(options.max_growth * double(state_.input_tets));
    growth_cap_ = std::max(growth_budget_, std::size_t(options.max_growth_last_resort * double(state_.input_tets)));
  }

  // After run(): what §3–§4 made of the input, when a restart from the other start may follow.
  std::shared_ptr<PreparedSource> kept_for_restart() const { return kept_for_restart_; }

  VolumeMapResult run() {
    if (prepared_) {
      take_prepared_source();
    } else {
      analyze();
      ChordSplitResult chords;
      const bool edited = options_.allow_refinement && remove_blocking_chords_stage(chords);
      if (restart_possible())
        kept_for_restart_ = std::make_shared<PreparedSource>(PreparedSource{
            state_.source, state_.target.data(), state_.locked.data(), result_.feasibility, result_.infeasibility, chords, edited});
    }
    start_map();
    // A boundary image enclosing a non-positive volume (mirrored map): no map exists at any
    // refinement (the target volumes sum to that volume), so no untangler is run.
    if (result_.feasibility.infeasible_with_any_refinement()) {
      result_.certified_by.clear();
      return finish(false);
    }
    // An exact local certificate at fixed connectivity (§10): no untangler can succeed.
    if (!options_.allow_refinement && !result_.infeasibility.empty()) return finish(false);
    if (bad_ > 0 && !budget_->expired()) untangle_from_tlc();
    if (bad_ > 0 && cascade() && !b1_rounds_) fixed_connectivity_phase();
    if (bad_ > 0 && b1_rounds_) repair_rounds(plan_);
    if (bad_ > 0) use_time_beyond_plan();
    if (bad_ == 0 && options_.quality_pass && options_.method == MapMethod::Ffm && !budget_->expired()) quality();
    return finish(true);
  }

 private:
  const VolumeMapOptions& options_;
  const BoundaryMap& map_;
  TimeBudget total_;  // started first: the time of the whole call
  TimeBudget attempt_;  // this run's share of it (less than total_ when a restart may follow)
  MapState state_;
  StageJudge judge_;
  VolumeMapResult result_;
  TimeBudget plan_;            // the first min(limit, planning horizon) seconds: the planned schedule
  TimeBudget cascade_budget_;  // the untangling cascade's part of plan_
  const TimeBudget* budget_ = nullptr;  // the current phase's budget
  bool b1_rounds_ = false;
  std::size_t growth_budget_ = 0;  // tets B0 + B1 may add (grown by escalate_growth_budget)
  std::size_t growth_cap_ = 0;
  std::size_t bad_ = 0;  // exact non-positive count of the state kept
  std::size_t early_b1_stalled_at_ = std::size_t(-1);  // bad count of the last early B1 that patched nothing
  bool input_has_tet_labels_, input_has_vertex_labels_;  // label arrays stay empty when the input's were
  const PreparedSource* prepared_ = nullptr;
  std::size_t split_rounds_ = 0;  // split_bad_tets stages run
  std::shared_ptr<PreparedSource> kept_for_restart_;

  // The schedule over attempt_: planned over min(its limit, the planning horizon); with refinement
  // the cascade gets the first refine_time_share of the plan. MapMethod::Tlc is one stage: it plans
  // nothing and gets the whole limit.
  void plan_schedule() {
    const double horizon = options_.method == MapMethod::Ffm ? options_.planning_horizon_seconds : 0;
    plan_ = attempt_.limited() && horizon > 0 && attempt_.limit_seconds() > horizon
                ? attempt_.first_part(horizon / attempt_.limit_seconds())
                : attempt_;
    cascade_budget_ = b1_rounds_ ? plan_.first_part(options_.refine_time_share) : plan_;
    budget_ = &cascade_budget_;
  }

  // ---- bookkeeping --------------------------------------------------------------------------
  // Runs one untangling stage and judges it; names it as the certifying stage when it left no
  // non-positive tet. A stage that throws volmap::Error failed internally (the input was validated
  // when the state was built): its partial work is undone, the reason recorded, and the cascade goes
  // on from the best state. Before any state was judged there is nothing to go back to: it throws.
  template <class Run>
  void judged_stage(const std::string& name, Run&& run, const std::string& certifier) {
    const double t0 = total_.elapsed();
    std::string failure;
    try {
      run();
    } catch (const Error& e) {
      if (judge_.best() == std::size_t(-1)) throw;
      failure = e.reason();
      judge_.restore_best();
    }
    const StageVerdict v = judge_.judge();
    result_.stages.push_back({name, total_.elapsed() - t0, v.measured, state_.source.num_tets(), failure});
    bad_ = v.kept;
    if (bad_ == 0 && failure.empty() && !certifier.empty()) result_.certified_by = certifier;
  }
  template <class Run>
  void judged_stage(const std::string& name, Run&& run) { judged_stage(name, std::forward<Run>(run), name); }
  // A stage that changes no target (analysis, B0 splits) is only timed.
  template <class Run>
  void timed_stage(const std::string& name, Run&& run) {
    const double t0 = total_.elapsed();
    run();
    result_.stages.push_back({name, total_.elapsed() - t0, 0, state_.source.num_tets(), ""});
  }
  bool cascade() const { return options_.method == MapMethod::Ffm; }

  // ---- §3, §4, §2: before untangling ----------------------------------------------------------
  void analyze() {
    timed_stage("feasibility", [&] {
      result_.feasibility = analyze_feasibility(state_);
      result_.infeasibility = find_local_infeasibility(state_);
    });
  }

  // B0 when something blocks; false when nothing needed it.
  bool remove_blocking_chords_stage(ChordSplitResult& cs) {
    const FeasibilityReport& f = result_.feasibility;
    if (f.blocking_chord_edges.empty() && f.blocking_chord_faces.empty() && f.fixed_nonpositive_tets.empty()) return false;
    timed_stage("chord-split", [&] { cs = remove_blocking_chords(state_, f); });
    record_chords(cs);
    return true;
  }

  void record_chords(const ChordSplitResult& cs) {
    result_.chord_edges_split = cs.edges_split;
    result_.chord_faces_split = cs.faces_split;
    result_.chord_edges_removed = cs.edges_removed;
    result_.chord_faces_flipped = cs.faces_flipped;
    result_.chord_cone_patches = cs.cone_patches;
    result_.chord_splits_refused = cs.splits_refused;
    result_.refined = cs.vertices_added > 0 || cs.edges_removed > 0 || cs.faces_flipped > 0;
  }

  bool restart_possible() const {
    return cascade() && options_.start == StartMap::Fewest && options_.restart_share < 1 && total_.limited();
  }

  // The restart's state after §3–§4, as the first run left it (a stage of no time in the list).
  void take_prepared_source() {
    const PreparedSource& p = *prepared_;
    state_.source = p.mesh;  // resets the properties...
    state_.target.data() = p.target;  // ...restored here
    state_.locked.data() = p.locked;
    result_.feasibility = p.feasibility;
    result_.infeasibility = p.infeasibility;
    if (p.chords_edited) record_chords(p.chords);
    result_.stages.push_back({"feasibility-and-chord-split-reused", 0, 0, state_.source.num_tets(), ""});
  }

  // The given initial map (chord-split vertices placed by a local Laplacian), or the start of
  // options_.start: Tutte 3D, the radial start, or both when the boundary image is not convex (the
  // second is undone when it leaves more non-positive tets; on a convex image Tutte already keeps
  // every vertex inside). The TLC baseline always starts from Tutte 3D, as published.
  void start_map() {
    if (!options_.initial_xyz.empty()) {
      judged_stage("initial", [&] { place_new_vertices_by_laplacian(state_, state_.input_vertices); });
      return;
    }
    const StartMap start = cascade() ? options_.start : StartMap::Tutte;
    if (start == StartMap::Radial) {
      judged_stage("radial-tutte", [&] {
        if (!place_by_radial_tutte(state_).placed) place_by_tutte(state_);
      });
      result_.start = StartMap::Radial;
      return;
    }
    judged_stage("tutte3d", [&] { place_by_tutte(state_); });
    result_.start = StartMap::Tutte;
    if (start != StartMap::Fewest || bad_ == 0) return;
    if (boundary_image_is_convex(state_)) {
      // Tutte keeps every free vertex inside a convex image: it starts alone and this run keeps the
      // whole limit. The radial start is the second chance for a run that stalls with time left.
      result_.other_start = StartMap::Radial;
      return;
    }
    const std::size_t tutte_bad = bad_;
    judged_stage("radial-tutte", [&] { place_by_radial_tutte(state_); });
    const bool radial_kept = result_.stages.back().nonpositive_after <= tutte_bad && result_.stages.back().failure.empty();
    result_.start = radial_kept ? StartMap::Radial : StartMap::Tutte;
    result_.other_start = radial_kept ? StartMap::Tutte : StartMap::Radial;
    // A restart from the other start may follow: this run keeps its first share of the limit.
    if (bad_ > 0 && options_.restart_share < 1 && total_.limited()) {
      attempt_ = total_.first_part(options_.restart_share);
      plan_schedule();
    }
  }

  // ---- stages used by several phases ----------------------------------------------------------
  void link_kernel() {
    if (bad_ == 0 || !cascade() || budget_->expired()) return;
    judged_stage("link-kernel", [&] { run_link_kernel(state_, 50); });
    kernel_descent();
  }

  void kernel_descent() {
    if (bad_ == 0 || !cascade() || !options_.kernel_descent || budget_->expired()) return;
    judged_stage("kernel-descent", [&] { run_kernel_descent(state_); });
  }

  // Local FFM (Newton) on the region of the remaining non-positive tets, the rest frozen.
  void local_ffm(double share) {
    if (bad_ == 0 || !cascade() || !options_.local_untangle || budget_->expired()) return;
    LocalUntangleOptions lo;
    lo.time_limit_seconds = budget_->option_seconds(share);
    judged_stage("ffm-local", [&] { run_local_ffm(state_, lo); });
    kernel_descent();
  }

  // The local FFM's share in the cascade: smaller when B1 follows (cone patches and splits finish
  // most maps it leaves; measured below split_bad_tets), larger at fixed connectivity, where it is
  // one of the few moves left.
  double cascade_local_share() const { return b1_rounds_ ? 0.1 : 0.25; }

  // TLC with a 100× smaller lift (alpha 1e-8) from the current map, then link-kernel relocation.
  void small_lift_tlc(const std::string& name, double share) {
    TlcOptions to;
    hand_over_stalls(to);
    to.alpha_ratio = 1e-8;
    to.time_limit_seconds = budget_->option_seconds(share);
    judged_stage(name, [&] { run_tlc(state_, to); });
    link_kernel();
  }

  // B1 cone repair of every cluster, within what is left of the growth budget and half the time left.
  // Early attempts and the first repair rounds are cheap tries; once a repair round has stalled
  // (repair and local FFM both without progress), the repair widens the search when a round repairs
  // nothing (ConeRepairOptions::search_escalations). A widening persists: later rounds start from the
  // widest search used so far.
  ConeRepairResult cone_repair_stage(const std::string& name, bool widen_search, double time_share = 0.5) {
    ConeRepairOptions co;
    if (!widen_search) {
      co.search_escalations = 0;
    } else {
      const int widened = int(result_.cone_search_widenings);  // only the repair phase widens
      widen_growth_limits(co, widened);
      co.search_escalations = std::max(0, co.search_escalations - widened);
    }
    const long long used = (long long)state_.source.num_tets() - (long long)state_.input_tets;
    co.max_added_tets = std::size_t(std::max(1LL, (long long)growth_budget_ - used));
    co.time_limit_seconds = budget_->option_seconds(time_share);
    ConeRepairResult cr;
    judged_stage(name, [&] { cr = run_cone_repair(state_, co); }, "cone-repair");
    if (!result_.stages.back().failure.empty()) cr = ConeRepairResult{};  // undone
    result_.cone_search_widenings += cr.search_escalations;
    result_.cone_patches += cr.patches;
    if (cr.patches > 0) result_.refined = true;
    return cr;
  }

  // Where a repair round left few tets: their interior edges are split and link kernel, kernel
  // descent and local FFM run on the finer mesh, judged as one stage (undone when the count ends
  // higher). Measured on coarse thin shapes whose last 1-4 tets no cone patch could reach (target
  // needles: no kernel point), one round certified fins -> pyr, fins -> tet and coarse limbs -> tet.
  // Over the thin_coarse, surfaces and tetmeshes sets (bench/eval/stage_progress.py on the build
  // before this order) the local FFM lowered the count in 14 of 498 calls (836 s without progress);
  // the split lowered it in 14 of 78, 11 of them finishing the map. At most kSplitRounds times per
  // run, within the growth cap.
  bool split_bad_tets() {
    static constexpr std::size_t kSplitMaxBad = 64, kSplitRounds = 6, kTetsPerBadTet = 40;
    if (bad_ == 0 || bad_ > kSplitMaxBad || split_rounds_ >= kSplitRounds || !cascade() || budget_->expired()) return false;
    const long long used = (long long)state_.source.num_tets() - (long long)state_.input_tets;
    if (used + (long long)(kTetsPerBadTet * bad_) > (long long)growth_cap_) return false;
    ++split_rounds_;
    const std::size_t before = bad_;
    LocalUntangleOptions lo;
    lo.time_limit_seconds = budget_->option_seconds(0.15);
    judged_stage("split-bad-tets", [&] {
      split_edges_of_nonpositive_tets(state_);
      run_link_kernel(state_, 50);
      if (options_.kernel_descent) run_kernel_descent(state_);
      if (options_.local_untangle) run_local_ffm(state_, lo);
    });
    if (bad_ >= before) return false;
    result_.refined = true;
    return true;
  }

  // After a B1 round that refused a patch for the budget while bad tets remain (see
  // max_growth_last_resort): a larger budget; false when it is at the cap already.
  bool escalate_growth_budget(const ConeRepairResult& cr) {
    if (cr.failures.budget == 0 || bad_ == 0 || growth_budget_ >= growth_cap_) return false;
    const long long used = std::max(0LL, (long long)state_.source.num_tets() - (long long)state_.input_tets);
    const std::size_t wanted = std::max(2 * growth_budget_, std::size_t(used) + std::max<std::size_t>(16, growth_budget_));
    growth_budget_ = std::min(growth_cap_, wanted);
    ++result_.growth_budget_escalations;
    return true;
  }

  // Flips that take non-positive tets out without a new vertex (bad_tet_flip.hpp): every move
  // lowers the count and touches no other tet. They run before each early repair attempt (the
  // repair then gets smaller clusters, docs/mapping.md §8 step 8) and after the repair of each B1
  // round; the link kernel follows when a move freed the vertices around it.
  void flip_bad_tets() {
    if (bad_ == 0 || !b1_rounds_ || !options_.bad_tet_flips || budget_->expired()) return;
    BadTetFlipResult fr;
    judged_stage("flip-bad-tets", [&] { fr = flip_nonpositive_tets(state_); });
    if (!result_.stages.back().failure.empty() || fr.edges_removed + fr.faces_flipped == 0) return;
    result_.bad_tet_flips += fr.edges_removed + fr.faces_flipped;
    result_.refined = true;
    link_kernel();
  }

  // Early B1: as soon as a stage leaves few non-positive tets, the cone repair is tried (it leaves a
  // cluster untouched when it fails); not again at an unchanged count after an attempt that stalled.
  void try_early_b1(const std::string& after) {
    if (bad_ == 0 || !b1_rounds_ || bad_ > options_.early_repair_max_bad || bad_ >= early_b1_stalled_at_) return;
    flip_bad_tets();
    if (bad_ == 0) return;
    const ConeRepairResult cr = cone_repair_stage("cone-repair-after-" + after, false);
    if (cr.patches == 0 || cr.failed_clusters > 0) early_b1_stalled_at_ = bad_;
  }

  void global_ffm_stage(const std::string& name, FfmOptions fo) {
    judged_stage(name, [&] { run_ffm(state_, fo); });
    link_kernel();
  }

  // ---- the phases -----------------------------------------------------------------------------
  // §6 TLC (the whole method with MapMethod::Tlc), then in the cascade the link kernel, a
  // small-lift TLC round and local FFM, each followed by an early B1 attempt.
  // A TLC stage hands the last few non-positive tets over to B1 when B1 may run (see the options).
  void hand_over_stalls(TlcOptions& to) const {
    if (!b1_rounds_) return;
    to.stall_evaluations = options_.tlc_stall_evaluations;
    to.stall_max_bad = options_.early_repair_max_bad;
  }

  // In the cascade TLC offers its iterate to exact local moves (finish_by_link_kernels) each time
  // its count reaches a new low within tlc_finish_max_bad; they end TLC only by finishing the map.
  // A partial local repair is not kept: moved vertices are a worse start for TLC than its own
  // iterate. The bound is small because a map finished earlier had fewer TLC iterations of
  // smoothing, which the quality pass does not make up for (docs/mapping.md §6).
  void untangle_from_tlc() {
    TlcOptions to;
    hand_over_stalls(to);
    if (cascade()) {
      to.finish_max_bad = options_.tlc_finish_max_bad;
      to.finish = [&](std::vector<double>& x) { return finish_by_link_kernels(state_, x); };
    }
    to.time_limit_seconds = budget_->option_seconds(cascade() ? options_.tlc_time_share : 1.0);
    judged_stage("tlc", [&] { run_tlc(state_, to); });
    link_kernel();
    try_early_b1("tlc");
    if (bad_ > 0 && cascade() && !budget_->expired()) {
      small_lift_tlc("tlc-small-alpha", 0.3);
      try_early_b1("tlc-small-alpha");
    }
    local_ffm(cascade_local_share());
    try_early_b1("ffm-local");
    try_b1_after_stall();
  }

  // When TLC and the local moves leave more non-positive tets than an early B1 attempt takes: one B1
  // attempt with a quarter of the time left before the B1 rounds (no global FFM stage runs with
  // refinement, see global_ffm); what it repairs is kept.
  void try_b1_after_stall() {
    if (bad_ == 0 || !b1_rounds_ || bad_ <= options_.early_repair_max_bad || budget_->expired()) return;
    cone_repair_stage("cone-repair-after-stall", false, 0.25);
  }

  // §5 global FFM with the regular reference, then the rest shape, each followed by the link kernel,
  // an early B1 attempt and local FFM. Only at fixed connectivity: where B1 may run, 1 of 136 global
  // FFM stages lowered the count over the thin_coarse, surfaces and tetmeshes sets
  // (bench/eval/stage_progress.py), and their time goes to the repair rounds instead.
  void global_ffm() {
    std::vector<ReferenceShape> refs = {ReferenceShape::RegularTet, ReferenceShape::RestShape};
    if (options_.ffm_rest_shape_first) std::swap(refs[0], refs[1]);
    for (ReferenceShape ref : refs) {
      if (bad_ == 0 || budget_->expired()) break;
      FfmOptions fo;
      fo.reference = ref;
      fo.time_limit_seconds = budget_->option_seconds(options_.local_untangle ? 0.6 : 1.0);
      fo.stall_outer_iterations = options_.local_untangle ? 40 : 0;
      if (options_.ffm_max_lbfgs_iterations > 0) fo.max_lbfgs_iterations = options_.ffm_max_lbfgs_iterations;
      const std::string name = ref == ReferenceShape::RegularTet ? "ffm-regular" : "ffm-rest";
      global_ffm_stage(name, fo);
      try_early_b1(name);
      local_ffm(cascade_local_share());
      try_early_b1("ffm-local");
    }
  }

  // Without refinement, after the untangling phase: with few non-positive tets left, local rounds;
  // else the global FFM stages. Global FFM restarts from ε = 1, which smooths a nearly valid map
  // away and is then undone by the judge (docs/mapping.md §10, "Local rounds").
  void fixed_connectivity_phase() {
    if (options_.local_rounds_max_bad > 0 && bad_ <= options_.local_rounds_max_bad)
      local_rounds();
    else
      global_ffm();
  }

  // Rounds of small-lift TLC (it moves the whole map, also at an unchanged count, so the local
  // stages start from another state) and local FFM with a larger share, until two rounds in a row
  // lower nothing or the time is out.
  void local_rounds() {
    for (int idle = 0; bad_ > 0 && idle < 2 && !budget_->expired();) {
      const std::size_t before = bad_;
      small_lift_tlc("tlc-small-alpha", 0.3);
      local_ffm(0.5);
      idle = bad_ < before ? 0 : idle + 1;
    }
  }

  // §7 B1 rounds over the whole time limit: repair → link kernel → (on a handful of tets) local FFM
  // on the repaired mesh (the rest of the map is valid and stays frozen) → repair again. When the
  // repair and the local solve both stall: one small-lift TLC over the whole mesh (its moves at an
  // equal count change the state the repair sees), after which the repair widens its search; at the
  // next stall, stop (the time left goes to the restart from the other start, when there is one).
  void repair_rounds(const TimeBudget& budget) {
    budget_ = &budget;
    bool tlc_retried = false;
    for (int round = 0; round < 8 && bad_ > 0 && !budget_->expired(); ++round) {
      const std::size_t bad_before = bad_;
      const ConeRepairResult cr = cone_repair_stage("cone-repair", tlc_retried);
      if (escalate_growth_budget(cr)) {  // the same round again with the larger budget (bounded: the cap)
        --round;
        continue;
      }
      link_kernel();
      flip_bad_tets();
      if (bad_ == 0 || budget_->expired()) break;
      // Few tets left: the split (with its own short local FFM) before the long local FFM at fixed
      // connectivity, which rarely finishes where a repair left tets (measured below split_bad_tets)
      // and runs only on a handful (VolumeMapOptions::round_local_max_bad).
      const std::size_t splits_before = split_rounds_;
      if (split_bad_tets()) continue;
      const bool split_tried = split_rounds_ > splits_before;
      const std::size_t bad_local = bad_;
      if (bad_ <= options_.round_local_max_bad) local_ffm(0.15);
      if (bad_ == 0 || budget_->expired()) break;
      if (!(cr.patches == 0 && bad_ >= bad_before && bad_ >= bad_local)) continue;
      if (!split_tried && split_bad_tets()) continue;  // finer where it is tangled: the next round starts from there
      if (tlc_retried) break;  // nothing moves any more
      tlc_retried = true;
      small_lift_tlc("tlc-after-repair", 0.25);
    }
  }

  // A limit beyond the planning horizon changes none of the planned stages; what is left after them
  // goes to more judged rounds of the last phase (B1 rounds, or the fixed-connectivity phase without B1),
  // so more time never ends with more non-positive tets.
  void use_time_beyond_plan() {
    if (!attempt_.limited() || plan_.limit_seconds() >= attempt_.limit_seconds() || attempt_.expired()) return;
    if (b1_rounds_) {
      repair_rounds(attempt_);
    } else if (cascade()) {
      budget_ = &attempt_;
      fixed_connectivity_phase();
    }
  }

  // Quality pass (never breaks validity: kept only when the exact check passes). Not after
  // MapMethod::Tlc: the baseline reproduces the published method alone.
  void quality() {
    double seconds = std::max(options_.quality_min_seconds, options_.quality_time_ratio * total_.elapsed());
    if (budget_->limited()) seconds = std::min(seconds, budget_->remaining());
    judged_stage("quality", [&] { run_quality_pass(state_, ReferenceShape::RestShape, options_.quality_iterations, seconds,
                                                      options_.quality_relative_decrease); }, "");
  }

  // ---- the result -----------------------------------------------------------------------------
  // The state as flat arrays; with `certify`, check_map decides on exactly these arrays.
  VolumeMapResult finish(bool certify) {
    state_.require_compact();
    result_.source = state_.source.to_data();
    if (!input_has_tet_labels_) result_.source.tet_labels.clear();
    if (!input_has_vertex_labels_) result_.source.vertex_labels.clear();
    result_.target_xyz = state_.target_xyz();
    result_.locked = state_.locked.data();
    result_.input_tets = state_.input_tets;
    result_.input_vertices = state_.input_vertices;
    result_.nonpositive = bad_;
    result_.certified = false;
    if (certify) {
      TetMeshData mapped = result_.source;
      mapped.xyz = result_.target_xyz;
      try {
        const MapCheckReport check = check_map(result_.source, mapped, &map_);
        result_.nonpositive = check.output.zero + check.output.negative;
        result_.certified = check.certified();
      } catch (const Error&) {  // e.g. a non-finite target: not certified, never the user's bad input
        result_.nonpositive = result_.source.num_tets();
      }
    }
    if (!result_.certified) result_.certified_by.clear();
    result_.seconds = total_.elapsed();
    return std::move(result_);
  }
};

// prepared: what an earlier run of the same input made of it before its start map (or null);
// kept (when not null): receives this run's, when a restart could use it.
VolumeMapResult run_mapper(const TetMeshData& input, const BoundaryMap& map, const VolumeMapOptions& options,
                           const PreparedSource* prepared = nullptr, std::shared_ptr<PreparedSource>* kept = nullptr) {
  VolumeMapper mapper(input, map, options, prepared);  // validates the input (Error(BadInput))
  try {
    VolumeMapResult r = mapper.run();
    if (kept) *kept = mapper.kept_for_restart();
    return r;
  } catch (const Error& e) {  // the input was valid: whatever fails now is the mapper's own failure
    if (e.kind() != ErrorKind::BadInput) throw;
    throw Error(ErrorKind::Failed, "", 0, "internal: " + e.reason());
  }
}

// The least share of the limit left worth a restart (a run from the radial start needs its TLC and
// at least one repair round).
constexpr double kMinRestartShare = 0.1;

// A run from the start with fewer non-positive tets that ended uncertified gets a second run from
// the other start, unless an exact certificate proves that no map exists (at any refinement, or
// at fixed connectivity without refinement), or too little time is left.
bool worth_a_restart(const VolumeMapResult& r, const VolumeMapOptions& options, const TimeBudget& total) {
  if (r.certified || !r.other_start || options.restart_share >= 1) return false;
  // A first run that kept the whole limit (a convex image) restarts only when it stalled early.
  if (total.limited() && total.remaining() < kMinRestartShare * total.limit_seconds()) return false;
  if (r.feasibility.infeasible_with_any_refinement()) return false;
  return options.allow_refinement || r.infeasibility.empty();
}

// The certified run, else the one with fewer non-positive tets (the first on a tie). Its stage list
// is the first run's, `separator`, then the second run's, so the result shows all the work done.
VolumeMapResult better_run(VolumeMapResult first, VolumeMapResult second, const VolumeMapStage& separator, double seconds) {
  const bool second_wins = second.certified || (!first.certified && second.nonpositive < first.nonpositive);
  std::vector<VolumeMapStage> stages = std::move(first.stages);
  stages.push_back(separator);
  stages.insert(stages.end(), second.stages.begin(), second.stages.end());
  VolumeMapResult& kept = second_wins ? second : first;
  kept.stages = std::move(stages);
  kept.seconds = seconds;
  return std::move(kept);
}

// The run from the kept start and, when worth it, the restart from the other one.
VolumeMapResult map_from_both_starts(const TetMeshData& input, const BoundaryMap& map, const VolumeMapOptions& options) {
  const TimeBudget total(options.time_limit_seconds);
  std::shared_ptr<PreparedSource> prepared;
  VolumeMapResult first = run_mapper(input, map, options, nullptr, &prepared);  // validates the input (Error(BadInput))
  if (!worth_a_restart(first, options, total)) return first;
  VolumeMapOptions again = options;
  again.start = *first.other_start;
  again.restart_share = 1;
  if (total.limited()) again.time_limit_seconds = total.remaining();
  try {
    VolumeMapResult second = run_mapper(input, map, again, prepared.get());
    const VolumeMapStage restart{"restart", 0, first.nonpositive, first.input_tets, ""};  // the first run's count; the input again
    VolumeMapResult kept = better_run(std::move(first), std::move(second), restart, total.elapsed());
    kept.restarted = true;
    return kept;
  } catch (const Error& e) {  // the restart failed internally: the first run's result stands
    first.stages.push_back({"restart", 0, first.nonpositive, first.input_tets, e.reason()});
    first.seconds = total.elapsed();
    return first;
  }
}

// The share of the time left that the interior remesh may take: the rest maps the remeshed source,
// which takes seconds where TetGen takes tens (docs/mapping.md §8 step 11).
constexpr double kRemeshTimeShare = 0.8;

// An uncertified result gets another run (on the remeshed source, or continuing after a refused
// remesh) when the map may exist at some refinement and at least kMinRestartShare of the limit is
// left.
bool worth_another_run(const VolumeMapResult& r, const TimeBudget& total) {
  if (r.certified || r.feasibility.infeasible_with_any_refinement()) return false;
  return !total.limited() || total.remaining() >= kMinRestartShare * total.limit_seconds();
}

// A later run on first's (refined) source or a remeshed one reports growth, input counts and the
// feasibility report of the input, as `first` (a run from the input) does; it is refined when
// either run refined.
void report_against_input(VolumeMapResult& later, const VolumeMapResult& first) {
  later.input_tets = first.input_tets;
  later.input_vertices = first.input_vertices;
  later.feasibility = first.feasibility;
  later.infeasibility = first.infeasibility;
  later.refined = later.refined || first.refined;
}

// The time left goes on from where an uncertified result stopped: its (refined) source and map are
// the input and the initial map of one more run, whose growth budgets are what is left of the
// input's. Returns the better of the two (growth, input counts and the feasibility report of the
// input); `first` stands if the continuation fails. `separator` is the stage listed between them
// (a failed remesh, or "continue").
VolumeMapResult continue_run(VolumeMapResult first, const BoundaryMap& map, const VolumeMapOptions& options,
                             const TimeBudget& total, const VolumeMapStage& separator) {
  auto keep_first = [&](const std::string& why) {
    first.stages.push_back(separator);
    if (!why.empty()) first.stages.push_back({"continue", 0, first.nonpositive, first.source.num_tets(), why});
    first.seconds = total.elapsed();
    return std::move(first);
  };
  if (!worth_another_run(first, total)) return keep_first("");
  VolumeMapOptions again = options;
  again.remesh_interior = nullptr;
  again.restart_share = 1;
  again.initial_xyz = first.target_xyz;
  const double input_tets = double(first.input_tets), tets_now = double(first.source.num_tets());
  auto budget_left = [&](double fraction) { return std::max(0.0, (1 + fraction) * input_tets / tets_now - 1); };
  again.max_growth = budget_left(options.max_growth);
  again.max_growth_last_resort = std::max(again.max_growth, budget_left(options.max_growth_last_resort));
  if (total.limited()) again.time_limit_seconds = total.remaining();
  VolumeMapResult second;
  try {
    second = map_from_both_starts(first.source, map, again);
  } catch (const Error& e) {
    return keep_first("continuing the runs from the input failed: " + e.reason());
  }
  report_against_input(second, first);
  return better_run(std::move(first), std::move(second), separator, total.elapsed());
}

// Maps the remeshed source with the time left; returns the better of `first` and that run (growth,
// input counts and the feasibility report of the input). A remesh that fails or breaks its contract
// is a stage failure: the time left continues the runs from the input (continue_run).
VolumeMapResult with_remeshed_source(VolumeMapResult first, const TetMeshData& input, const BoundaryMap& map,
                                     const VolumeMapOptions& options, const TimeBudget& total) {
  const TimeBudget remesh_clock;
  auto keep_first = [&](const std::string& why) {
    const VolumeMapStage failed{"remesh", remesh_clock.elapsed(), first.nonpositive, first.source.num_tets(), why};
    return continue_run(std::move(first), map, options, total, failed);
  };
  TetMeshData remeshed;
  std::string problem;
  try {
    remeshed = options.remesh_interior(input, total.option_seconds(kRemeshTimeShare));
    problem = interior_remesh_problem(input, remeshed);
  } catch (const std::exception& e) {
    problem = e.what();
  }
  if (!problem.empty()) return keep_first("remesh refused: " + problem);
  VolumeMapOptions again = options;
  again.remesh_interior = nullptr;
  again.initial_xyz.clear();
  if (total.limited()) again.time_limit_seconds = total.remaining();
  const double remesh_seconds = remesh_clock.elapsed();
  VolumeMapResult second;
  try {
    second = map_from_both_starts(remeshed, map, again);
  } catch (const Error& e) {
    return keep_first("mapping the remeshed source failed: " + e.reason());
  }
  report_against_input(second, first);
  second.refined = second.remeshed = true;
  const VolumeMapStage remesh{"remesh", remesh_seconds, first.nonpositive, remeshed.num_tets(), ""};
  return better_run(std::move(first), std::move(second), remesh, total.elapsed());
}

// The share of the time limit held back for the whole-mesh cone (step 12) when ∂M is star-shaped
// in both spaces: the patches of the 34k–58k-tet plates and stars of thin_coarse-s4 took 0.1–0.5 s
// alone (1.5 s beside two other runs); the patch may take the rest of the limit, or this share.
constexpr double kWholeConeShare = 0.05;
constexpr double kWholeConeMinSeconds = 1.0;

// Runs end before the limit when every stage has stalled; the time left then continues from the
// best result (continue_run), again while a continuation lowers the count and enough time is left:
// more time never ends with more non-positive tets, and a long local solve the shares cut short
// gets its chance (docs/mapping.md §8 step 13).
VolumeMapResult continue_while_it_helps(VolumeMapResult r, const BoundaryMap& map, const VolumeMapOptions& options,
                                        const TimeBudget& total) {
  static constexpr int kMaxContinuations = 3;
  for (int k = 0; k < kMaxContinuations && total.limited() && worth_another_run(r, total); ++k) {
    const std::size_t before = r.nonpositive;
    const VolumeMapStage separator{"continue", 0, r.nonpositive, r.source.num_tets(), ""};
    r = continue_run(std::move(r), map, options, total, separator);
    if (r.nonpositive >= before) break;
  }
  return r;
}

// The runs from the input and, with a remesher, the runs on the remeshed source (steps 1–11).
VolumeMapResult map_with_remesh(const TetMeshData& input, const BoundaryMap& map, const VolumeMapOptions& options) {
  const bool remesh = options.allow_refinement && options.remesh_interior;
  const TimeBudget total(options.time_limit_seconds);
  VolumeMapOptions from_input = options;
  if (remesh && total.limited()) from_input.time_limit_seconds = options.remesh_share * total.limit_seconds();
  VolumeMapResult first = map_from_both_starts(input, map, from_input);  // validates the input (Error(BadInput))
  if (!remesh || !worth_another_run(first, total)) return first;
  return continue_while_it_helps(with_remeshed_source(std::move(first), input, map, options, total), map, options, total);
}

// Why whole_mesh_cone left the mesh as it was.
std::string whole_cone_refusal(const ConeRepairResult& cr) {
  const auto& f = cr.failures;
  if (f.not_ball) return "the boundary is not a sphere";
  if (f.last_no_target) return "the boundary image has no strict kernel point";
  if (f.last_no_source) return "the source boundary has no strict kernel point";
  if (f.reinsertion) return "an interior vertex could not be re-inserted";
  if (f.time_limit) return "the time limit passed while re-inserting the interior vertices";
  return "a cone tet was not exactly positive";
}

// A replacement of a result's arrays made by one of the last stages (steps 12 and 14), or why there
// is none.
struct ArraysEdit {
  TetMeshData source;
  std::vector<double> target_xyz;
  std::vector<std::uint8_t> locked;
  std::string refusal;
};

// Runs `make` (r -> ArraysEdit) and keeps its arrays when it made some and check_map certifies them
// exactly: r is then certified (certified_by `certifier`, unless empty) and refined. Stage `stage`
// either way, its failure the refusal (or the error `make` threw).
template <class MakeEdit>
VolumeMapResult with_certified_edit(VolumeMapResult r, const BoundaryMap& map, const TimeBudget& total, const std::string& stage,
                                    const std::string& certifier, MakeEdit make) {
  const TimeBudget clock;
  ArraysEdit e;
  try {
    e = make(r);
    if (e.refusal.empty()) {
      TetMeshData mapped = e.source;
      mapped.xyz = e.target_xyz;
      if (!check_map(e.source, mapped, &map).certified()) e.refusal = "the exact check of the " + stage + " result failed";
    }
  } catch (const Error& err) {
    e.refusal = err.reason();
  }
  if (e.refusal.empty()) {
    r.source = std::move(e.source);
    r.target_xyz = std::move(e.target_xyz);
    r.locked = std::move(e.locked);
    r.certified = r.refined = true;
    if (!certifier.empty()) r.certified_by = certifier;
    r.nonpositive = 0;
  }
  r.stages.push_back({stage, clock.elapsed(), r.nonpositive, r.source.num_tets(), e.refusal});
  r.seconds = total.elapsed();
  return r;
}

// Step 12: an uncertified result's source becomes one cone patch over ∂M (interior vertices
// re-inserted), kept when check_map certifies it exactly and the growth stays within
// max_growth_last_resort; otherwise r stands. Stage "whole-mesh-cone" either way.
VolumeMapResult with_whole_mesh_cone(VolumeMapResult r, const BoundaryMap& map, const VolumeMapOptions& options,
                                     const TimeBudget& total) {
  return with_certified_edit(std::move(r), map, total, "whole-mesh-cone", "whole-mesh-cone", [&](const VolumeMapResult& run) {
    ArraysEdit e{run.source, run.target_xyz, run.locked, ""};
    // At least the share held back for it (and a second), also when the runs overran the limit.
    const double seconds = total.limited()
                               ? std::max({total.remaining(), kWholeConeShare * total.limit_seconds(), kWholeConeMinSeconds})
                               : 0.0;
    const ConeRepairResult cr = whole_mesh_cone(e.source, e.locked, e.target_xyz, seconds);
    const double growth = double(e.source.num_tets()) / double(std::max<std::size_t>(1, run.input_tets)) - 1.0;
    if (cr.patches != 1)
      e.refusal = whole_cone_refusal(cr);
    else if (growth > options.max_growth_last_resort)
      e.refusal = "the cone patch grows the input by more than max_growth_last_resort";
    return e;
  });
}

// Step 14: each of its two stages may take what is left of the limit, at most kFillMaxSeconds and
// at least kFillMinSeconds (the runs may have used it all).
constexpr double kFillMaxSeconds = 2.0;
constexpr double kFillMinSeconds = 0.25;

double fill_seconds(const TimeBudget& total) {
  return std::clamp(total.limited() ? total.remaining() : kFillMaxSeconds, kFillMinSeconds, kFillMaxSeconds);
}

// Step 14a: a new tetrahedralisation of ∂M valid in both spaces with fewer tets (boundary_fill.hpp)
// replaces r when check_map certifies it exactly. Stage "boundary-fill" either way.
VolumeMapResult with_boundary_fill(VolumeMapResult r, const TetMeshData& input, const BoundaryMap& map, const TimeBudget& total) {
  return with_certified_edit(std::move(r), map, total, "boundary-fill", "boundary-fill", [&](const VolumeMapResult& run) {
    BoundaryFillLimits limits;
    limits.time_limit_seconds = fill_seconds(total);
    const CertifiedPoints points = run.certified ? CertifiedPoints{&run.source, &run.target_xyz} : CertifiedPoints{};
    const std::size_t must_beat = run.certified ? run.source.num_tets() : std::numeric_limits<std::size_t>::max();
    BoundaryFill fill = fill_boundary_with_fewer_tets(input, map, points, must_beat, limits);
    return ArraysEdit{std::move(fill.source), std::move(fill.target_xyz), std::move(fill.locked), fill.found ? "" : fill.why_not};
  });
}

// Steps 14b and 14c: an edit of the certified result's arrays that only takes tets out, given the
// stage's share of the limit; `take_out` returns false when it changed nothing, and `refusal` is
// the stage's failure then. Kept when check_map certifies the result exactly (certified_by stays).
template <class TakeOut>
VolumeMapResult with_tets_taken_out(VolumeMapResult r, const BoundaryMap& map, const TimeBudget& total, const std::string& stage,
                                    const std::string& refusal, TakeOut take_out) {
  const std::string certifier = r.certified_by;
  return with_certified_edit(std::move(r), map, total, stage, certifier, [&](const VolumeMapResult& run) {
    ArraysEdit e{run.source, run.target_xyz, run.locked, ""};
    if (!take_out(e, fill_seconds(total))) e.refusal = refusal;
    return e;
  });
}

// Step 14b: the vertices refinement added (ids from the input's vertex count on) whose link has a
// fill with fewer tets, valid in both spaces, are taken back (vertex_removal.hpp). Stage
// "vertex-removal".
VolumeMapResult with_added_vertices_removed(VolumeMapResult r, const TetMeshData& input, const BoundaryMap& map, const TimeBudget& total) {
  return with_tets_taken_out(std::move(r), map, total, "vertex-removal", "no added vertex has a fill of its link with fewer tets",
                             [&](ArraysEdit& e, double seconds) {
                               VertexRemovalLimits limits;
                               limits.time_limit_seconds = seconds;
                               const auto first_added = std::uint32_t(input.num_vertices());
                               return remove_added_vertices(e.source, e.locked, e.target_xyz, first_added, limits).removed > 0;
                             });
}

// Step 14c: interior edges of degree 3 whose two ring tets are positive in both spaces are
// flipped 3-2 (edge_removal_fewer_tets.hpp). Stage "edge-removal".
VolumeMapResult with_degree3_edges_removed(VolumeMapResult r, const BoundaryMap& map, const TimeBudget& total) {
  return with_tets_taken_out(std::move(r), map, total, "edge-removal", "no interior edge of degree 3 has a 3-2 flip valid in both spaces",
                             [](ArraysEdit& e, double seconds) {
                               EdgeRemovalLimits limits;
                               limits.time_limit_seconds = seconds;
                               return remove_degree3_edges(e.source, e.locked, e.target_xyz, limits).flips > 0;
                             });
}

// Step 14 on the result of steps 1–12, when it grew the input or is uncertified. The fill searches
// are heuristic: fewer points (after removals) can make one succeed that failed before, and the
// other way round, so a small input gets a fill before and after the removals.
VolumeMapResult with_fewer_tets(VolumeMapResult r, const TetMeshData& input, const BoundaryMap& map, const VolumeMapOptions& options,
                                const TimeBudget& total) {
  auto grew_or_failed = [&] { return !r.certified || r.source.num_tets() > input.num_tets(); };
  const bool small = input.num_tets() <= options.boundary_fill_max_tets;
  // An uncertified result gives interior vertices no images: only a map that fixes every vertex
  // leaves the fill something to search.
  const bool images = r.certified || map.size() == input.num_vertices();
  if (grew_or_failed() && small && images) r = with_boundary_fill(std::move(r), input, map, total);
  if (!grew_or_failed() || !r.certified) return r;
  const std::size_t before = r.source.num_tets();
  r = with_added_vertices_removed(std::move(r), input, map, total);
  if (grew_or_failed() && small && r.source.num_tets() < before) r = with_boundary_fill(std::move(r), input, map, total);
  if (grew_or_failed()) r = with_degree3_edges_removed(std::move(r), map, total);
  return r;
}

}  // namespace

VolumeMapResult compute_volume_map(const TetMeshData& input, const BoundaryMap& map, const VolumeMapOptions& options) {
  std::unique_ptr<tbb::global_control> thread_limit;
  if (options.max_threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(options.max_threads));
  if (!(options.tlc_time_share >= 0 && options.tlc_time_share <= 1))
    throw Error(ErrorKind::BadInput, "", 0, "tlc_time_share must be in [0, 1]");
  if (!(options.remesh_share > 0 && options.remesh_share <= 1))
    throw Error(ErrorKind::BadInput, "", 0, "remesh_share must be in (0, 1]");
  const TimeBudget total(options.time_limit_seconds);
  // Not for MapMethod::Tlc: the baseline reproduces the published method alone.
  const bool cone_last = options.method == MapMethod::Ffm && options.allow_refinement && options.whole_mesh_cone &&
                         boundary_star_shaped_in_both_spaces(input, map);
  VolumeMapOptions runs = options;
  if (cone_last && total.limited()) runs.time_limit_seconds = (1 - kWholeConeShare) * total.limit_seconds();
  VolumeMapResult r = map_with_remesh(input, map, runs);  // validates the input (Error(BadInput))
  if (cone_last && !r.certified) r = with_whole_mesh_cone(std::move(r), map, options, total);
  const bool fewer = options.method == MapMethod::Ffm && options.allow_refinement && options.fewer_tets;
  return fewer ? with_fewer_tets(std::move(r), input, map, options, total) : r;
}

}  // namespace volmap
