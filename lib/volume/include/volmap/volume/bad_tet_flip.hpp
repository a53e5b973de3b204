// volmap/volume/bad_tet_flip.hpp — flips that remove non-positive tets without a new vertex
// (docs/mapping.md §8 step 8): for each non-positive target tet, an edge removal of one of its
// interior edges (n tets -> 2n-4) or a 2-3 flip of one of its interior faces, admissible only when
// every new tet is exactly positive (volmap predicates) in the source AND in the target. A move
// therefore lowers the exact count of non-positive tets by at least one and changes no other tet:
// the stage is monotone and never grows the mesh by more than n-4 tets per removal.
// Conventions: a MapState without tombstones; ∂M is never touched (the edited tets fill the same
// cavity); no vertex is added or moved; the mesh is compacted on return (vertex ids never change).
// Among admissible edge-removal triangulations the one whose worst new tet has the best source shape
// is taken (tet_shape, chord_rules.hpp), never flatter than kFixShapeRatio times the worst tet it
// replaces, so the refined source stays a usable rest shape.
#pragma once

#include <volmap/volume/map_state.hpp>

#include <cstddef>

namespace volmap {

struct BadTetFlipResult {
  std::size_t bad_before = 0, bad_after = 0;
  std::size_t edges_removed = 0;  // edge removals (including 3-2 flips)
  std::size_t faces_flipped = 0;  // 2-3 flips
  std::size_t tets_before = 0, tets_after = 0;
};

// Passes over the non-positive tets until a pass makes no move (at most max_passes); rings of more
// than max_ring tets are not removed.
BadTetFlipResult flip_nonpositive_tets(MapState& state, int max_passes = 4, int max_ring = 10);

}  // namespace volmap
