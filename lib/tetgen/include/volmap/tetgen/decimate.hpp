// volmap/tetgen/decimate.hpp — coarsen a closed genus-0 triangle surface to a target face count before
// tetrahedralizing it (surfaces of 100k+ triangles give TetGen meshes of millions of tets).
// Quadric-error edge collapses (OpenMesh Decimater + ModQuadric), each also refused when it turns a
// triangle normal by more than `max_normal_deviation_deg` (ModNormalFlipping) or leaves a triangle
// with a worse aspect ratio than `min_aspect_ratio` that it did not already have (ModAspectRatio).
// Every collapse passes OpenMesh's link condition, which keeps a closed 2-manifold closed, manifold
// and of the same genus; the result is checked again before it is returned. Collapses can still make
// an embedded surface self-intersect (two sheets of a thin part collapsing into each other): with
// keep_embedded, such a result is discarded and the input decimated again towards a 25 % larger
// target, until the result is embedded (exact test), so the face count may stay above the target.
// Deterministic: same input, same output.
#pragma once

#include <volmap/io/io_surface.hpp>

#include <cstddef>

namespace volmap {

struct DecimateOptions {
  std::size_t target_faces = 10000;      // stop at (at most) this many triangles
  double max_normal_deviation_deg = 45;  // a collapse may turn no triangle normal more than this
  double min_aspect_ratio = 12;          // longest edge / height bound of the triangles it creates
  bool keep_embedded = true;             // an embedded input gives an embedded output (see above)
};

struct DecimateResult {
  SurfaceData surface;
  std::size_t faces_before = 0, faces_after = 0;
  bool reached_target = false;  // false when every remaining collapse was refused by a constraint
  std::size_t target_used = 0;  // the target of the run returned (> target_faces after retries;
                                // faces_before when the input is returned)
  int embedding_retries = 0;    // runs discarded because they self-intersected
};

// A surface with at most target_faces triangles is returned unchanged, and so is an embedded surface
// when no larger target below its face count decimates it without self-intersection. Throws Error(BadInput) when
// the input is not a closed, manifold, genus-0 surface (or cannot be built as an OpenMesh mesh),
// Error(Failed) when the decimated surface is not (never expected: collapses keep topology).
DecimateResult decimate_surface(const SurfaceData& surface, const DecimateOptions& options);

}  // namespace volmap
