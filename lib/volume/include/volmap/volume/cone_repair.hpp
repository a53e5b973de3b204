// volmap/volume/cone_repair.hpp — B1 star-patch cone repair (docs/mapping.md §7).
// For each cluster of non-positive target tets: grow a region R (a ball) until its boundary is
// star-shaped in BOTH the target and the source (strict kernel points, kernel_lp.hpp), replace R by
// the cones from one apex w (source p, target q) over the outward faces of ∂R, and re-insert R's
// other interior vertices by splitting the cone tet that contains them (kept vertices; their target
// is a point strictly inside the matching target tet). Every new tet is exactly positive in both
// spaces, so the refined source stays a valid tetrahedralisation and the repaired map stays
// certifiable. The replacement is one TetMesh::replace_cavity edit per patch.
// Conventions: the source is a TetMesh with VOLMAP-positive tets (orient3d(v0,v1,v2,v3) > 0); the
// target is a PositionProperty of that mesh and the locked mask a vertex property (locked vertices,
// the boundary, and the faces of ∂M are never changed). Patches leave tombstones (compact() the
// mesh afterwards for flat arrays); vertex ids never change, new vertices take new slots.
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct ConeRepairOptions {
  // Net tet growth budget over all patches (0 = unlimited). A region whose patch would exceed it
  // absorbs free ∂R vertices, keeping both kernels, until the patch fits (docs/mapping.md §7).
  std::size_t max_added_tets = 0;
  std::size_t max_region_tets = 4000; // give up on a cluster when R grows beyond this
  int max_growth_steps = 400;         // per cluster (and as many vertex absorptions tried to fit the budget)
  // Growth candidates (tets behind the most violated faces) tried per step; <= 1: the worst only.
  // After a failure, plain growth and a 2-candidate lookahead are tried too.
  int growth_lookahead = 4;
  // Bulk growth: each LP growth step also adds the tets behind the |R| / bulk_growth_divisor most
  // violated faces (0 = one tet per step), so the steps to reach a region of n tets grow like
  // log n instead of n when the kernel lies far out.
  std::size_t bulk_growth_divisor = 0;
  int stall_growth_steps = 128;       // give up when the kernel LP slack has not improved for this many steps (0 = never)
  int max_rounds = 8;                 // recompute clusters and retry
  // Wall-clock limit of the whole call (0 = none), checked before each cluster, at each growth step
  // and between the re-insertions of a patch; a cluster interrupted by it is left exactly as it was
  // (counted in failures.time_limit).
  double time_limit_seconds = 0;
  // When the LP growth fails on a cluster with a face on ∂M: grow again towards fixed target points
  // just inside that face, then near its edges inside both it and the ∂M face across the edge
  // (exact visibility), see docs/mapping.md §7.
  bool aimed_growth = true;
  // Stop a growth once the ∂M faces of ∂R alone have no common kernel point in either space (no
  // larger region can have one; counted in failures.mesh_boundary). Off: the growth runs on to its
  // other limits, with the same outcome (tests compare the two).
  bool stop_at_mesh_boundary = true;
  // When a round repairs no cluster, the limits above (stall, growth steps, region size) are
  // multiplied by search_widening and the round is repeated, at most search_escalations times: the
  // first ball with both kernels can lie far beyond the stall limit (docs/mapping.md §7).
  int search_escalations = 2;
  int search_widening = 4;
  // A growth step that adds one tet along a disk of a ball skips the sphere check of ∂R (a shelling
  // step, docs/mapping.md §7); when set, the check runs anyway and a disagreement throws (tests).
  bool verify_shelling = false;
};

