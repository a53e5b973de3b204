// volmap/map_extension.hpp — carry a boundary map across boundary edge splits.
// When a mesh is refined by splitting boundary edges at their midpoints (new vertices appended after
// the original ones, each at 0.5*(a+b) of its parent edge (a,b), as volmap-surface-map does), a map
// of the unrefined boundary extends to the refined one by giving each new vertex the midpoint of its
// parents' images. Each image triangle is then split like its source, so in exact arithmetic every
// cone orientation keeps its sign (orient3d is affine in each point); the rounded result must still
// be verified (volmap-surface-map-check) before it is trusted.
#pragma once

#include <cstddef>

#include <volmap/mesh_data.hpp>

namespace volmap {

// `map` covers the boundary vertices with ids < original_vertices of `refined`. Returns the map of
// every boundary vertex of `refined` (sorted by vid). Throws Error(Failed) when a new boundary
// vertex is not the exact midpoint of two older boundary neighbours (not a pure edge-split refinement).
BoundaryMap extend_boundary_map_over_splits(const BoundaryMap& map, const TetMeshData& refined,
                                            std::size_t original_vertices);

}  // namespace volmap
