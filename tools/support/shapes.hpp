// tools/support/shapes.hpp — procedurally generated closed genus-0 surfaces for the demo, the tests and
// the evaluation sets (no downloaded data). Every shape is closed, manifold and genus 0 by
// construction (see shapes.cpp), with outward, counter-clockwise triangles.
#pragma once

#include <string>
#include <vector>

#include <volmap/io/io_surface.hpp>

namespace volmap {

// The names of the built-in (demo) shapes: ellipsoid, bumpy, peanut, rounded_box, spiky, banana.
const std::vector<std::string>& builtin_shape_names();

// The thin-feature shapes of the evaluation sets (issue 15): tentacles, limbs (a creature with
// legs, neck and tail), fins (a fish), plate (a coin), spiky_star, dumbbell, each also `_thin`
// (thinner), tentacles and limbs also `_coarse` (half the resolution, rings 3x farther apart than
// around), and calibration_cube(_thin), a coarse CAD box with a raised bar, block and a pocket.
const std::vector<std::string>& thin_shape_names();

// The shape `name`: a demo shape on an icosphere subdivided `subdivisions` times (20·4^s
// triangles), or a thin-feature shape whose resolution doubles with each subdivision (3 = default).
// Throws Error(BadInput) for an unknown name or subdivisions outside [0, 7] ([1, 5] for thin shapes).
SurfaceData make_builtin_shape(const std::string& name, int subdivisions = 3);

}  // namespace volmap