struct ConeRepairResult {
  std::size_t clusters = 0;           // clusters found in the first round
  std::size_t patches = 0;            // patches applied
  std::size_t failed_clusters = 0;    // clusters left (last round)
  std::size_t tets_before = 0, tets_after = 0, vertices_added = 0;
  std::size_t max_region = 0;         // largest |R| applied
  // Diagnostics (every attempt of every round): why a cluster was left as it was.
  struct Failures {
    std::size_t region_limit = 0;       // R grew beyond max_region_tets
    std::size_t growth_steps = 0;       // max_growth_steps exhausted
    std::size_t stalled = 0;            // no LP progress for stall_growth_steps
    std::size_t not_ball = 0;           // ∂R not a sphere and nothing left to add
    std::size_t no_growth_face = 0;     // kernel empty but every violated face is on ∂M
    std::size_t mesh_boundary = 0;      // the ∂M faces of ∂R alone have no kernel point: no larger R has one
    std::size_t last_no_target = 0;     // of the growth failures: the target kernel was empty last
    std::size_t last_no_source = 0;     //   ... the source kernel was empty last
    std::size_t reinsertion = 0;        // an interior vertex of R could not be re-inserted
    std::size_t not_positive = 0;       // a new tet not exactly positive in both spaces
    std::size_t face_mismatch = 0;      // new tets do not close onto ∂R (replace_cavity refused them)
    std::size_t budget = 0;             // max_added_tets would be exceeded, also after absorbing ∂R vertices
    std::size_t time_limit = 0;         // time_limit_seconds reached during growth or a patch
  } failures;
  std::size_t attempts = 0, growth_steps = 0, lp_solves = 0;  // work counters
  std::size_t shelling_steps = 0;     // growth steps that kept a ball without the sphere check
  std::size_t search_escalations = 0; // rounds repeated with wider growth limits
  std::size_t absorbed_vertices = 0;  // ∂R vertices absorbed to fit patches into max_added_tets
  double seconds_growth = 0, seconds_patch = 0, seconds_setup = 0;
};

// Multiplies the growth limits of `options` (stall, growth steps, region size) by search_widening,
// `times` times: the search of a widened round (docs/mapping.md §7 "Widening the search"). A widened
// search also grows in bulk (bulk_growth_divisor 64 unless set).
void widen_growth_limits(ConeRepairOptions& options, int times = 1);

// Repairs the clusters of non-positive target tets in place: the mesh is refined, new vertices get
// their target here and the locked property's default (0). A cluster whose region cannot be made a
// ball with strict kernels in both spaces within the limits, or whose patch would exceed
// max_added_tets however many free ∂R vertices R absorbs, is left exactly as it was (counted in
// failed_clusters). Properties attached to the mesh follow every patch (new tets take the values of
// the region tet they were cut from).
ConeRepairResult cone_repair(TetMesh& source, PositionProperty& target, const VertexProperty<std::uint8_t>& locked,
                             const ConeRepairOptions& options = {});

// The last resort of docs/mapping.md §8 step 12: R = the whole mesh. When ∂M is star-shaped in both
// spaces (strict kernel points p in the source, q in the target, verified exactly), every tet is
// replaced by the cones from one apex over the boundary faces, with the interior vertices
// re-inserted as in a patch: a valid map whatever the targets were. Otherwise (or when a
// re-insertion fails, or time_limit_seconds (0 = none) passes during the re-insertions) the mesh is
// left exactly as it was; failures says why (not_ball, last_no_target, last_no_source, reinsertion,
// not_positive, time_limit). patches is 1 when applied. Re-inserting thousands of vertices into one
// cone makes ever flatter tets (no flips restore them): on Kuhn grids of 15³ cells and more a
// re-insertion fails, and the work grows with interior vertices × tets.
ConeRepairResult whole_mesh_cone(TetMesh& source, PositionProperty& target, const VertexProperty<std::uint8_t>& locked,
                                 double time_limit_seconds = 0);

// The same two on flat arrays: each builds the TetMesh, repairs, and writes back the compacted result (tet
// order of the survivors kept, new tets after them or in freed slots; original vertex ids kept, new
// vertices appended with locked 0). Throws Error(BadInput) on inconsistent arrays.
ConeRepairResult cone_repair(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                             const ConeRepairOptions& options = {});
ConeRepairResult whole_mesh_cone(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                                 double time_limit_seconds = 0);

}  // namespace volmap
