// volmap/core/shelling.hpp — one shelling step on a TetMesh: whether adding a tet t outside a region
// R of tets keeps R a 3-ball when R is one. That holds when t meets R in a disk made of 1, 2 or 3 of
// its faces, because gluing a ball to a ball along a boundary disk gives a ball:
//   - one face shared with R (its neighbour across it is in R): the vertex of t opposite that face
//     is in no tet of R;
//   - two faces shared: the edge joining the two vertices opposite them (the edge of t off their
//     common edge) is in no tet of R;
//   - three faces shared: always (they form a disk).
// No shared face or four means false (the test is sufficient, not necessary).
// `in_region(TetId)` says whether a tet is in R; `scratch` receives vertex stars (its capacity is
// reused). Cost: one vertex star. Used by B1's region growth (docs/mapping.md §7 "Shelling steps").
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <vector>

namespace volmap {

template <class InRegion>
bool attaches_along_disk(const TetMesh& mesh, TetId t, InRegion&& in_region, std::vector<TetId>& scratch) {
  VertexId off[4];  // vertices opposite the shared faces
  int shared = 0;
  for (int i = 0; i < 4; ++i) {
    const HalfFaceId o = mesh.half_face_opposite(HalfFaceId(t, i));
    if (o.is_valid() && in_region(o.tet())) off[shared++] = mesh.tet_vertex(t, i);
  }
  if (shared == 3) return true;
  if (shared != 1 && shared != 2) return false;
  mesh.vertex_star(off[0], scratch);
  for (TetId u : scratch) {
    if (!in_region(u)) continue;
    if (shared == 1 || mesh.tet_local_index(u, off[1]) >= 0) return false;
  }
  return true;
}

}  // namespace volmap
