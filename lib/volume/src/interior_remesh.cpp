// interior_remesh.cpp — exact check of a remesher's result (contract in interior_remesh.hpp):
// vertices 0..nv−1 compared bit for bit, boundary triangles compared as sorted vertex triples (from
// analyze_topology of both meshes, which also refuses non-manifold results), signs by orient3d_tets.
#include <volmap/volume/interior_remesh.hpp>

#include <volmap/core/boundary_faces.hpp>
#include <volmap/core/topology.hpp>
#include <volmap/predicates.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace volmap {

namespace {

std::vector<std::array<std::uint32_t, 3>> sorted_boundary_triangles(const TetMeshData& mesh, const TopologyReport& topo) {
  std::vector<std::array<std::uint32_t, 3>> tris;
  tris.reserve(topo.boundary_half_faces.size());
  for (const std::uint32_t hf : topo.boundary_half_faces) {
    std::array<std::uint32_t, 3> f = half_face_vertices(mesh, hf);
    std::sort(f.begin(), f.end());
    tris.push_back(f);
  }
  std::sort(tris.begin(), tris.end());
  return tris;
}

}  // namespace

std::string interior_remesh_problem(const TetMeshData& input, const TetMeshData& remeshed) {
  const std::size_t nv = input.num_vertices();
  if (remeshed.xyz.size() % 3 != 0 || remeshed.tets.size() % 4 != 0 || remeshed.num_tets() == 0)
    return "the remeshed arrays are malformed or empty";
  if (remeshed.num_vertices() < nv) return "the remesh lost vertices";
  if (!remeshed.tet_labels.empty() && remeshed.tet_labels.size() != remeshed.num_tets())
    return "the remeshed tet labels do not match its tets";
  if (std::memcmp(remeshed.xyz.data(), input.xyz.data(), 3 * nv * sizeof(double)) != 0)
    return "the remesh moved or renumbered an input vertex";
  for (std::uint32_t v : remeshed.tets)
    if (v >= remeshed.num_vertices()) return "a remeshed tet refers to a vertex out of range";
  const TetSignCounts signs =
      orient3d_tets(remeshed.xyz.data(), remeshed.num_vertices(), remeshed.tets.data(), remeshed.num_tets(), nullptr);
  if (!signs.ok || signs.negative + signs.zero > 0) return "a remeshed tet is not strictly positive";
  const TopologyReport before = analyze_topology(input), after = analyze_topology(remeshed);
  if (after.num_unused_vertices > 0 || after.num_nonmanifold_faces > 0 || after.num_tet_components != 1)
    return "the remeshed tets do not form one manifold solid using every vertex";
  if (sorted_boundary_triangles(input, before) != sorted_boundary_triangles(remeshed, after))
    return "the remesh changed the boundary triangles";
  return "";
}

}  // namespace volmap
