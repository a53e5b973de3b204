// tetgen_child.hpp — runs TetGen (libtet, TETLIBRARY interface: errors are thrown as ints) in a
// forked child with stdout and stderr on /dev/null, and returns its tets in the VOLMAP orientation
// (orient3d(v0,v1,v2,v3) > 0; TetGen's own tets have the opposite sign and are flipped after an
// exact check of each one). Internal to volmap::tetgen.
#pragma once

#include <volmap/core/mesh_data.hpp>

#include <string>

class tetgenio;

namespace volmap {

// Throws Error(Failed) with TetGen's reason when it refuses the input, when the child crashes,
// or when a produced tet is degenerate. With time_limit_seconds > 0 the child is killed when it
// has not finished by then, and Error(Failed) says so (TetGen itself cannot be interrupted).
TetMeshData run_tetgen_in_child(const std::string& switches, tetgenio& in, double time_limit_seconds = 0);

}  // namespace volmap
