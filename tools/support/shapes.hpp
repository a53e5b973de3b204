// tools/support/shapes.hpp — procedurally generated closed genus-0 surfaces for the demo and tests (no
// downloaded data). Every shape is an embedding of a subdivided icosahedron (hence genus 0,
// closed, manifold) with outward, counter-clockwise triangles.
#pragma once

#include <string>
#include <vector>

#include <volmap/io/io_surface.hpp>

namespace volmap {

// The names of the built-in shapes: ellipsoid, bumpy, peanut, rounded_box, spiky, banana.
const std::vector<std::string>& builtin_shape_names();

// The shape `name` on an icosphere subdivided `subdivisions` times (20·4^s triangles).
// Throws Error(BadInput) for an unknown name or subdivisions outside [0, 7].
SurfaceData make_builtin_shape(const std::string& name, int subdivisions = 3);

}  // namespace volmap
