// volmap/volume/map_stages.hpp — the stages of the volume mapper, each one algorithm run on the
// MapState (docs/mapping.md §8). A stage reads the source mesh, the target and the locked mask from
// the state and writes the target back; the refining stages (chord splitting, cone repair) edit the
// mesh and leave no tombstone (B0's splits on a compact mesh make none, cone repair compacts), so
// every stage starts on a compact mesh. Stages never judge their result: compute_volume_map does
// that with one StageJudge. Locked vertices are never moved.
#pragma once

#include <volmap/volume/chord_split.hpp>
#include <volmap/volume/cone_repair.hpp>
#include <volmap/volume/feasibility.hpp>
#include <volmap/volume/ffm.hpp>
#include <volmap/volume/infeasibility.hpp>
#include <volmap/volume/kernel_descent.hpp>
#include <volmap/volume/link_kernel.hpp>
#include <volmap/volume/map_state.hpp>
#include <volmap/volume/radial_start.hpp>
#include <volmap/volume/tlc.hpp>

namespace volmap {

// §3 on the current state (only the locked targets are read).
FeasibilityReport analyze_feasibility(const MapState& state);
// §10 exact local infeasibility certificates of the current state (only the locked targets are read).
std::vector<InfeasibilityCertificate> find_local_infeasibility(const MapState& state);
// §4 B0: removes the blocking chords of `report` by the cheapest admissible fix (flip or split);
// new vertices are unlocked, their target unset; the mesh is compacted (no vertex is deleted).
ChordSplitResult remove_blocking_chords(MapState& state, const FeasibilityReport& report);
// §2: every unlocked vertex at the uniform-Laplacian (Tutte) solution for the locked ones.
void place_by_tutte(MapState& state);
// §2 the radial start (radial_start.hpp) on the state's target; not placed: the target is untouched.
RadialStartResult place_by_radial_tutte(MapState& state);
// The boundary image (the locked targets) has no reflex edge beyond rounding (radial_start.hpp).
bool boundary_image_is_convex(const MapState& state);
// The same for the vertices after the first `keep` only (the rest keep their target): vertices made
// by B0 on a given initial map start at the average of their neighbours.
void place_new_vertices_by_laplacian(MapState& state, std::size_t keep);
// §6 TLC, §7 link-kernel relocation, §5 FFM (global, local, quality pass) on the state's target.
TlcResult run_tlc(MapState& state, const TlcOptions& options);
RelocationResult run_link_kernel(MapState& state, int max_sweeps);
// §10 bad-tet-driven descent of single vertices towards their link kernel.
KernelDescentResult run_kernel_descent(MapState& state);
// §7 + §10 as a trial on a map x of the state's mesh (not the state's own target): link-kernel
// relocation, then kernel descent. True when they leave x exactly positive on every tet; x is then
// the finished map. False: x is left as it was given.
bool finish_by_link_kernels(const MapState& state, std::vector<double>& x);
FfmResult run_ffm(MapState& state, const FfmOptions& options);
LocalUntangleResult run_local_ffm(MapState& state, const LocalUntangleOptions& options);
QualityResult run_quality_pass(MapState& state, ReferenceShape reference, int max_iterations, double time_limit_seconds,
                               double relative_decrease);
// §7 B1 cone repair; the mesh is compacted afterwards when a patch freed slots.
ConeRepairResult run_cone_repair(MapState& state, const ConeRepairOptions& options);

}  // namespace volmap
