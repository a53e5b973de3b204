// volmap/volume/tutte3d.hpp — the Tutte 3D baseline (VOLMAP's "Tutte3D"; mapping.md §2): every interior
// vertex at the plain average of its edge neighbours (uniform combinatorial Laplacian), boundary
// vertices fixed (hard Dirichlet) at the boundary map's positions.
// System: L_II·X_I = −L_IB·X_B with L the graph Laplacian over the mesh's UNIQUE edges; one sparse
// factorisation of L_II (Eigen SimplicialLDLT, AMD ordering) solved for the 3 coordinate columns at once.
// Conventions: vertex ids 0-based; positions are 3 doubles per vertex (x,y,z), in mesh order.
// No guarantee of injectivity (Floater & Pham-Trong 2006): callers certify with volmap::check_map.
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

// Flat, sorted list of the unique undirected edges of a tet mesh: pairs (a,b) with a < b, stored
// as 2*E ids, sorted lexicographically. Throws Error(BadInput) when a tet references an id >=
// num_vertices() or repeats a vertex.
std::vector<std::uint32_t> unique_tet_edges(const TetMeshData& mesh);
// The same list from a TetMesh's edges (tombstones are not edges).
std::vector<std::uint32_t> unique_tet_edges(const TetMesh& mesh);

enum class TutteWeights { Uniform };
// Eigen SimplicialLLT / SimplicialLDLT (AMD ordering), or ConjugateGradient (Jacobi preconditioner,
// relative residual 1e-12; "factorization" time = preconditioner setup) for comparison in bench/.
// CHOLMOD is not installed on this machine (no SuiteSparse headers), so it is not offered.
enum class SparseFactorization { LLT, LDLT, ConjugateGradient };

struct Tutte3dOptions {
  TutteWeights weights = TutteWeights::Uniform;
  SparseFactorization factorization = SparseFactorization::LLT;
};

// Wall-clock seconds per phase.
struct Tutte3dTimings {
  double edges = 0;          // unique edge extraction (0 when edges were given)
  double assembly = 0;       // L_II (compressed columns, lower triangle) and the 3 right-hand sides
  double factorization = 0;  // symbolic (AMD) + numeric LDLᵀ
  double solve = 0;          // the 3 triangular solves and scatter back
  double total() const { return edges + assembly + factorization + solve; }
};

struct Tutte3dResult {
  std::vector<double> xyz;  // 3 * num_vertices: boundary vertices exactly at the map's doubles
  std::size_t num_edges = 0;
  std::size_t num_free = 0;   // interior (solved) vertices
  std::size_t num_fixed = 0;  // locked (Dirichlet) vertices: the boundary
  Tutte3dTimings timings;
};

// Interior solve for a given locked mask, reusable by other mappers. `edges` is a unique edge list
// (as from unique_tet_edges); `locked[v]` != 0 marks vertex v as Dirichlet: its xyz is kept as given.
// Every other vertex is moved to the uniform-Laplacian (Tutte) solution. Throws Error(Failed) when
// the system is singular (a free component with no locked vertex), Error(BadInput) on size mismatch.
Tutte3dTimings solve_uniform_laplacian(std::size_t num_vertices, const std::vector<std::uint32_t>& edges,
                                       const std::vector<std::uint8_t>& locked, std::vector<double>& xyz,
                                       SparseFactorization factorization = SparseFactorization::LLT);

// Tutte 3D map of `mesh` with boundary vertex `map.vids[k]` fixed at `map.xyz[3k..3k+2]`. The map
// is not validated against the mesh's boundary here (use validate_boundary_map): any vid set is
// accepted as the Dirichlet set. Throws Error(BadInput) for vids out of range or repeated.
Tutte3dResult tutte3d(const TetMeshData& mesh, const BoundaryMap& map, const Tutte3dOptions& options = {});

}  // namespace volmap
