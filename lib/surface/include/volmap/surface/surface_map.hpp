// volmap/surface/surface_map.hpp — boundary maps of a genus-0 tet mesh onto a base domain
// (volmap-reference.md §4, VOLMAP paper §5 and Fig. 4), verified with the exact check.
//
// Algorithm (the boundary travels as an OpenMesh TriMesh, <volmap/surface/boundary_surface.hpp>):
//  1. Node vertices: the boundary vertex nearest to each node's probe (ties -> smallest vid; a vertex
//     already taken by an earlier node is skipped, so nodes always get distinct vertices).
//  2. Arcs, in the domain's order: Dijkstra shortest paths (edge length) over boundary edges, never
//     entering a vertex of an earlier arc or another node; the path must leave/enter each node inside
//     the sector that the domain's rotation system prescribes between the arcs already traced there,
//     so the embedded graph always has the domain's cyclic order of arcs around every node.
//     Star: the 6 face diagonals are traced as one path each and cut at h = floor(|p|/2); p[h] is
//     the face node.
//  3. Chord splits (new vertices appended, ids stable; ChordSplitRule): a chord is a boundary edge
//     off every arc whose two ends are graph vertices. The lean rule (default) splits, after the
//     last arc, only the chords whose two ends lie on one straight line of the domain: every other
//     chord crosses its chart's convex polygon, which Tutte's embedding allows. The reference's rule
//     splits every chord after each arc, which also keeps a free path between any two arcs (paper
//     Fig. 4) but multiplies the boundary of coarse meshes (coarse tentacles -> star: 2,165 new
//     vertices on 1,010). The splits are made on the surface (OpenMesh's 2-to-4 split) and replayed
//     at the end on a TetMesh with TetMesh::split_edge (all tets around the edge), which appends
//     vertices in the same order; the new tets are checked exactly.
//     Attempts, each from the input surface, in groups: the reference arc order, then a spanning
//     tree of the nodes first (the reference order can close a cycle, e.g. the octahedron's
//     equator, with two still isolated nodes on the same side); surfaces too coarse for the domain
//     are then retried after 1 and 2 rounds of splitting every boundary edge (on the tets as well).
//     In a group both rules run; of the maps that pass the exact check the one with fewer tets
//     wins (the lean rule's on a tie), and the first group with a map ends the search.
//  4. Charts: boundary triangles flooded between arcs, each matched to its domain face by the side of
//     its arcs; Tutte's embedding (uniform weights) in the face plane with the chart boundary on the
//     convex face polygon (arc vertices spaced by arc length), one sparse LDL^T solve per chart. A
//     chart that rounding leaves inverted (long thin limbs shrink exponentially under Tutte) is
//     re-solved with stretch-reducing positive weights until every triangle is positive (exact).
//  5. Verification: the exact surface-map check on the numbers that will be written.
//  6. Fewer splits: a map whose splits add more than 1 % to the tets is searched again (steps 1–5) with the
//     node probes turned by each of the other 23 rotations of the bounding box (with_rotated_probes),
//     and the map whose mesh has the fewest tets is kept (the unrotated one on a tie). The splits
//     depend on where the nodes land: on coarse meshes one placement needs many fewer than another
//     (octopus-low → star: 389 new vertices unrotated, 287 rotated).
//  7. When the best rotation still adds more than 1 %, the search goes on with the probes pulled
//     towards the box centre (with_pulled_probes, by each of kProbePulls: 90 % of their offset down
//     to 10 %), each in the 24 rotations, until a map adds at most 1 %; the fewest tets win (the
//     earlier map on a tie).
//     Nodes at the very extremities of a thin or coarse part sit where arcs must squeeze past
//     each other; a little inside there is room (octopus-low → star: 2,129 tets rotated, 1,293
//     pulled, from 1,140). Maps adding at most 1 % are unchanged by steps 6 and 7, so are the
//     reference's (reference_chord_splits). In both steps a placement whose traced graph already
//     needs at least as many tets as the best map is dropped before its charts (the costly part).
#pragma once

#include <volmap/surface/domain.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/surface/surface_map_check.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

