// volmap/core/topology.hpp — topology analysis of RAW tet arrays, robust to non-manifold and
// inconsistent input (nothing is assumed, nothing throws except out-of-range ids / bad sizes), so a
// checker can report what is wrong instead of failing to build a TetMesh.
// Conventions: half-face 4t+i is the face of tet t opposite local vertex i (outward winding
// kTetFace[i] for VOLMAP-positive tets). A face (vertex triple) is a boundary face when exactly one
// tet has it; faces held by more than two tets are non-manifold faces (neither boundary nor interior).
// Tets repeating a vertex id are counted as degenerate and ignored by every other count (duplicates
// included).
// The boundary surface is the set of boundary faces; its Euler characteristic is chi = V - E + F over
// boundary vertices/edges/faces, its components are vertex-connected components, and its genus is
// (2*components - chi)/2 (meaningful when the surface is a closed 2-manifold).
// The boundary surface counts (edges, vertex links, components, chi) come from analyze_surface_topology,
// the same code the surface checks of a triangle surface use (tetmesh_checks.hpp).
// Implementation: flat arrays, counting sorts and small sorts, union-find; no maps.
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct TopologyReport {
  std::size_t num_vertices = 0;
  std::size_t num_tets = 0;
  std::size_t num_degenerate_tets = 0;   // tets repeating a vertex id (ignored elsewhere)
  std::size_t num_unused_vertices = 0;   // vertices of no (non-degenerate) tet
  std::size_t num_faces = 0;             // distinct vertex triples
  std::size_t num_interior_faces = 0;    // held by exactly two tets
  std::size_t num_inconsistent_faces = 0;  // interior faces whose two half-faces have equal winding
  std::size_t num_nonmanifold_faces = 0;   // held by more than two tets
  std::size_t num_tet_components = 0;      // tets connected through shared faces
  // Tets whose four vertices are those of a lower-numbered tet (k copies count k - 1), and the first
  // such pair by the later tet (kInvalid when none): found through the shared faces.
  std::size_t num_duplicate_tets = 0;
  std::uint32_t example_duplicate_first = 0xFFFFFFFFu, example_duplicate_second = 0xFFFFFFFFu;

  std::size_t num_boundary_faces = 0;
  std::size_t num_boundary_vertices = 0;
  std::size_t num_boundary_edges = 0;
  std::size_t num_border_edges = 0;          // boundary edges with exactly one boundary face
  std::size_t num_overshared_edges = 0;      // boundary edges with more than two boundary faces
  std::size_t num_nonmanifold_boundary_edges = 0;  // != 2 boundary faces (= border + overshared)
  std::size_t num_nonmanifold_boundary_vertices = 0;  // link neither one cycle nor one path (at a border)
  std::size_t num_boundary_components = 0;
  long long boundary_euler = 0;  // chi = V - E + F of the boundary surface
  long long boundary_genus = 0;  // (2*components - chi)/2, rounded down when odd
  bool boundary_genus_defined = false;  // boundary is a closed 2-manifold (then genus is exact)

  // Per-check results.
  bool faces_manifold = true;            // no face held by > 2 tets
  bool orientation_consistent = true;    // no interior face with equal windings
  bool single_tet_component = true;
  bool boundary_edges_manifold = true;   // every boundary edge has exactly two boundary faces
  bool boundary_vertices_manifold = true;
  bool boundary_closed = true;           // no boundary edge with a single face
  bool single_boundary_component = true;
  bool boundary_genus_zero = true;       // genus defined and 0
  bool no_degenerate_tets = true;
  bool no_unused_vertices = true;

  // One example offender per problem (kInvalid = 0xFFFFFFFF when none): a half-face 4t+i, a vertex.
  std::uint32_t example_nonmanifold_face = 0xFFFFFFFFu;
  std::uint32_t example_inconsistent_face = 0xFFFFFFFFu;
  std::uint32_t example_nonmanifold_edge_vertex = 0xFFFFFFFFu;  // one endpoint
  std::uint32_t example_nonmanifold_vertex = 0xFFFFFFFFu;

  // Sorted boundary half-faces 4t+i (their outward triangles are kTetFace[i] of tet t).
  std::vector<std::uint32_t> boundary_half_faces;
};

// Throws Error(BadInput) only when the arrays are malformed (sizes, ids out of range).
TopologyReport analyze_topology(const TetMeshData& data);

// Topology of a triangle surface on flat arrays (tris: 3 ids per triangle, 0-based). Triangles
// repeating a vertex id are counted and ignored by every other count. Edges are vertex pairs; the
// link of a vertex (the opposite edges of its triangles) must be one cycle or one path (at a border).
struct SurfaceTopology {
  std::size_t num_vertices = 0;          // vertices in the arrays
  std::size_t num_used_vertices = 0;     // referenced by a valid triangle
  std::size_t num_triangles = 0;         // valid triangles (three distinct ids)
  std::size_t num_repeated_id_triangles = 0;  // triangles repeating a vertex id (ignored elsewhere)
  std::size_t num_edges = 0;
  std::size_t num_border_edges = 0;      // on one triangle
  std::size_t num_overshared_edges = 0;  // on more than two triangles
  std::size_t num_inconsistent_edges = 0;  // on two triangles that traverse it the same way
  std::size_t num_nonmanifold_vertices = 0;  // link is not a single cycle / single path
  std::size_t num_components = 0;        // vertex-connected components of the triangles
  long long euler = 0;                   // V - E + F (used vertices)
  bool genus_defined = false;            // closed 2-manifold: genus = sum over components (2 - chi_i)/2
  long long genus = 0;
  std::size_t num_nonzero_genus_components = 0;
  // Examples (0xFFFFFFFF when none): the lower endpoint of the first edge (by (lower, higher) id)
  // not on exactly two triangles, and the lowest non-manifold vertex.
  std::uint32_t example_nonmanifold_edge_vertex = 0xFFFFFFFFu;
  std::uint32_t example_nonmanifold_vertex = 0xFFFFFFFFu;
};

// Throws Error(BadInput) for ids out of range or a size that is not a multiple of 3.
SurfaceTopology analyze_surface_topology(std::size_t num_vertices, const std::vector<std::uint32_t>& tris);

// The triangles around one vertex v as a closed fan; one object serves vertex after vertex (its
// scratch is reused). Each triangle containing v is (v, next, prev) as seen from its corner v.
class VertexFan {
 public:
  // True when the m triangles tris[3·incident[i] ..] (i < m, each holding v) chain into one cycle:
  // every triangle's next is the prev of exactly one triangle, and stepping so goes once round all
  // m of them. A triangle repeating an id is never part of a closed fan. Then ring() lists the link
  // vertices in that order: triangle k of the cycle is (v, ring[k+1], ring[k]), indices mod m, and
  // every edge (v, w) lies on exactly two of the triangles, traversed in opposite directions.
  bool close(const std::uint32_t* tris, std::uint32_t v, const std::uint32_t* incident, std::size_t m);
  const std::vector<std::uint32_t>& ring() const { return ring_; }

 private:
  std::vector<std::uint32_t> next_, prev_, ring_;
};

}  // namespace volmap
