// volmap/tetgen/remesh.hpp — a new tetrahedralisation of a tet mesh's interior with TetGen (switches
// p q<quality> Y, else r q<quality> Y): the boundary triangles are the PLC (kept as they are: no Steiner point on them),
// every vertex of the input is a point of the PLC (interior ones as isolated points, which TetGen
// inserts), and TetGen's quality refinement adds interior points. When TetGen refuses or aborts on
// that PLC (its boundary recovery with isolated points fails on some thin shapes), the input's tets
// are refined instead (switches r q<quality> Y: Delaunay refinement from the input mesh, no
// boundary recovery). Vertex ids 0..nv−1 and their positions are the input's; new vertices are
// appended; tets are VOLMAP-positive. This is the
// remesher volmap-map hands to the mapper (volmap/volume/interior_remesh.hpp), which checks it.
#pragma once

#include <volmap/core/mesh_data.hpp>

namespace volmap {

struct InteriorRemeshOptions {
  // TetGen's radius-edge bound. A loose bound adds few points: on coarse TetGen meshes without
  // quality refinement (most tets with four boundary vertices) 3.0 changed the tet count by −8 % to
  // +12 % and gave every untangler interior vertices to move (docs/mapping.md §8 step 11).
  double quality = 3.0;
  // > 0: both TetGen attempts together stop after this long, and remesh_interior throws
  // Error(Failed). TetGen cannot be interrupted: it runs in a child that is killed then.
  double time_limit_seconds = 0;
};

// Tet labels: a labelled input with one label gives every new tet that label. Throws
// Error(BadInput) when the input's boundary is not a closed genus-0 surface, Error(Failed) when
// TetGen refuses both ways, runs out of its time limit, or does not keep every input vertex in
// place, or the input has several labels (the new tets could not carry them).
TetMeshData remesh_interior(const TetMeshData& mesh, const InteriorRemeshOptions& options = {});

}  // namespace volmap
