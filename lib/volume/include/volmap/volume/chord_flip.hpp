// volmap/volume/chord_flip.hpp — the connectivity fixes of B0 (docs/mapping.md §4): remove a
// blocking chord edge by an edge removal (n tets -> 2n-4, TetMesh::remove_edge) or a blocking chord
// face by a 2-3 flip (2 tets -> 3), without a new vertex. A fix is admissible only when every new tet
// is exactly positive in the source (volmap predicates) and it creates no blocking simplex under the
// rules of chord_rules.hpp: no new chord edge or chord face that blocks, no new tet with four locked
// vertices whose fixed image is not positive, and no new tet much flatter than the flattest tet it
// replaces (kFixShapeRatio). ∂M is never touched (the edited tets fill the same cavity), vertex
// ids never change; a removal of degree 3 leaves a tombstone.
#pragma once

#include <volmap/core/tet_mesh.hpp>
#include <volmap/volume/chord_rules.hpp>

#include <array>
#include <cstdint>

namespace volmap {

// Removes the interior edge (a, b) by the admissible triangulation of its ring whose worst new tet
// has the best shape (volume over the cube of the RMS edge length, in double; dynamic programming
// over the ring polygon). Returns false, leaving the mesh untouched, when (a, b) is not an interior
// edge, its ring has more than max_ring (at most 31) vertices, or no triangulation is admissible. `hint`: a tet
// that may hold the edge (checked; otherwise the edge is searched from a's star).
inline constexpr int kChordRingLimit = 12;  // remove_chord_edge's default max_ring
bool remove_chord_edge(TetMesh& mesh, const ChordRules& rules, std::uint32_t a, std::uint32_t b, int max_ring = kChordRingLimit,
                       TetId hint = TetId::kInvalid);

// Replaces the two tets on the interior face (a, b, c) by the three around the edge joining their
// apexes, when admissible. Returns false, leaving the mesh untouched, otherwise.
bool flip_chord_face(TetMesh& mesh, const ChordRules& rules, const std::array<std::uint32_t, 3>& face);

}  // namespace volmap
