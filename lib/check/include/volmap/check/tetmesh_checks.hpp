// volmap/check/tetmesh_checks.hpp — the seven VOLMAP input checks of a tet mesh (volmap-reference.md §8,
// `tetmesh_checks`), done exactly on every tet, and the five surface checks of a triangle surface
// (the input of tetrahedralization).
//
// Tet mesh checks, in this order (keys used in JSON):
//   orientation        every tet VOLMAP-positive: orient3d(v0,v1,v2,v3) > 0 (exact, all tets; quirk 18:
//                      VOLMAP looks at tet 0 only). Classified as all positive / coherently opposite
//                      (no positive tet, some negative) / mixed (both signs present); the detail is
//                      describe_orientation's sentence (orientation.hpp).
//   volume             no zero-volume tet (exact orient3d == 0; repeated vertex ids count as zero).
//   genus              the boundary surface is a closed 2-manifold of genus 0.
//   components         one tet component (tets joined through faces), one boundary shell, no
//                      vertex outside every tet.
//   manifold           no face shared by more than two tets, every boundary edge on at most two
//                      boundary faces, every boundary vertex with a single fan.
//   closed             the boundary exists and has no border edge (edge of a single boundary face).
//   self_intersections the boundary surface is embedded (see self_intersection.hpp).
// Surface checks: genus, components, manifold, closed, self_intersections (same meanings on the
// surface itself; faces must be triangles).
// Nothing here throws on bad topology: problems are reported. Error(BadInput) is thrown only for
// malformed arrays (ids out of range, non-finite coordinates).
#pragma once

#include <volmap/check/orientation.hpp>
#include <volmap/io/io_surface.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/predicates.hpp>
#include <volmap/check/self_intersection.hpp>
#include <volmap/core/topology.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

struct CheckItem {
  std::string key;     // "orientation", "volume", "genus", "components", "manifold", "closed", "self_intersections"
  bool passed = false;
  std::string detail;  // one line with the figures (and the reason when failed)
};

struct TetMeshCheckOptions {
  SelfIntersectionOptions self_intersection;
};

struct TetMeshCheckReport {
  std::size_t num_vertices = 0;
  std::size_t num_tets = 0;
  TetSignCounts signs;                        // exact orient3d signs over every tet
  OrientationClass orientation = OrientationClass::Empty;
  TopologyReport topology;                    // analyze_topology (boundary faces, components, ...)
  SelfIntersectionResult self_intersections;  // of the boundary faces
  std::vector<CheckItem> checks;              // the seven checks, in the order above

  bool all_passed() const;
  const CheckItem& check(const std::string& key) const;  // throws std::out_of_range when unknown
};

// Runs the seven checks on every tet. Throws Error(BadInput) for ids out of range / non-finite
// coordinates / sizes that are not multiples of 3 and 4.
TetMeshCheckReport check_tet_mesh(const TetMeshData& mesh, const TetMeshCheckOptions& options = {});

// Swaps local vertices 0 and 1 of every tet (orient3d changes sign exactly; vertex ids, labels, tet
// order untouched). This is what `--fix` applies to a coherently opposite mesh.
void flip_all_tets(TetMeshData& mesh);

// ---- surfaces ------------------------------------------------------------------------------------
// SurfaceTopology and analyze_surface_topology: topology.hpp (shared with analyze_topology).

struct SurfaceCheckReport {
  SurfaceTopology topology;
  SelfIntersectionResult self_intersections;
  std::vector<CheckItem> checks;  // genus, components, manifold, closed, self_intersections
  bool all_passed() const;
  const CheckItem& check(const std::string& key) const;
};

// The surface checks a tetrahedralizer input must pass (closed, manifold, one component, genus 0,
// embedded). xyz: 3 doubles per vertex; tris: 3 ids per triangle.
SurfaceCheckReport check_triangle_surface(const std::vector<double>& xyz, const std::vector<std::uint32_t>& tris,
                                          const SelfIntersectionOptions& options = {});

// Same on a surface as read by read_surface (io_surface.hpp). This is the gate a tetrahedralizer
// input must pass; volmap-tetmesh-check runs it on .off/.obj/.stl/.ply inputs.
SurfaceCheckReport check_surface(const SurfaceData& surface, const SelfIntersectionOptions& options = {});

}  // namespace volmap
