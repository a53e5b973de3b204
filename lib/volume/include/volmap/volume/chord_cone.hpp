// volmap/volume/chord_cone.hpp — B0's vertex cone (docs/mapping.md §4): the star of a boundary
// vertex v is replaced by the cone from one new interior vertex w over the star's boundary (the
// faces opposite v, and the faces of ∂M at v). Every interior edge and face at v disappears at once,
// for |∂M faces at v| new tets — cheaper than splitting several blocking chords at v one by one.
// w is the Chebyshev centre of the star's strict kernel in the source (kernel_lp.hpp), verified
// exactly; every new tet holds w, so the cone makes no chord and no fixed tet. ∂M is unchanged
// (v keeps its faces of ∂M), vertex ids never change, w is appended (vertex properties: defaults).
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>

namespace volmap {

// The number of faces of ∂M at v in its star (the tets a cone at v adds), 0 for an interior vertex.
std::size_t boundary_faces_at(const TetMesh& mesh, std::uint32_t v);

// Replaces the star of the boundary vertex v by the cone from a new vertex at a verified strict
// kernel point of the star, when one exists and no new tet is much flatter than the flattest tet of
// the star (kFixShapeRatio, chord_rules.hpp). Returns false, leaving the mesh untouched, otherwise.
bool cone_vertex_star(TetMesh& mesh, std::uint32_t v);

}  // namespace volmap
