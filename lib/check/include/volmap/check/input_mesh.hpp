// volmap/check/input_mesh.hpp — is a tet mesh a valid input for a mapper or a map checker?
// A map certificate is only meaningful for a valid input mesh, so every mapper and checker asks this
// first. Valid means: the seven checks of tetmesh_checks.hpp pass (the verdict of
// volmap-tetmesh-check, so no tool certifies anything for a mesh that check rejects: every tet
// VOLMAP-positive, one component, a closed 2-manifold genus-0 boundary without self-intersections or
// coincident boundary vertices), and two things a VOLMAP-positive mesh cannot have: an interior face
// wound the same way by both its tets (the tets overlap), and two tets over the same four vertices.
// Cost: linear topology (analyze_topology, which also finds duplicate tets through their shared
// faces), exact orient3d over every tet and the boundary's exact self-intersection test.
// The reason is said in words, most basic problem first ("3 faces are shared by more than two tets
// (first: face 2 of tet 17)"), with the number of further problems.
#pragma once

#include <volmap/check/tetmesh_checks.hpp>
#include <volmap/core/mesh_data.hpp>

#include <string>
#include <vector>

namespace volmap {

struct InputMeshVerdict {
  bool valid = false;
  // Everything but the orientation is fine: no zero-volume tet, only some (or all) tets negative
  // (and interior faces wound alike by tets whose vertex order disagrees). A relative map check
  // (VOLMAP's, sign against sign) is meaningful then; a certificate never is.
  bool valid_up_to_orientation = false;
  std::vector<std::string> problems;  // most basic first; empty when valid
  TetMeshCheckReport report;          // the seven checks
  std::string reason() const;         // problems[0] (+ "; and N more problems"), "" when valid
};

// Throws Error(BadInput) (no file) for malformed arrays: sizes, ids out of range, non-finite values.
InputMeshVerdict judge_input_mesh(const TetMeshData& mesh);

// Throws Error(BadInput, path) "not a valid input tet mesh: <reason>" unless the mesh is valid
// (malformed arrays are reported naming `path` too).
void require_valid_input_mesh(const TetMeshData& mesh, const std::string& path);

}  // namespace volmap
