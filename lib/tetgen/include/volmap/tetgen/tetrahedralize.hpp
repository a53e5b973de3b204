// volmap/tetgen/tetrahedralize.hpp — closed triangle surface -> tet mesh with TetGen (libtet), the way
// VOLMAP's `tetmesh_generation` does it (switches p, q<quality>, Y: the boundary is preserved, no
// Steiner points on it; `coarse` drops q: no quality refinement, so most tets touch the boundary), written in the VOLMAP orientation convention (orient3d(v0,v1,v2,v3) > 0;
// TetGen's own tets have the opposite sign and are flipped after an exact check of each one).
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

// A triangle soup with shared vertices (quads and polygons are fan-triangulated on reading).
struct TriangleSurface {
  std::vector<double> xyz;           // 3 per vertex
  std::vector<std::uint32_t> tris;   // 3 per triangle, 0-based
  std::size_t rejected_faces = 0;    // faces a reader could not add (non-manifold edge/vertex)
  std::size_t num_vertices() const { return xyz.size() / 3; }
  std::size_t num_triangles() const { return tris.size() / 3; }
};

// Reads .obj/.off/.stl (ASCII or binary)/.ply (ASCII or binary, triangle strips too) through
// <volmap/io_surface.hpp> (OpenMesh for STL). Throws Error(Io / BadInput / Unsupported).
TriangleSurface read_triangle_surface(const std::string& path);

// Topological problems that make a surface unusable for a genus-0 volume map, empty when none:
// not closed, not manifold, several components, genus > 0. (Self-intersections are found by TetGen,
// which refuses them.)
std::string surface_topology_problem(const TriangleSurface& surface);

struct TetrahedralizeOptions {
  double quality = 1.414;  // radius-edge ratio bound (TetGen q)
  double max_volume = 0;   // TetGen a<V> when > 0
  bool coarse = false;     // no quality refinement (TetGen without q; `quality` is ignored)
  double time_limit_seconds = 0;  // > 0: TetGen is stopped after this long (Error(Failed))
};

// Throws Error(BadInput) for topological problems, Error(Failed) with TetGen's reason when TetGen
// refuses the input (self-intersections, tiny features, ...), a produced tet is degenerate, or the
// time limit passed.
TetMeshData tetrahedralize_surface(const TriangleSurface& surface, const TetrahedralizeOptions& options = {});

}  // namespace volmap
