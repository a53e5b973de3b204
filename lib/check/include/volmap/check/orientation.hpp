// volmap/check/orientation.hpp — what the exact orient3d signs of a mesh's tets say about its
// orientation convention: a class, and one sentence for people. Every tool that reports orientation
// words it with describe_orientation, so the wording lives here only.
// VOLMAP convention: orient3d(v0,v1,v2,v3) > 0 for every tet. Gmsh and OpenVolumeMesh order tets the
// other way round: read as they are, their meshes are "coherently opposite" (every tet negative) and
// a global flip (flip_all_tets, `volmap-tetmesh-check --fix`) brings them to the VOLMAP convention.
#pragma once

#include <volmap/predicates.hpp>

#include <string>

namespace volmap {

enum class OrientationClass {
  AllPositive,         // VOLMAP convention (zero-volume tets are the volume check's business)
  CoherentlyOpposite,  // no positive tet, at least one negative: flip every tet to fix
  Mixed,               // both signs present: not fixable by a global flip
  Empty                // no tets at all (or only zero-volume ones)
};
const char* to_string(OrientationClass c);  // "positive", "coherently_opposite", "mixed", "empty" (JSON keys)

OrientationClass classify_orientation(const TetSignCounts& signs);

// One sentence (no final period), e.g. "all 6,059 tets are in the opposite orientation convention
// (orient3d < 0, as Gmsh and OpenVolumeMesh order them); volmap-tetmesh-check --fix flips them".
// `fix` names the command that flips a coherently opposite mesh ("--fix" inside that tool).
std::string describe_orientation(const TetSignCounts& signs, const std::string& fix = "volmap-tetmesh-check --fix");

}  // namespace volmap
