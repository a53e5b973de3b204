// volmap/volume/chord_split.hpp — B0 of docs/mapping.md §4: split chord edges (at the source midpoint)
// and chord faces (at the source centroid) so that no interior simplex has all its vertices on the
// boundary. Conventions: VOLMAP-positive tets (orient3d(v0,v1,v2,v3) > 0). The splits are
// TetMesh::split_edge / split_face: every child replaces one vertex of its parent by the new interior
// vertex, so orient3d(child) = λ·orient3d(parent) > 0; every child is verified exactly before the
// split (the point is nudged along the simplex when rounding to doubles would break it). Vertex ids
// never change; new vertices take new slots (vertex properties: their defaults, e.g. locked 0).
#pragma once

#include <volmap/core/mesh_data.hpp>
#include <volmap/core/tet_mesh.hpp>
#include <volmap/volume/chord_rules.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct ChordSplitResult {
  std::size_t edges_split = 0;
  std::size_t faces_split = 0;
  std::size_t edges_removed = 0;  // by an edge removal flip (remove_blocking_chords only)
  std::size_t faces_flipped = 0;  // by a 2-3 flip (remove_blocking_chords only)
  std::size_t cone_patches = 0;   // regions replaced by a cone (remove_blocking_chords only)
  std::size_t tets_before = 0;
  std::size_t tets_after = 0;
  std::size_t vertices_added = 0;
  // Simplices left unsplit because no verified point keeps every child exactly positive (the
  // centroid, nudged barycentric weights and the strict kernel of the children's faces all failed:
  // a sliver parent); the mesh is unchanged there.
  std::size_t splits_refused = 0;
};

// Splits `edges` first, then those of `faces` that still exist. Edges/faces are given by vertex ids;
// simplices not found (already split) are skipped, and so are those without a verified split point
// (splits_refused).
ChordSplitResult split_chords(TetMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces);

// B0 as the mapper runs it (docs/mapping.md §4): the cheapest admissible fix for each blocking
// chord. Edges: an edge removal (chord_flip.hpp; n -> 2n-4 tets), tried over all edges by increasing
// degree and again while removals make progress (each one changes its neighbours' rings); every
// edge still left is removed if a removal has become admissible, else split (n -> 2n). Then faces
// that still exist: a 2-3 flip (+1 tet), else a split (+4). No fix creates a blocking simplex, so
// the mesh ends without any. A removal of degree 3 leaves a tombstone (compact() afterwards).
ChordSplitResult remove_blocking_chords(TetMesh& mesh, const ChordRules& rules, const std::vector<std::array<std::uint32_t, 2>>& edges,
                                        const std::vector<std::array<std::uint32_t, 3>>& faces);

// B0 for the tets whose four vertices are locked and whose fixed image is not strictly positive
// (no vertex move can repair them): each one still in the mesh loses one interior face, by a 2-3
// flip when one is admissible (chord_flip.hpp), else by a split of its largest interior face, so
// every tet that replaces it holds a vertex that can move. Counts go into `r` (faces_flipped,
// faces_split, vertices_added, tets_after); returns the number of tets freed.
std::size_t free_fixed_nonpositive_tets(TetMesh& mesh, const ChordRules& rules, ChordSplitResult& r);

// The same on flat arrays: the result is written back compacted (original ids kept, new vertices
// appended, locked extended with 0).
ChordSplitResult split_chords(TetMeshData& mesh, std::vector<std::uint8_t>& locked,
                              const std::vector<std::array<std::uint32_t, 2>>& edges,
                              const std::vector<std::array<std::uint32_t, 3>>& faces);

}  // namespace volmap
