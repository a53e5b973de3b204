// volmap/volume/bad_tet_split.hpp — refinement where the untanglers stall (docs/mapping.md §8
// step 8): every interior edge of every non-positive tet is split, so the local untanglers that
// follow have more free vertices exactly where the map is tangled.
// Conventions: a MapState without tombstones. An edge is split at a point inside it (its source
// midpoint, nudged when rounding would flatten a child: chord_split.hpp), so every child is exactly
// positive in the source; ∂M is never touched (edges of ∂M are not split). The new vertex is free
// and its target starts at the midpoint of the edge's targets, where its children are as inverted
// as their parent was: the split alone never lowers the count, the untanglers run after it must.
// The mesh is compacted on return; input ids never change (new vertices are appended).
#pragma once

#include <volmap/volume/map_state.hpp>

#include <cstddef>

namespace volmap {

struct BadTetSplitResult {
  std::size_t bad_tets = 0;       // non-positive tets found
  std::size_t edges_split = 0;
  std::size_t edges_skipped = 0;  // no split point kept every child positive (near-degenerate)
  std::size_t tets_before = 0, tets_after = 0;
};

// Splits the interior edges of the non-positive tets, at most max_edges of them (0 = all), the
// longest (in the target) first.
BadTetSplitResult split_edges_of_nonpositive_tets(MapState& state, std::size_t max_edges = 0);

}  // namespace volmap
