// local_region.cpp — k-ring sub-problems of local untangling stages (conventions in local_region.hpp).
#include "local_region.hpp"

#include <volmap/core/error.hpp>

namespace volmap {

void LocalRegion::write_back(std::vector<double>& target_xyz) const {
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (!locked[i])
      for (int c = 0; c < 3; ++c) target_xyz[3 * std::size_t(vertices[i]) + c] = target[3 * i + c];
}

namespace {

// Marks the vertices of the seed tets and of `rings` vertex rings around them.
std::vector<std::uint8_t> ring_vertices(const TetMesh& mesh, const std::vector<std::uint32_t>& seed_tets, int rings) {
  std::vector<std::uint8_t> in_rings(mesh.num_vertices(), 0);
  std::vector<std::uint32_t> frontier, next;
  for (std::uint32_t t : seed_tets)
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t v = mesh.tet_vertex(TetId(t), k).idx();
      if (!in_rings[v]) {
        in_rings[v] = 1;
        frontier.push_back(v);
      }
    }
  for (int r = 0; r < rings; ++r) {
    next.clear();
    for (std::uint32_t v : frontier)
      for (TetId t : mesh.vertex_tets(VertexId(v)))
        for (int j = 0; j < 4; ++j) {
          const std::uint32_t u = mesh.tet_vertex(t, j).idx();
          if (!in_rings[u]) {
            in_rings[u] = 1;
            next.push_back(u);
          }
        }
    frontier.swap(next);
  }
  return in_rings;
}

}  // namespace

LocalRegion extract_local_region(const TetMesh& mesh, const std::vector<std::uint8_t>& locked,
                                 const std::vector<double>& target_xyz, const std::vector<std::uint32_t>& seed_tets, int rings) {
  const std::size_t nv = mesh.num_vertex_slots(), nt = mesh.num_tet_slots();
  if (mesh.num_free_tet_slots() != 0 || mesh.num_vertices() != nv)
    throw Error(ErrorKind::BadInput, "", 0, "local region: the mesh has tombstones (compact it first)");
  if (target_xyz.size() != 3 * nv || locked.size() != nv)
    throw Error(ErrorKind::BadInput, "", 0, "local region: inconsistent array sizes");
  const std::vector<std::uint8_t> in_rings = ring_vertices(mesh, seed_tets, rings);
  std::vector<std::uint8_t> tet_in(nt, 0);
  for (std::size_t v = 0; v < nv; ++v)
    if (in_rings[v] && !locked[v])
      for (TetId t : mesh.vertex_tets(VertexId(std::uint32_t(v)))) tet_in[t.idx()] = 1;
  LocalRegion region;
  std::vector<std::uint32_t> local_id(nv, kInvalidIndex);
  for (std::size_t t = 0; t < nt; ++t)
    if (tet_in[t])
      for (int k = 0; k < 4; ++k) local_id[mesh.tet_vertex(TetId(std::uint32_t(t)), k).idx()] = 0;
  for (std::size_t v = 0; v < nv; ++v)
    if (local_id[v] != kInvalidIndex) {
      local_id[v] = std::uint32_t(region.vertices.size());
      region.vertices.push_back(std::uint32_t(v));
    }
  for (std::size_t t = 0; t < nt; ++t)
    if (tet_in[t])
      for (int k = 0; k < 4; ++k) region.tets.push_back(local_id[mesh.tet_vertex(TetId(std::uint32_t(t)), k).idx()]);
  const std::vector<double>& positions = mesh.positions();
  region.locked.resize(region.vertices.size());
  region.source.resize(3 * region.vertices.size());
  region.target.resize(3 * region.vertices.size());
  for (std::size_t i = 0; i < region.vertices.size(); ++i) {
    const std::uint32_t v = region.vertices[i];
    region.locked[i] = !(in_rings[v] && !locked[v]);
    for (int c = 0; c < 3; ++c) {
      region.source[3 * i + c] = positions[3 * std::size_t(v) + c];
      region.target[3 * i + c] = target_xyz[3 * std::size_t(v) + c];
    }
  }
  return region;
}

}  // namespace volmap
