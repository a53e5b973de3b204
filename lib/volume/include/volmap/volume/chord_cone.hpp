// volmap/volume/chord_cone.hpp — B0's cone patches (docs/mapping.md §4): a region R of the source
// made of whole stars of boundary vertices is replaced by the cones from one new interior vertex w
// over ∂R (the faces of R's tets not shared with another tet of R, ∂M's faces included). Every
// interior edge and face at those vertices disappears at once; every new tet holds w, so the patch
// makes no chord and no fixed tet. It adds |∂R| − |R| tets, which is negative where R has more tets
// than faces (coarse meshes whose tets mostly touch ∂M). w is the Chebyshev centre of ∂R's strict
// kernel in the source (kernel_lp.hpp), verified exactly. A region may not swallow a vertex (every
// vertex of R stays on ∂R: ids are kept), and no new tet may be much flatter than the flattest tet
// of R (kFixShapeRatio, chord_rules.hpp). ∂M is unchanged, vertex ids never change, w is appended
// (vertex properties: defaults), the new tets take R's slots first (each with the label and tet
// properties of the R tet whose face it covers).
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace volmap {

// The number of faces of ∂M at v in its star (the tets a cone over v's star adds), 0 for an
// interior vertex.
std::size_t boundary_faces_at(const TetMesh& mesh, std::uint32_t v);

// The cone over the star of the boundary vertex v alone. Returns false, leaving the mesh untouched,
// when the star has no admissible cone.
bool cone_vertex_star(TetMesh& mesh, std::uint32_t v);

struct ConeRegionLimits {
  std::size_t max_tets = 1200;  // |R|
  int max_steps = 64;           // stars tried after the seed's (accepted or not)
};

// What a patch must beat: chords(v) lists the pending chords at vertex v as (chord id, what fixing
// that chord otherwise costs in tets). A patch is committed only when it costs fewer tets than the
// chords it takes away.
using PendingChordsAt = std::function<std::vector<std::pair<std::size_t, long long>>(std::uint32_t)>;

// Grows R from the star of the boundary vertex `seed` by the stars of boundary vertices of R, most
// costly pending chords first; a star joins when the grown region still has an admissible cone and
// its cost grows by at most the chords it takes away that no vertex of R had taken yet. Commits the
// last admissible region when it beats its chords. Returns false, leaving the mesh untouched,
// otherwise. On success *added is |∂R| − |R| and *touched the vertices of R.
bool cone_region(TetMesh& mesh, std::uint32_t seed, const PendingChordsAt& chords, const ConeRegionLimits& limits, long long* added,
                 std::vector<std::uint32_t>* touched);

}  // namespace volmap
