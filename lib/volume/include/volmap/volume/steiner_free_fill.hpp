// volmap/volume/steiner_free_fill.hpp — a tetrahedralisation of a closed triangle surface that uses
// only its own vertices (no Steiner point) and is valid in two spaces at once: every tet strictly
// positive (exact orient3d, volmap predicates) with the source positions AND with the target
// positions (docs/mapping.md §4.1). On a mesh whose vertices all lie on ∂M the boundary map fixes
// every image, so such a fill is a certified map with |tets| = V − 3 + (interior edges), often fewer
// tets than any repair that adds vertices.
// Why a closed fill is valid: each face of the fill is shared by two tets, the surface's faces by
// one; with every tet positive, the number of tets covering a point off the faces is the winding
// number of the surface about it — 1 inside, 0 outside — in each space (the degree argument), so
// the tets tile the solid without overlap in both.
// Conventions: faces in the VOLMAP outward order (orient3d(a, b, c, inside) > 0, as kTetFace gives
// for a positive tet); output tets VOLMAP-positive (orient3d(t0, t1, t2, t3) > 0) in both spaces.
// The search is an advancing front, most constrained face first (ties by a seeded hash of the
// face), branch and bound on the tet count.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace volmap {

struct SteinerFreeFillLimits {
  std::size_t max_nodes = 200000;   // tets tried (placed and undone) before the search stops
  double time_limit_seconds = 0;    // 0 = none
  bool minimise = true;             // after the first fill, search on for fills with fewer tets
  std::size_t max_tets = 0;         // only fills with fewer tets than this are searched (0 = any)
  std::uint64_t seed = 0;           // breaks ties between equally constrained faces (restarts)
};

struct SteinerFreeFillResult {
  bool found = false;
  bool exhausted = false;           // the whole search space was seen (no limit stopped it)
  bool optimal = false;             // found and exhausted with minimise: no fill has fewer tets
  std::vector<std::uint32_t> tets;  // 4 per tet, VOLMAP-positive in both spaces
  std::size_t nodes = 0;
};

// faces: the closed surface (3 ids each, outward); source_xyz / target_xyz: 3 doubles per vertex
// id, every id used < num_vertices. Vertices are the surface's, `required` (points inside the solid
// in both spaces that the fill must use: no tet may hold one, so a closed fill uses each) and
// `optional` (inside points a fill may use or leave out). Other ids are ignored.
SteinerFreeFillResult fill_without_steiner_points(const std::vector<std::array<std::uint32_t, 3>>& faces,
                                                  const double* source_xyz, const double* target_xyz,
                                                  std::size_t num_vertices, const SteinerFreeFillLimits& limits = {},
                                                  const std::vector<std::uint32_t>& required = {},
                                                  const std::vector<std::uint32_t>& optional = {});

}  // namespace volmap
