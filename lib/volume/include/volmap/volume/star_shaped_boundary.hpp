// volmap/volume/star_shaped_boundary.hpp — whether a tet mesh's boundary ∂M is star-shaped both in
// the source and in a boundary map's image (docs/mapping.md §8 step 12): a strict kernel point in
// each space, found by the kernel LP and verified with exact orient3d (kernel_lp.hpp). Then the
// cones from the two kernel points over the boundary faces are a valid map whatever the interior
// (cone_repair.hpp, whole_mesh_cone), so a map with refinement exists.
// Orientation: boundary faces in the outward order of their tet (kTetFace); a kernel point lies
// strictly on the inner side of every one of them.
#pragma once

#include <volmap/core/mesh_data.hpp>

namespace volmap {

// False (never throws) when the mesh or the map is inconsistent (a tet vertex id out of range, a map
// id out of range, a boundary vertex the map does not prescribe), when there is no boundary, or
// when either kernel has no verified strict point.
bool boundary_star_shaped_in_both_spaces(const TetMeshData& source, const BoundaryMap& map);

// The same test, keeping the two verified points: source_point (3 doubles) strictly inside ∂M's
// kernel in the source, image_point in the kernel of its image. False (points unspecified) in the
// cases above.
bool boundary_kernel_points(const TetMeshData& source, const BoundaryMap& map, double* source_point, double* image_point);

}  // namespace volmap