struct SurfaceMapResult {
  TetMeshData mesh;            // the (possibly refined) tet mesh the map refers to
  BoundaryMap map;             // one entry per boundary vertex of `mesh`, sorted by vid
  std::size_t added_vertices = 0;
  std::vector<std::uint32_t> node_vertices;  // vertex of every domain node
  std::size_t collided_nodes = 0;            // nodes whose nearest vertex was taken by an earlier node
  SurfaceMapCheckResult check;               // the exact check of `map` on `mesh`
  std::string attempt;                       // the attempt that produced the map (arc order, subdivisions)
  std::vector<std::string> failed_attempts;  // "<attempt>: <reason>" for every earlier attempt
};

// Whether `map`'s mesh has at most (1 + growth) times `input_tets` tets.
inline bool adds_at_most(const SurfaceMapResult& map, std::size_t input_tets, double growth) {
  return double(map.mesh.num_tets()) <= (1 + growth) * double(input_tets);
}

// Which chords (boundary edges off every arc joining two graph vertices) are split (step 3 above).
enum class ChordSplitRule {
  OnlyAlongOneLine,  // lean: after the last arc, the chords whose ends lie on one line of the domain
  AfterEveryArc,     // the reference's: every chord, after each arc
};

// Steps 6 and 7 run when the splits add more than this fraction of the input's tets: below it the
// growth does not matter and more searches would multiply the time (armadillo → octa: 72 of 72,923
// tets). Step 7 stops at the first map within it. The sphere map keeps its cube map within it too.
inline constexpr double kPlacementSearchGrowth = 0.01;

// Step 7's pulls (with_pulled_probes), tried in this order: the nearer the extremities, the more
// the map looks like the reference's.
inline constexpr double kProbePulls[] = {0.9, 0.75, 0.6, 0.5, 0.4, 0.25, 0.1};

struct SurfaceMapOptions {
  // true: only the reference's chord rule is tried (its split counts, e.g. to compare with VOLMAP's
  // own surface maps); false: both rules, the map whose mesh has fewer tets kept (step 3 above).
  bool reference_chord_splits = false;
  // Steps 6 and 7: when the splits add more than 1 % to the tets, also try the other probe
  // placements and keep the map with the fewest tets (never with reference_chord_splits: the
  // reference's maps).
  bool search_placements = true;
};

// Maps the boundary of `mesh` onto `domain`. Throws Error(Failed) when no attempt traces the arcs,
// matches the domain's embedding and passes the exact check; Error(BadInput) for a mesh whose
// boundary is not a closed manifold surface.
SurfaceMapResult map_surface_to_domain(const TetMeshData& mesh, const Domain& domain,
                                       const SurfaceMapOptions& options = {});

// Sphere maps: the central projection of a star-shaped map (in practice the cube map) onto the
// sphere of radius `radius` around `centre`, judged like every map: every cone positive about the
// centroid of the image points (volmap-reference.md §5). The projection keeps the cones positive
// about the centre; when a thin triangle's plane passes between the centre and the centroid, the
// image is balanced (relaxation on the sphere and re-centring, both keeping every cone positive
// about the centre, exact) until the centroid is inside every cone. The result is re-checked with
// check_surface_map (sphere options). Throws Error(Failed) when that does not converge.
SurfaceMapResult project_to_sphere(const SurfaceMapResult& star_shaped, const Point3& centre, double radius);

// The sphere map of `volmap-surface-map sphere`: a star-shaped map projected and balanced
// (project_to_sphere). First the cube map; when it adds more than kPlacementSearchGrowth to the tets
// or does not balance, also the map onto the regular tetrahedron on the cube's alternate corners
// (fewer nodes and arcs, so fewer splits on coarse surfaces); the one whose mesh has fewer tets is
// kept (the cube's on a tie). The cube's image is the rounder one, so it is kept where the
// tetrahedron could only save a few tets. When balancing stalls, the longest edges of the
// triangles still inverted about the centroid are split and the map balanced again (within twice
// the balancing rounds of one projection). Only when neither balances is the cube map by the
// reference's chord rule projected. Throws Error(Failed) with every reason when nothing balances.
SurfaceMapResult map_surface_to_sphere(const TetMeshData& mesh, const Point3& centre, double radius,
                                       const SurfaceMapOptions& options = {});

// The sphere domain used by `volmap-surface-map sphere`: centre (50,50,50), radius 50.
inline constexpr double kSphereCentre[3] = {50, 50, 50};
inline constexpr double kSphereRadius = 50;

}  // namespace volmap
