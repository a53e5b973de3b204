// flat_array_edit.hpp — running a TetMesh edit (cone repair, the whole-mesh cone, vertex removal) on
// the flat arrays of a map: a source TetMeshData, 3 target doubles and one locked flag per vertex.
// Conventions: the arrays are checked (sizes, tet vertex ids) and the mesh, a PositionProperty of
// the targets and a VertexProperty of the locked flags are built from them; the edit runs on those;
// when `changed(result)` the mesh is compacted (survivors keep their order, so ids below the first
// deleted vertex stay) and written back with the properties, label arrays kept empty when they
// were; otherwise the arrays stay as given. Internal header (lib/src).
#pragma once

#include <volmap/core/error.hpp>
#include <volmap/core/mesh_data.hpp>
#include <volmap/core/properties.hpp>
#include <volmap/core/tet_mesh.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace volmap {

template <class Edit, class Changed>
auto edit_on_flat_arrays(TetMeshData& source, std::vector<std::uint8_t>& locked, std::vector<double>& target_xyz,
                         const char* who, Edit&& edit, Changed&& changed) {
  const std::size_t nv = source.num_vertices();
  if (source.tets.size() != 4 * source.num_tets() || locked.size() != nv || target_xyz.size() != source.xyz.size())
    throw Error(ErrorKind::BadInput, "", 0, std::string(who) + ": inconsistent array sizes");
  for (std::uint32_t v : source.tets)
    if (v >= nv) throw Error(ErrorKind::BadInput, "", 0, std::string(who) + ": tet vertex id out of range");
  TetMesh mesh(source);
  PositionProperty target(mesh);
  VertexProperty<std::uint8_t> locked_property(mesh);
  for (std::size_t v = 0; v < nv; ++v) {
    for (int i = 0; i < 3; ++i) target.data()[v][i] = target_xyz[3 * v + i];
    locked_property.data()[v] = locked[v];
  }
  const auto res = edit(mesh, target, locked_property);
  if (!changed(res)) return res;  // the arrays stay as given
  mesh.compact();
  const bool had_tet_labels = !source.tet_labels.empty(), had_vertex_labels = !source.vertex_labels.empty();
  source = mesh.to_data();
  if (!had_tet_labels) source.tet_labels.clear();
  if (!had_vertex_labels) source.vertex_labels.clear();
  target_xyz.resize(3 * source.num_vertices());
  locked.resize(source.num_vertices());
  for (std::size_t v = 0; v < source.num_vertices(); ++v) {
    for (int i = 0; i < 3; ++i) target_xyz[3 * v + i] = target.data()[v][i];
    locked[v] = locked_property.data()[v];
  }
  return res;
}

}  // namespace volmap
