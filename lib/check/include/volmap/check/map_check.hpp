// volmap/check/map_check.hpp — exact certification of a volume map (volmap-reference.md §6, mapping.md §1).
// Orientation: VOLMAP-positive means Shewchuk orient3d(v0,v1,v2,v3) > 0. Every sign is exact
// (volmap::orient3d_tets). Both meshes are evaluated in the INPUT tet's vertex order: output tet
// positions are looked up by the input tet's vertex ids, so an output that lists a tet's vertices in
// another order (or its tets in another order) is checked exactly like VOLMAP's volume_mapping_check.
// Relative mode (default, VOLMAP's): tet t is bad iff sign_in(t) == 0, sign_out(t) == 0 or the signs
// differ (signs are compared, never multiplied). Absolute mode additionally requires the output tet,
// in the output file's own vertex order, to be strictly positive.
// Certified (the only "valid" verdict) iff there is no bad tet AND every input tet is positive AND
// (when a boundary map is given) every boundary vertex sits exactly on its prescribed position.
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/predicates_rational.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

// How two meshes' connectivity corresponds.
enum class ConnectivityMatch {
  Identical,     // same tet list, same per-tet vertex order
  Reordered,     // same tet (vertex-set) list by index; some tets list their vertices in another order
  Permuted,      // same multiset of tet vertex sets, tets in another order
};

struct ConnectivityPairing {
  ConnectivityMatch match = ConnectivityMatch::Identical;
  // For Permuted only: output_tet[t] = index in `out` of input tet t's vertex set (empty otherwise,
  // meaning tet t pairs with output tet t).
  std::vector<std::uint64_t> output_tet;
};

// Throws Error(BadInput) with a one-line reason when the two meshes are not the same tet complex
// over the same vertex ids (vertex count, tet count, an id out of range, or an input tet's vertex
// set missing from `out`).
ConnectivityPairing match_connectivity(const TetMeshData& in, const TetMeshData& out);

struct MapCheckOptions {
  bool absolute = false;                 // also require orient3d(out tet in out's own order) > 0
  std::size_t max_reported_bad = 20;     // ids of the first bad tets kept in the report
  bool parallel = true;                  // split the batch predicate over TBB workers
};

struct MapCheckReport {
  std::size_t num_tets = 0;
  ConnectivityMatch connectivity = ConnectivityMatch::Identical;
  bool rational = false;  // signs computed on exact rational coordinates
  // Absolute signs of the input and of the output (both in the input's per-tet vertex order).
  TetSignCounts input;
  TetSignCounts output;
  // Output in its own file order (absolute mode only; equals `output` when connectivity is Identical).
  TetSignCounts output_own_order;
  // Relative comparison per tet: same nonzero sign / output or input degenerate / opposite signs.
  std::size_t relative_positive = 0;
  std::size_t relative_zero = 0;
  std::size_t relative_negative = 0;
  std::size_t num_bad = 0;                 // tets failing the (relative or absolute) test
  std::vector<std::uint64_t> first_bad;    // up to max_reported_bad ids, increasing
  // Boundary check (when a map was given).
  bool boundary_checked = false;
  std::size_t boundary_mismatches = 0;
  std::vector<std::uint32_t> first_boundary_mismatches;  // vertex ids
  bool input_all_positive() const { return input.positive == num_tets; }
  bool map_valid() const { return num_bad == 0; }  // VOLMAP's verdict (relative unless absolute)
  bool certified() const { return map_valid() && input_all_positive() && boundary_mismatches == 0; }
};

// Exact check on doubles. `boundary` may be null. Throws Error(BadInput) on mismatched connectivity,
// non-finite coordinates, or a boundary map with out-of-range ids.
MapCheckReport check_map(const TetMeshData& in, const TetMeshData& out, const BoundaryMap* boundary = nullptr,
                         const MapCheckOptions& options = {});

// Exact check on rational coordinates (3 per vertex, mesh order). Either side may come from doubles
// converted exactly (rationals_from_doubles). Connectivity comes from the meshes. With a boundary map,
// the output rationals must equal the map's doubles exactly.
MapCheckReport check_map_rational(const TetMeshData& in, const std::vector<Rational>& in_xyz,
                                  const TetMeshData& out, const std::vector<Rational>& out_xyz,
                                  const BoundaryMap* boundary = nullptr, const MapCheckOptions& options = {});

// orient3d_tets split into chunks over TBB workers (same result as the serial call). Throws
// Error(BadInput) naming `what` when coordinates are non-finite or ids out of range.
TetSignCounts orient3d_tets_parallel(const double* xyz, std::size_t num_vertices, const std::uint32_t* tets,
                                     std::size_t num_tets, std::int8_t* signs, const char* what = "mesh");

// Exact conversion of doubles to rationals (every finite double is a dyadic rational).
std::vector<Rational> rationals_from_doubles(const std::vector<double>& xyz);

}  // namespace volmap
