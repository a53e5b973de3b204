// volmap/surface/map_extension.hpp — carry a boundary map across boundary edge splits.
// When a mesh is refined by splitting boundary edges at their midpoints (new vertices appended after
// the original ones, each at 0.5*(a+b) of the edge (a,b) it splits, as volmap-surface-map does), a map
// of the original boundary extends to the refined one by giving each new vertex the midpoint of its
// parents' images. Each image triangle is then split like its source, so in exact arithmetic every
// cone orientation keeps its sign (orient3d is affine in each point); the rounded result must still
// be verified (volmap-surface-map-check) before it is trusted.
#pragma once

#include <volmap/core/mesh_data.hpp>

namespace volmap {

// `map` is a map of `original`'s boundary; `refined` is `original` after midpoint splits (same first
// vertices, new ones appended). Replays the splits on the original boundary triangles in vertex-id
// order and returns the map of every boundary vertex of `refined` (sorted by vid). Throws
// Error(Failed) when the refined boundary is not the result of such splits.
BoundaryMap extend_boundary_map_over_splits(const BoundaryMap& map, const TetMeshData& original,
                                            const TetMeshData& refined);

}  // namespace volmap
