// remesh.cpp — interior remesh with TetGen (conventions in remesh.hpp). First the PLC: every input
// vertex plus the boundary half-faces in their outward winding (kTetFace), `pq<quality>Y`. When
// TetGen refuses or aborts on that PLC, the input mesh itself is refined: `rq<quality>Y` starts
// from the input's tets (handed to TetGen in its orientation) and its boundary triangles as
// subfaces, so no boundary has to be recovered.
#include <volmap/tetgen/remesh.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/error.hpp>
#include <volmap/core/time_budget.hpp>
#include <volmap/tetgen/tetrahedralize.hpp>

#include "tetgen_child.hpp"

#include <tetgen.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace volmap {
namespace {

TetMeshData remesh_from_boundary(const TetMeshData& mesh, double quality, double time_limit_seconds) {
  TriangleSurface surface;
  surface.xyz = mesh.xyz;
  for (const std::uint64_t hf : boundary_half_faces(mesh))
    for (const std::uint32_t v : half_face_vertices(mesh, hf)) surface.tris.push_back(v);
  TetrahedralizeOptions tetgen;
  tetgen.quality = quality;
  tetgen.time_limit_seconds = time_limit_seconds;
  return tetrahedralize_surface(surface, tetgen);
}

TetMeshData refine_input_tets(const TetMeshData& mesh, double quality, double time_limit_seconds) {
  tetgenio in;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(mesh.num_vertices());
  in.pointlist = new REAL[mesh.xyz.size()];
  std::copy(mesh.xyz.begin(), mesh.xyz.end(), in.pointlist);
  in.numberofcorners = 4;
  in.numberoftetrahedra = static_cast<int>(mesh.num_tets());
  in.tetrahedronlist = new int[mesh.tets.size()];
  for (std::size_t t = 0; t < mesh.num_tets(); ++t) {  // VOLMAP-positive -> TetGen's orientation
    const std::uint32_t* q = &mesh.tets[4 * t];
    const std::uint32_t swapped[4] = {q[1], q[0], q[2], q[3]};
    for (int k = 0; k < 4; ++k) in.tetrahedronlist[4 * t + std::size_t(k)] = static_cast<int>(swapped[k]);
  }
  // The boundary triangles as subfaces, each its own facet (a marker per triangle): without them
  // `Y` does not hold the boundary, and with one marker TetGen flips coplanar neighbours.
  const std::vector<std::uint64_t> boundary = boundary_half_faces(mesh);
  in.numberoftrifaces = static_cast<int>(boundary.size());
  in.trifacelist = new int[3 * boundary.size()];
  in.trifacemarkerlist = new int[boundary.size()];
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    const auto v = half_face_vertices(mesh, boundary[f]);
    for (int k = 0; k < 3; ++k) in.trifacelist[3 * f + std::size_t(k)] = static_cast<int>(v[std::size_t(k)]);
    in.trifacemarkerlist[f] = static_cast<int>(f) + 1;
  }
  std::ostringstream switches;
  switches.precision(17);
  switches << "rq" << quality << "YQz";
  return run_tetgen_in_child(switches.str(), in, time_limit_seconds);
}

}  // namespace

TetMeshData remesh_interior(const TetMeshData& mesh, const InteriorRemeshOptions& options) {
  // New tets cannot take labels from parents: a labelled input keeps its one label, or is refused.
  const bool labelled = !mesh.tet_labels.empty();
  if (labelled && std::adjacent_find(mesh.tet_labels.begin(), mesh.tet_labels.end(), std::not_equal_to<>()) != mesh.tet_labels.end())
    throw Error(ErrorKind::Failed, "the interior remesh would lose the input's tet labels (more than one label)");
  // Both attempts share the time limit; the second gets what the first left (none: stop).
  const TimeBudget budget(options.time_limit_seconds);
  TetMeshData remeshed;
  try {
    remeshed = remesh_from_boundary(mesh, options.quality, budget.option_seconds());
  } catch (const Error& from_boundary) {
    if (from_boundary.kind() != ErrorKind::Failed || budget.expired()) throw;
    try {
      remeshed = refine_input_tets(mesh, options.quality, budget.option_seconds());
    } catch (const Error& refining) {
      throw Error(ErrorKind::Failed, std::string(from_boundary.reason()) + "; refining the input tets: " + refining.reason());
    }
  }
  const std::size_t nv = mesh.num_vertices();
  if (remeshed.num_vertices() < nv || std::memcmp(remeshed.xyz.data(), mesh.xyz.data(), 3 * nv * sizeof(double)) != 0)
    throw Error(ErrorKind::Failed, "TetGen did not keep every input vertex in place");
  if (labelled) remeshed.tet_labels.assign(remeshed.num_tets(), mesh.tet_labels.front());
  return remeshed;
}

}  // namespace volmap
