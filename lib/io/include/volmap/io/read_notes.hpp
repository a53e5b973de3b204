// volmap/io/read_notes.hpp — what a tet-mesh reader left out or renumbered on the way in.
// Readers that keep everything (Medit, VTK, VTU, OpenVolumeMesh) leave the notes empty. The Gmsh
// reader records the lower-dimensional elements it skipped (per element type), the nodes it dropped
// because no tetrahedron uses them, the file's node tag of every vertex when vertex i is not simply
// node tag i+1, and how tet labels were chosen. Tools print `messages` and report the rest under
// "input_notes" in --json.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

struct TetMeshReadNotes {
  struct IgnoredElements {
    std::string type;      // e.g. "triangle", "line", "point", "triangle (6-node)"
    int code = 0;          // the format's element type code (Gmsh: 2 = triangle, ...)
    std::size_t count = 0;
  };
  std::string format;                          // "mesh", "vtk", "vtu", "msh", "ovm"
  std::vector<IgnoredElements> ignored_elements;  // in order of first appearance in the file
  std::size_t dropped_vertices = 0;            // nodes used by no tet, removed
  std::vector<std::uint64_t> source_vertex_ids;  // file id of vertex i when not i+1 (else empty)
  std::vector<std::string> messages;           // one sentence per note (what happened and why)

  bool empty() const { return ignored_elements.empty() && dropped_vertices == 0 && source_vertex_ids.empty() && messages.empty(); }
};

}  // namespace volmap
