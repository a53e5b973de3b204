// volmap/core/local_tables.hpp — the constexpr local tables of a tetrahedron (volmap-reference.md §1,
// datastructure.md §2). For a VOLMAP-positive tet (v0,v1,v2,v3), i.e. orient3d(v0,v1,v2,v3) > 0:
//   kTetFace[i]  : the face opposite local vertex i, listed counter-clockwise seen from outside:
//                  F0=(1,3,2) F1=(0,2,3) F2=(0,3,1) F3=(0,1,2)   (orient3d(F_i, v_i) > 0).
//   kTetEdge[k]  : (0,1) (0,2) (0,3) (1,2) (1,3) (2,3); kTetEdge[k] and kTetEdge[5-k] are opposite.
//   kTetCross[a][b] = d where (a,b,c,d) is an even permutation of (0,1,2,3): the local face (opposite
//                  d) to cross when turning around the edge a->b. Crossing kTetCross[b][a] = c turns
//                  the other way. The rotation sense is the same in every consistently oriented tet.
#pragma once

#include <cstdint>

namespace volmap {

inline constexpr std::uint8_t kTetFace[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
inline constexpr std::uint8_t kTetEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
inline constexpr std::uint8_t kNoLocal = 0xFF;
inline constexpr std::uint8_t kTetCross[4][4] = {
    {kNoLocal, 3, 1, 2}, {2, kNoLocal, 3, 0}, {3, 0, kNoLocal, 1}, {1, 2, 0, kNoLocal}};
// Local edge index k of the (unordered) local vertex pair (a,b), a != b.
inline constexpr std::uint8_t kTetEdgeOf[4][4] = {
    {kNoLocal, 0, 1, 2}, {0, kNoLocal, 3, 4}, {1, 3, kNoLocal, 5}, {2, 4, 5, kNoLocal}};

}  // namespace volmap
