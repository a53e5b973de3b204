// volmap/volume/radial_start.hpp — the radial start (docs/mapping.md §2 "Radial start"): a starting
// map for a boundary image that is star-shaped about a point c (the star domain, and every convex
// domain). The boundary image is projected from c onto the unit sphere, Tutte 3D places the free
// vertices inside that nearly convex polyhedron Q, and each placed point is mapped back by the linear
// map of its cone: the cone over a boundary triangle (0, ŝa, ŝb, ŝc) of Q goes to the cone
// (c, pa, pb, pc) of the image. These cone maps join into a piecewise-linear homeomorphism from Q to
// the image (each boundary vertex is scaled along its own ray by a positive factor, so a cone that is
// positive in the image is positive in Q), so a tet that Tutte leaves positive inside one cone stays
// positive. Orientation: boundary triangles in outward order (kTetFace); c is on the inner side of
// each one (exact). Doubles only: the result is a starting point, judged exactly by the caller.
#pragma once

#include <volmap/core/tet_mesh.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace volmap {

struct RadialStartResult {
  bool placed = false;                // false: x untouched (see place_by_radial_tutte)
  std::array<double, 3> centre{};     // the exactly verified strict kernel point c
  std::size_t located_by_search = 0;  // free vertices whose cone the walk did not reach (full search)
};

// Places every free vertex of the compact `mesh` (x: 3 doubles per vertex, locked[v] != 0: kept) by
// the radial start. Nothing is placed (placed = false) when the locked vertices are not exactly the
// boundary vertices, or when no strict kernel point of the boundary image was verified.
RadialStartResult place_by_radial_tutte(const TetMesh& mesh, const std::vector<std::uint8_t>& locked, std::vector<double>& x);

// No boundary edge of the image x is clearly reflex: for each boundary edge, the far vertex of one
// adjacent triangle is not outside the other's plane by more than 1e-2 of the edges' length (a bend
// of about half a degree; doubles: a choice of start, never a validity sign). Domain faces bent by
// rounding or by maps written with few decimals count as flat. A closed embedded image with no
// reflex edge is convex, and Tutte 3D then keeps every free vertex inside it.
bool boundary_image_is_convex(const TetMesh& mesh, const std::vector<double>& x);

}  // namespace volmap
